// Running a case on one system type: the sweep, the claims, --refine. This is
// where every claim is instantiated for a system, so it is compiled once per
// system and scalar, in translation units harness/CMakeLists.txt generates
// (explicit instantiations of run_on_system, the systems of one scalar and
// dimension together); run_case.cpp only dispatches.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>

#include "harness/claims/registry.hpp"
#include "harness/run/derivative_check.hpp"
#include "harness/run/run_system.hpp"
#include "harness/verdicts/deferred_findings.hpp"

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

// Whether the case's first step from the initial state, of size h, converges (a map's
// explicit step always does): what a solver failure is explained by.
template <LagrangianSystem System>
bool first_step_converges(const CaseContext<System>& context, const typename System::Scalar& h) {
  try {
    if (context.map) return true;
    if (context.tq)
      return tq_step(context.system, context.tq_past ? *context.tq_past : *context.tq, *context.tq,
                     context.initial, h)
          .report.converged;
    const auto [q0, q1] = context.start(context.scheme, h);
    return del_step(context.at_step(h, 1), context.scheme, q0, q1, h).second.converged;  // q_1 at t0 + h
  } catch (const SolverError&) {
    return false;
  } catch (const SingularLagrangianError&) {  // an iterate where L is not regular
    return false;
  } catch (const std::domain_error&) {  // an iterate left the Lagrangian's domain
    return false;
  }
}

// After a Newton solve failed: which step sizes T/N take their first step, over the sweep
// and halving h past its finest (at most `beyond` times), so the message can say the largest
// h that converged. Each probe stops at Newton's first sign of divergence (core/numerics/newton.hpp).
template <LagrangianSystem System>
std::string first_step_probe(const CaseContext<System>& context, int beyond = 10) {
  using T = typename System::Scalar;
  const std::vector<int>& sweep = context.spec.steps;  // increasing: h decreases
  auto listed = [](const std::vector<int>& steps) {
    std::string text;
    for (std::size_t i = 0; i < steps.size(); ++i) text += (i ? ", " : "") + std::to_string(steps[i]);
    return text;
  };
  std::vector<int> failed, converged;
  for (int N : sweep) {
    context.report("probing the first step with N = " + std::to_string(N));
    (first_step_converges(context, context.final_time / N) ? converged : failed).push_back(N);
  }
  const std::string from = "the first step from the initial state ";
  if (failed.empty())
    return from +
           "converges at every h of the sweep: the solve failed further along, at the t and q "
           "named " +
           "above, where the state has moved; to go on, take step counts large enough for the "
           "motion there " +
           "(a smaller h), or a T that ends before it";
  if (!converged.empty()) {
    const int largest = converged.front();
    return from + "fails for N = " + listed(failed) + " and converges for N = " + listed(converged) +
           "; the largest h that converged is " + to_decimal<T>(context.final_time / largest, 6) + " (N = " +
           std::to_string(largest) + ")" +
           (largest > failed.back() ? ": drop the step counts below " + std::to_string(largest) : "");
  }
  long N = sweep.back();
  for (int halving = 1; halving <= beyond && 2 * N <= SweepRecord::max_steps; ++halving) {
    N *= 2;
    context.report("probing the first step with N = " + std::to_string(N));
    if (first_step_converges(context, context.final_time / T(N)))
      return from + "fails at every h of the sweep (N = " + listed(failed) + ") and converges at h = " +
             to_decimal<T>(context.final_time / T(N), 6) + " (N = " + std::to_string(N) +
             "), the largest h = T/N with N = " + std::to_string(sweep.back()) +
             "·2^j that converged: take step counts of at least " + std::to_string(N);
  }
  return from + "fails at every h of the sweep (N = " + listed(failed) + ") and at every h = T/N down to N = " +
         std::to_string(N) + ": no step size tried converged";
}

// The derivative check of the case, or the one an earlier case of the run made of the same
// reference flow from the same initial state, T and finest h (the same numbers: for a one-step map
// or a TQ case it reads L and the flow alone; a Q × Q case's checks its own DEL step as well and is
// made for each case). On the 114-coordinate LJ38 cluster it costs about 6 s in float128.
template <LagrangianSystem System>
DerivativeCheck shared_derivative_check(const CaseContext<System>& context) {
  const CaseSpec& spec = context.spec;
  if (spec.discretization.formalism == "qxq") return derivative_free_check(context);
  nlohmann::json detail = {{"q", spec.q}, {"w", spec.w}, {"T", spec.final_time}, {"finest N", spec.steps.back()}};
  bool kept = false;
  DerivativeCheck check = shared_reference<DerivativeCheck>(
      reference_key(spec), [&] { return derivative_free_check(context); }, kept, "derivative check " + detail.dump());
  if (kept) context.report("L's derivatives: the cross-check an earlier case from this state made, kept for this one");
  return check;
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
      check_expected_failures(context);
      check_motion_above_floor(context);
      result.reference_method = context.reference.method();
      result.reference_tolerance = to_decimal<T>(context.reference.tolerance());
      result.reference_cross_check = context.reference.cross_check();
      context.report("cross-checking the reference flow to T against an independent integration");
      try {
        result.reference_check = check_reference(context.reference, context.initial, context.final_time);
      } catch (const SolverError&) {
        throw;
      } catch (const SingularLagrangianError&) {
        throw;  // names the state already
      } catch (const std::runtime_error& error) {  // a flow that cannot reach T
        throw std::runtime_error(std::string("the reference flow's cross-check: ") + error.what());
      }
      result.reference_error_estimate = result.reference_check.error_estimate;
      context.report("cross-checking L's derivatives against differences of its values");
      result.derivative_check = shared_derivative_check(context);
    }
    // Every claim's floor rests on the reference's accuracy as its cross-check measured it.
    if (const std::string& estimate = result.reference_check.error_estimate;
        !estimate.empty() && std::isfinite(std::strtold(estimate.c_str(), nullptr)))
      context.reference_error_at_T = from_decimal<T>(estimate);
    std::map<std::string, double> seconds_before;  // earlier --refine rounds' time, by claim
    for (const auto& claim : result.claims) seconds_before[claim.id] = claim.seconds;
    result.claims.clear();
    for (const auto& id : spec.claims) {
      if (progress) progress(spec.name + ": claim " + id);
      try {
        const auto started = std::chrono::steady_clock::now();
        result.claims.push_back(evaluate_claim(id, context));
        result.claims.back().seconds =
            seconds_before[id] + std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      } catch (const SolverError& error) {
        SolverError explained(std::string(error.what()) + "; " + first_step_probe(context));
        explained.step_sizes_probed = true;
        throw explained;
      }
    }
    result.run_costs = context.run_costs;
    context.save_reference_answers();
    if (!refine) break;
    // --refine: halve h (double N) until every order-fitted series settles, within the budget.
    auto unsettled = unsettled_series(result.claims, context.order_tolerance);
    if (!unsettled) {
      result.sweep.stopped =
          "every fitted series settled (its two finest pairwise orders and its fitted "
          "order within a quarter of the order tolerance of each other, and an exact "
          "prediction within a quarter of the tolerance of the finest order or inside the "
          "fit's interval — or further than the tolerance from it) or reached the floor";
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
  settle_deferred_findings(result.claims);
  apply_reference_check(result.claims, result.reference_check);
  apply_derivative_check(result.claims, result.derivative_check);
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
