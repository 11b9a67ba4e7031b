// Observed order of convergence (docs/theory.md (observed orders)): the fit in order_fit.cpp,
// the verdict judge_order in order_verdict.cpp.
//
// A sweep gives step sizes h_i and errors e_i. The observed order is the
// least-squares slope of log e against log h over the asymptotic range only:
// points at the round-off / reference-tolerance floor and large-h points that
// are not yet asymptotic are left out, and every point left out says why.
//
// The pieces compose: the logarithms are taken in the sweep's scalar T (errors
// may be far below the range of a double), everything after that is
// statistics in long double — pairwise orders, medians, the plateau and
// pre-asymptotic rules, the least-squares line and its Student-t interval.
#pragma once

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/numerics/scalar.hpp"
#include "reports/results.hpp"  // OrderFit, the data a fit produces

namespace vivv {

// How the asymptotic range is chosen and the interval reported.
struct FitOptions {
  // Pre-asymptotic: the leading point goes while |p_first − median p_rest| > asymptotic_tolerance.
  double asymptotic_tolerance = 0.25;
  // The plateau and pre-asymptotic rules never leave fewer points than this.
  int minimum_points = 3;
  // Plateau: the trailing point goes while p_last < plateau_fraction · median p_rest ...
  double plateau_fraction = 0.25;
  // ... the rest clearly converges, median p_rest >= plateau_minimum_order, while the trailing
  // point does not, p_last < plateau_minimum_order (a point that still falls like h^0.5 or faster
  // is a lower-order term, evidence, never a plateau) ...
  double plateau_minimum_order = 0.5;
  // ... and e_last <= plateau_floor_factor · floor, and e_last did not grow. A plateau further
  // above the floor, or an error that grew, is a failure to converge (an inconsistent scheme, a
  // wrong limit), not round-off: it stays in the fit, with a note. The floor is already a thousand
  // times the rounding a correct method shows, so ten times it is 10^4 times that rounding.
  double plateau_floor_factor = 10;
  // Two-sided confidence level of [confidence_low, confidence_high].
  double confidence = 0.95;
  // The verdict also looks at this many pairwise orders at the small-h end of the fit.
  int finest_orders = 2;
  // A refined sweep (--refine) reaches the asymptotic regime, and its finest pairwise order says
  // where that is: leading points whose pairwise order differs from it by more than this are
  // pre-asymptotic too. 0 turns the rule off.
  double asymptote_tolerance = 0;
};

// The comparison of an observed order with a prediction: holds, fails, or (inconclusive) the
// evidence cannot decide, with what would decide it.
struct OrderVerdict {
  bool holds = false;
  bool inconclusive = false;
  // Inconclusive because the pairwise orders move away from the prediction (receding evidence),
  // and the halvings of h estimated to decide it: --refine goes on in exactly that case.
  bool receding = false;
  int halvings_to_decide = 0;
  std::string to_decide;
  std::string explanation;
  std::string detection_limit;  // the orders that would have failed and the fit's resolution
};

// Where a series' floor comes from. Below `rounding` an error may be the working precision's
// rounding over N_max steps (1000·N_max·ε·scale); below `reference` it may be the reference's own
// error (1000·tolerance·scale). The floor is the larger; an error "vanishes to working precision"
// only at the rounding level rounding/1000, and only when the reference is not the limit.
// The MPFR digits that would resolve an error above the floor, as advice.
inline std::string digits_advice(int digits) {
  const std::string d = std::to_string(digits);
  return "scalar \"mpfr\" with \"digits\": " + d + " (or --scalar mpfr --digits " + d + ")" +
         (digits >= 1000 ? ", the most vivv takes, which may not be enough" : "");
}

template <class T>
struct Floor {
  T rounding = 0;
  T reference = 0;
  long double scale = 1;  // the state's size and any scaling of the series (e.g. 1/h^(r+1))
  long double n_max = 1;  // the sweep's largest step count
  // The precision is the program's own (a map program that computes in double, "precision":
  // "double"): more digits are not an option the case accepts, larger steps are.
  bool precision_fixed = false;

  // What would bring `error` above this floor, in what the case accepts: more digits or larger
  // steps, or larger steps alone where the precision is fixed.
  std::string advice_for(const T& error) const {
    if (precision_fixed)
      return "larger steps (the program computes in double: more digits cannot lower this floor)";
    return digits_advice(digits_for(error)) + ", or larger steps";
  }

