// Running a case on one system type: the sweep, the claims, --refine. This is
// where every claim is instantiated for a system, so it is compiled once per
// system and scalar, in translation units harness/CMakeLists.txt generates
// (explicit instantiations of run_on_system, the systems of one scalar and
// dimension together); run_case.cpp only dispatches.
#pragma once

#include <cmath>

#include "harness/claims.hpp"
#include "harness/run_system.hpp"

namespace vivv {

// A case whose motion over T is not above the round-off floor measures nothing: every error
// would be "at the floor" and every lower bound on an order would hold vacuously (T = 1e-400
// once passed lagrangian-order that way). Bad input naming T, the motion and the floor.
template <LagrangianSystem System>
void check_motion_above_floor(const CaseContext<System>& context) {
  using T = typename System::Scalar;
  const T motion = state_distance(context.final_state, context.initial);
  if (motion > context.floor()) return;
  throw CaseError(context.spec.file, "T",
                  "the motion over T (|F_T(x0) - x0| = " + format_scalar(motion) +
                      ") is not above the round-off floor " + format_scalar(context.floor()) +
                      ": the method's errors could not be told from rounding; take a larger T or "
                      "an initial state that moves");
}

template <LagrangianSystem System>
void run_on_system(const System& system, CaseSpec& spec, CaseResult& result, bool refine,
                   const std::function<void(const std::string&)>& progress) {
  using T = typename System::Scalar;
  for (int round = 0;; ++round) {
    CaseContext context(spec, system, [&](const std::string& message) {
      if (progress) progress(spec.name + ": " + message);
    });
    if (refine) context.fit_options.asymptote_tolerance = context.order_tolerance / 4;
    if (round == 0) {
      check_declared_orders(context);
      check_motion_above_floor(context);
      result.reference_method = context.reference.method();
      result.reference_tolerance = to_decimal<T>(context.reference.tolerance());
      result.reference_cross_check = context.reference.cross_check();
      result.reference_check = check_reference(context.reference, context.initial, context.final_time);
      result.reference_error_estimate = result.reference_check.error_estimate;
    }
    result.claims.clear();
    for (const auto& id : spec.claims) {
      if (progress) progress(spec.name + ": claim " + id);
      result.claims.push_back(evaluate_claim(id, context));
    }
    if (!refine) break;
    // --refine: halve h (double N) until every order-fitted series settles, within the budget.
    auto unsettled = unsettled_series(result.claims, context.order_tolerance);
    if (!unsettled) {
      result.sweep.stopped = "every fitted series settled (its two finest pairwise orders and its fitted "
                             "order within a quarter of the order tolerance, and an exact prediction inside "
                             "the fit's interval unless the finest orders are further than the tolerance from "
                             "it) or reached the floor";
      break;
    }
    const long next = 2L * spec.steps.back();
    if (round == SweepRecord::max_refinements || next > SweepRecord::max_steps) {
      result.sweep.stopped = "budget reached (" + std::to_string(SweepRecord::max_refinements) +
                             " halvings of h, N <= " + std::to_string(SweepRecord::max_steps) +
                             ") before settling: " + *unsettled;
      break;
    }
    if (progress) progress(spec.name + ": refine to N = " + std::to_string(next) + " (" + *unsettled + ")");
    spec.steps.push_back(static_cast<int>(next));
  }
  apply_reference_check(result.claims, result.reference_check);
  for (auto& claim : result.claims)
    if (auto it = spec.xfail.find(claim.id); it != spec.xfail.end()) apply_expected_failure(claim, it->second);
  T smallest = 0;
  for (const auto& claim : result.claims)
    for (const auto& series : claim.series)
      if (series.predicted_order)
        for (const auto& e : series.error) {
          T value = from_decimal<T>(e);
          if (value > 0 && (smallest == 0 || value < smallest)) smallest = value;
        }
  if (smallest > 0) {
    using std::log2;
    result.smallest_error = to_decimal<T>(smallest);
    result.guard_bits = static_cast<double>(result.precision_bits + log2(smallest));
  }
}

}  // namespace vivv
