#include "harness/run_case.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cases/catalogue.hpp"
#include "harness/claims.hpp"

namespace vivv {

std::optional<std::string> unsettled_series(const std::vector<ClaimResult>& claims, double tolerance) {
  for (const auto& claim : claims)
    for (const auto& series : claim.series) {
      if (!series.predicted_order || !series.fit) continue;
      const OrderFit& fit = *series.fit;
      // The smallest h left out of the fit is at the floor (the fit drops only leading points as
      // pre-asymptotic): halving h further cannot show more.
      const bool floor_reached = fit.sorted.empty() || fit.used.empty() ||
                                 std::find(fit.used.begin(), fit.used.end(), fit.sorted.back()) == fit.used.end();
      if (floor_reached || !fit.ok) continue;
      const auto& finest = fit.finest_orders;
      const bool steady = finest.size() == 2 && std::isfinite(finest[0]) && std::isfinite(finest[1]) &&
                          std::fabs(finest[1] - finest[0]) <= tolerance / 4 &&
                          std::fabs(fit.order - finest[1]) <= tolerance / 4;
      // An exact prediction outside the fit's interval that the finest orders are still near:
      // more data at small h decides it.
      const double predicted = *series.predicted_order;
      const bool undecided = series.exact_order && std::isfinite(fit.confidence_low) &&
                             (predicted < fit.confidence_low || predicted > fit.confidence_high) &&
                             finest.size() == 2 && std::fabs(finest[1] - predicted) <= tolerance;
      if (!steady || undecided)
        return claim.id + " / " + series.label + ": fitted order " + format_scalar(fit.order, 4) + " [" +
               format_scalar(fit.confidence_low, 4) + ", " + format_scalar(fit.confidence_high, 4) +
               "], finest pairwise orders " +
               (finest.size() == 2 ? format_scalar(finest[0], 4) + ", " + format_scalar(finest[1], 4)
                                   : std::string("(fewer than two)")) +
               (steady ? ": the interval excludes the predicted " + format_scalar(predicted, 3)
                       : ": not within " + format_scalar(tolerance / 4, 3) + " of each other");
    }
  return std::nullopt;
}

CaseResult run_case(const CaseSpec& case_spec, std::optional<int> digits, bool refine,
                    const std::function<void(const std::string&)>& progress) {
  auto started = std::chrono::steady_clock::now();
  CaseSpec spec = case_spec;
  if (digits) spec.digits = *digits;
  refine = refine || spec.refine;
  PrecisionGuard guard(spec.digits);
  using T = mpfr_real;
  std::vector<std::string> parameters;
  for (const auto& [name, value] : spec.parameters) parameters.push_back(value);
  CaseResult result;
  result.scalar = scalar_name<T>();
  result.digits = spec.digits;
  result.precision_bits = precision_bits<T>();
  result.sweep.refine = refine;
  result.sweep.requested_steps = spec.steps;
  visit_system<T>(spec.system, parameters, [&](auto system) {
    for (int round = 0;; ++round) {
      CaseContext context(spec, system, [&](const std::string& message) {
        if (progress) progress(spec.name + ": " + message);
      });
      if (refine) context.fit_options.asymptote_tolerance = context.order_tolerance / 4;
      if (round == 0) {
        check_declared_orders(context);
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
  });
  result.spec = spec;  // with the sweep actually used
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace vivv
