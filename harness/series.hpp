// Turning a measured error sweep into a Series: decimal strings, the fitted
// order (docs/theory.md (observed orders)) and, when the claim predicts one, its verdict.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/claim_result.hpp"
#include "harness/order_fit.hpp"

namespace vivv {

// A series of errors against h, fitted, and judged against `predicted`
// (a lower bound unless `exact`) with `tolerance` on the order.
template <class T>
Series make_series(const std::string& label, const std::vector<T>& h, const std::vector<T>& error,
                   const T& floor, std::optional<double> predicted, bool exact, double tolerance,
                   const FitOptions& options = {}) {
  using std::isfinite;
  for (std::size_t i = 0; i < error.size(); ++i)
    if (!isfinite(error[i]))
      throw std::domain_error(label + " is " + to_decimal<T>(error[i]) + " at h = " + to_decimal<T>(h[i], 17) +
                              ": the computation left the finite numbers (a step too large for the method, or a "
                              "state outside the Lagrangian's domain); nothing is fitted to it");
  Series series;
  series.label = label;
  for (const auto& x : h) series.h.push_back(to_decimal<T>(x));
  for (const auto& e : error) series.error.push_back(to_decimal<T>(e));
  series.floor = to_decimal<T>(floor);
  series.fit = fit_order(h, error, floor, options);
  series.predicted_order = predicted;
  series.exact_order = exact;
  bool all_at_floor = std::all_of(error.begin(), error.end(), [&](const T& e) { return e <= floor; });
  if (predicted && !exact && all_at_floor) {
    // A quantity that vanishes to working precision at every h satisfies any
    // lower bound on its order; an exact order cannot be confirmed from it.
    series.holds = true;
    series.explanation = "at the floor at every h: vanishes to working precision";
  } else if (predicted) {
    OrderVerdict verdict = judge_order(*series.fit, *predicted, exact, tolerance);
    series.holds = verdict.holds;
    series.explanation = verdict.explanation;
  }
  return series;
}

// "pass" when every judged series holds, else "fail"; the explanation names the failures.
inline void conclude(ClaimResult& claim) {
  bool all_hold = true;
  std::string failures;
  for (const auto& series : claim.series) {
    if (series.holds && !*series.holds) {
      all_hold = false;
      failures += (failures.empty() ? "" : "; ") + series.label + ": " + series.explanation;
    }
  }
  if (claim.verdict.empty()) claim.verdict = all_hold ? "pass" : "fail";
  if (claim.explanation.empty()) claim.explanation = all_hold ? "every prediction holds" : failures;
}

}  // namespace vivv