  T value() const { return rounding > reference ? rounding : reference; }
  bool reference_limited() const { return reference > rounding; }
  T rounding_level() const { return rounding / 1000; }
  // The same floor for a series scaled by 1/divisor.
  Floor scaled_down(const T& divisor) const {
    return {rounding / divisor, reference / divisor, scale / static_cast<long double>(divisor),
            n_max, precision_fixed};
  }
  // MPFR decimal digits that put this floor a thousand times below `error`: with D digits the
  // reference is promised to 10^(10 − D) (ten guard digits) and N steps round to about
  // 2N·10^(−D), so the floor is 1000·max(10^(10 − D), 2N·10^(−D))·scale.
  int digits_for(const T& error) const {
    // An error of 0 (or not finite) has no logarithm: the most digits a case may use then.
    const long double log10_error =
        error > 0 ? static_cast<long double>(log10_of(error)) : -INFINITY;
    long double digits =
        std::ceil(std::log10(1e6L * std::max(1e10L, 2 * n_max) * scale) - log10_error);
    if (!(digits <= 1000)) digits = 1000;              // vivv's largest "digits" (NaN too)
    return static_cast<int>(std::max(digits, 20.0L));  // and its smallest
  }

 private:
  static T log10_of(const T& x) {
    using std::log10;
    return log10(x);
  }
};

// One point of a sweep in logarithms, as the statistics see it.
struct LogPoint {
  int index = 0;              // into the caller's arrays
  long double log_h = 0;      // log h (NaN or −inf when h <= 0)
  long double log_error = 0;  // log e (−inf when e = 0)
  std::string masked;         // why the point is out before any fit; empty if usable
  bool near_floor = false;    // e <= plateau_floor_factor · floor
};

// Least-squares line y ≈ intercept + slope·x.
struct LeastSquaresLine {
  long double slope = NAN;
  long double intercept = NAN;
  long double standard_error = NAN;  // NaN when there are only 2 points
  int points = 0;
};

// slope = Σ(x − x̄)(y − ȳ) / Σ(x − x̄)², intercept = ȳ − slope·x̄,
// standard_error = sqrt(Σ r² / ((n − 2) Σ(x − x̄)²)); needs n >= 2 and distinct x.
LeastSquaresLine least_squares_line(const std::vector<long double>& x,
                                    const std::vector<long double>& y);

// p_k = (y_k − y_{k+1}) / (x_k − x_{k+1}) for consecutive points; NaN where undefined.
std::vector<double> pairwise_slopes(const std::vector<long double>& x,
                                    const std::vector<long double>& y);

// The median of the finite values (NaN if there are none).
double median_of_finite(std::vector<double> values);

// The fit's mark of "undefined" (a slope of one point, the order of no fit).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// x with `digits` significant digits, for the verdicts' sentences: "0.62", "1.98", "1e+06".
std::string format_digits(long double x, int digits = 3);

// t with P(|t_ν| <= t) = confidence for Student's t distribution with ν degrees of freedom.
double students_t_two_sided(double confidence, int degrees_of_freedom);

// Drops trailing points of `kept` (decreasing h) while p_last < plateau_fraction · median p_rest
// with median p_rest >= plateau_minimum_order > p_last, as "at the floor (plateau ...)".
void drop_plateau(std::vector<LogPoint>& kept, std::vector<DroppedPoint>& dropped,
                  std::vector<std::string>& notes, const FitOptions& options);

// Drops leading points of `kept` (decreasing h) while |p_first − median p_rest| >
// asymptotic_tolerance, then (when asymptote_tolerance > 0) while |p_first − p_finest| >
// asymptote_tolerance, as "pre-asymptotic (...)".
void drop_pre_asymptotic(std::vector<LogPoint>& kept, std::vector<DroppedPoint>& dropped,
                         const FitOptions& options);

// log e ≈ log C + order · log h by least squares over the points that survive the mask, the
// plateau rule and the pre-asymptotic rule, in that order.
OrderFit fit_order_in_logs(std::vector<LogPoint> points, const FitOptions& options = {});

// Whether an order agrees with the prediction: p >= predicted − tolerance, or
// |p − predicted| <= tolerance if exact.
bool order_agrees(double order, double predicted, bool exact, double tolerance);

// holds ⇔ fit.ok, the fitted order agrees with the prediction and so does each of the finest
// pairwise orders (an asymptotic statement is about small h: a fit pulled up by large-h points
// cannot pass a sweep whose last steps converge more slowly). The explanation says which of the
// two disagrees, and when an exact prediction lies outside the fit's confidence interval.
// Inconclusive instead of a failure where the sweep is not yet asymptotic: pairwise orders still
// converging on the prediction, an error that dips between the two finest steps, or two points
// above the floor with the smaller steps hidden below it (docs/claims.md); and instead of a pass
// where the fit's interval cannot tell the prediction from the next integer order.
// Before a pass, the evidence must not recede: where the pairwise orders above the floor move away
// from the prediction by more than receding_noise (or toward it on a course that ends beyond the
// tolerance), the verdict is inconclusive, never a pass, and names the halvings of h that decide.
// Rising orders that converge on the prediction, the finest within the tolerance, while the fit
// still lags are inconclusive too (a short sweep: one more halving decides). Every verdict's
// detection limit names the smallest lower-order term b·h_min/h (its share of the error at the
// smallest h) that would not have passed.
OrderVerdict judge_order(const OrderFit& fit, double predicted, bool exact, double tolerance);

// The noise of a pairwise order of a correct method above the floor: a point there is rounded by
// at most 10⁻³ of its error (the floor is 1000 times the rounding), which moves a pairwise order at
// h ratio 2 by at most 0.003; the correct methods of the default suite, the examples and the
// controls move their last pairwise order away from the prediction by at most 0.0002.
constexpr double receding_noise = 0.01;

// The pairwise orders between the points above the floor, largest h first (the pre-asymptotic
// ones included: a rule that dropped leading points must not hide where the orders go).
inline std::vector<double> orders_above_floor(const OrderFit& fit) {
  const std::size_t count = static_cast<std::size_t>(std::max(fit.above_floor - 1, 0));
  return {fit.pairwise_orders.begin(),
          fit.pairwise_orders.begin() + static_cast<std::ptrdiff_t>(std::min(count, fit.pairwise_orders.size()))};
}

// The smallest b for which e(h) = h^p·(1 + b·h_min/h), on the step sizes of `fit` above the floor,
// would not pass judge_order (NaN where none up to 10³ fails it, or the fit has no steps).
double lower_order_detection_limit(const OrderFit& fit, double predicted, bool exact, double tolerance);

// x written with `digits` significant digits, as a stream writes T ("1.2e-61", "0.5").
template <class T>
std::string format_scalar(const T& x, int digits = 2) {
  std::ostringstream out;
  out << std::setprecision(digits) << x;
  return out.str();
}

// Why (h, e) is out before any fit, against `floor`: "zero error", "at the floor (error e <=
// floor f)", a non-positive step or a non-finite error; empty when the point is usable.
template <class T>
std::string mask_reason(const T& h, const T& error, const T& floor) {
  using std::isfinite;
  if (!(h > 0) || !isfinite(h))
    return "step not positive and finite (h = " + format_scalar(h) + ")";
  if (!isfinite(error) || error < 0)
    return "error not finite and >= 0 (" + format_scalar(error) + ")";
  if (error == 0) return "zero error";
  if (error <= floor) {
    return "at the floor (error " + format_scalar(error) + " <= floor " + format_scalar(floor) +
           ")";
  }
  return "";
}

// The observed order of the sweep (h_i, e_i): logarithms in T, then fit_order_in_logs.
template <class T>
OrderFit fit_order(const std::vector<T>& h, const std::vector<T>& error, const T& floor,
                   const FitOptions& options = {}) {
  using std::log;
  if (h.size() != error.size()) {
    throw std::invalid_argument("fit_order: " + std::to_string(h.size()) + " step sizes but " +
                                std::to_string(error.size()) + " errors");
  }
  const T plateau_reach = T(options.plateau_floor_factor) * floor;
  std::vector<LogPoint> points(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    LogPoint& point = points[i];
    point.index = static_cast<int>(i);
    point.masked = mask_reason(h[i], error[i], floor);
    point.log_h = h[i] > 0 ? static_cast<long double>(log(h[i])) : -INFINITY;
    point.log_error = error[i] > 0 ? static_cast<long double>(log(error[i])) : -INFINITY;
    point.near_floor = error[i] <= plateau_reach;
  }
  return fit_order_in_logs(std::move(points), options);
}

}  // namespace vivv
