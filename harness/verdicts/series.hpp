// Turning a measured error sweep into a Series: decimal strings, the fitted
// order (docs/theory.md (observed orders)) and, when the claim predicts one, its verdict.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/verdicts/claim_result.hpp"
#include "harness/verdicts/order_fit.hpp"

namespace vivv {

// A series of errors against h, fitted, and judged against `predicted`
// (a lower bound unless `exact`) with `tolerance` on the order.
//
// Fewer than two errors above the floor cannot be fitted. Then the series vanishes to working
// precision (a lower bound holds) only when every error is at the rounding level and the floor
// is the precision's, not the reference's; otherwise it is inconclusive, naming the digits that
// would resolve it: an error below the reference's accuracy cannot be told from the reference's
// own error, and an error between the rounding level and the floor from rounding.
template <class T>
Series make_series(const std::string& label, const std::vector<T>& h, const std::vector<T>& error,
                   const Floor<T>& floors, std::optional<double> predicted, bool exact,
                   double tolerance, const FitOptions& options = {}) {
  using std::isfinite;
  for (std::size_t i = 0; i < error.size(); ++i)
    if (!isfinite(error[i]))
      throw std::domain_error(label + " is " + to_decimal<T>(error[i]) + " at h = " + to_decimal<T>(h[i], 17) +
                              ": the computation left the finite numbers (a step too large for the method, or a "
                              "state outside the Lagrangian's domain); nothing is fitted to it");
  const T floor = floors.value();
  Series series;
  series.label = label;
  for (const auto& x : h) series.h.push_back(to_decimal<T>(x));
  for (const auto& e : error) series.error.push_back(to_decimal<T>(e));
  series.floor = to_decimal<T>(floor);
  series.rounding_floor = to_decimal<T>(floors.rounding);
  series.reference_floor = to_decimal<T>(floors.reference);
  series.fit = fit_order(h, error, floor, options);
  series.predicted_order = predicted;
  series.exact_order = exact;
  if (!predicted) return series;
  int above = 0;
  T largest_at_floor = 0, smallest = 0;
  for (const T& e : error) {
    if (e > floor)
      ++above;
    else if (e > largest_at_floor)
      largest_at_floor = e;
    if (e > 0 && (smallest == 0 || e < smallest)) smallest = e;
  }
  if (above >= 2) {
    OrderVerdict verdict = judge_order(*series.fit, *predicted, exact, tolerance);
    series.rule = "order";
    series.holds = verdict.holds;
    series.inconclusive = verdict.inconclusive;
    series.to_decide = verdict.to_decide;
    series.explanation = verdict.explanation;
    series.detection_limit = verdict.detection_limit;
    // Points the floor hid: more precision (or larger steps) brings them back into the fit.
    const int hidden = static_cast<int>(std::count_if(
        series.fit->dropped.begin(), series.fit->dropped.end(),
        [](const DroppedPoint& point) { return point.second.rfind("at the floor", 0) == 0; }));
    if (series.inconclusive && hidden > 0) {
      const std::string more = "; or bring back the " + std::to_string(hidden) + " point" +
                               (hidden > 1 ? "s" : "") + " the floor " + format_scalar(floor) +
                               " hides: " + floors.advice_for(smallest);
      series.to_decide += more;
      series.explanation += more;
    }
    // A widened tolerance shows beside its verdict the one the default tolerance gives.
    const double default_tolerance = std::stod(default_order_tolerance);
    if (tolerance > default_tolerance) {
      const OrderVerdict at_default =
          judge_order(*series.fit, *predicted, exact, default_tolerance);
      series.explanation += std::string("; at the default order tolerance ") +
                            default_order_tolerance + " it " +
                            (at_default.holds          ? "holds too"
                             : at_default.inconclusive ? "is inconclusive"
                                                       : "fails");
    }
    return series;
  }
  const bool at_rounding = largest_at_floor <= floors.rounding_level();
  series.rule = "floor";
  if (above == 0 && at_rounding && !floors.reference_limited() && !exact) {
    // A quantity that vanishes to working precision at every h satisfies any lower bound on its
    // order.
    series.holds = true;
    series.explanation = "at the rounding level (<= " + format_scalar(floors.rounding_level()) +
                         ") at every h: vanishes to working precision";
    series.detection_limit = "an error above the floor " + format_scalar(floor) +
                             " at two or more h would have been fitted";
    return series;
  }
  series.holds = false;
  series.inconclusive = true;
  const std::string counted = std::to_string(above) + " of " + std::to_string(error.size()) +
                              " errors above the floor " + format_scalar(floor);
  if (above == 0 && at_rounding && exact && !floors.reference_limited()) {
    series.explanation =
        "every error is at the rounding level: an exact order cannot be confirmed from errors "
        "that vanish";
    series.to_decide = "larger steps (smaller step counts), where the error is above the floor";
  } else if (floors.reference_limited()) {
    series.explanation = counted +
                         ", which the reference's accuracy sets (1000 x its tolerance, scaled: " +
                         format_scalar(floors.reference) + "; the rounding floor is " +
                         format_scalar(floors.rounding) +
                         "): the errors below it cannot be told from the "
                         "reference's own error";
    series.to_decide = floors.precision_fixed
                           ? floors.advice_for(smallest)
                           : "a reference accurate enough for the smallest error " + format_scalar(smallest) +
                                 ": " + floors.advice_for(smallest);
  } else {
    series.explanation = counted + " and the others between the floor and the rounding level " +
                         format_scalar(floors.rounding_level()) + " (largest " +
                         format_scalar(largest_at_floor) + "): no order can be measured from them";
    series.to_decide = floors.precision_fixed
                           ? floors.advice_for(smallest)
                           : "more precision for the smallest error " + format_scalar(smallest) + ": " +
                                 floors.advice_for(smallest);
  }
  series.explanation += "; to decide: " + series.to_decide;
  return series;
}

// A series judged against a single floor (tests, synthetic sweeps): the floor is the rounding's.
template <class T>
Series make_series(const std::string& label, const std::vector<T>& h, const std::vector<T>& error,
                   const T& floor, std::optional<double> predicted, bool exact, double tolerance,
                   const FitOptions& options = {}) {
  return make_series(label, h, error, Floor<T>{floor, T(0)}, predicted, exact, tolerance, options);
}

// "fail" when a judged series fails, else "inconclusive" when one cannot decide, else "pass";
// the explanation names the failures (or what would decide), and the first series that decided
// a fail or an inconclusive verdict is the claim's decisive series, its detection limit the
// claim's.
inline void conclude(ClaimResult& claim) {
  std::string failures, undecided;
  int first_failure = -1, first_undecided = -1;
  for (std::size_t i = 0; i < claim.series.size(); ++i) {
    const Series& series = claim.series[i];
    if (!series.holds || *series.holds) continue;
    std::string& text = series.inconclusive ? undecided : failures;
    int& first = series.inconclusive ? first_undecided : first_failure;
    if (first < 0) first = static_cast<int>(i);
    text += (text.empty() ? "" : "; ") + series.label + ": " + series.explanation;
  }
  const std::string verdict = first_failure >= 0     ? "fail"
                              : first_undecided >= 0 ? "inconclusive"
                                                     : "pass";
  const bool decided_here = claim.verdict.empty();
  if (decided_here) claim.verdict = verdict;
  if (decided_here && claim.verdict != "pass")
    claim.decisive_series = claim.verdict == "fail" ? first_failure : first_undecided;
  if (claim.explanation.empty())
    claim.explanation = verdict == "fail"           ? failures
                        : verdict == "inconclusive" ? undecided
                                                    : "every prediction holds";
  if (claim.detection_limit.empty() && !claim.series.empty())
    claim.detection_limit =
        claim.series[static_cast<std::size_t>(claim.decisive_series)].detection_limit;
}

}  // namespace vivv
