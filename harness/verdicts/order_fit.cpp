#include "harness/verdicts/order_fit.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <cstdio>
#include <limits>
#include <numeric>
#include <optional>

namespace vivv {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// e = exp(log_e) written as "1.2e-61", even where e itself is outside the range of long double.
std::string format_from_log(long double log_e) {
  if (!std::isfinite(log_e)) return format_digits(std::exp(log_e), 2);
  const long double decimal = log_e / std::log(10.0L);
  long double exponent = std::floor(decimal);
  long double mantissa = std::pow(10.0L, decimal - exponent);
  if (std::round(mantissa * 10) >= 100) {  // 9.96 rounds to 10
    mantissa /= 10;
    exponent += 1;
  }
  return format_digits(mantissa, 2) + "e" + (exponent < 0 ? "-" : "+") +
         format_digits(std::fabs(exponent), 6);
}

std::vector<double> pairwise_orders_of(const std::vector<LogPoint>& points) {
  std::vector<long double> log_h, log_error;
  for (const LogPoint& point : points) {
    log_h.push_back(point.log_h);
    log_error.push_back(point.log_error);
  }
  return pairwise_slopes(log_h, log_error);
}

}  // namespace

LeastSquaresLine least_squares_line(const std::vector<long double>& x,
                                    const std::vector<long double>& y) {
  LeastSquaresLine line;
  const std::size_t n = x.size();
  line.points = static_cast<int>(n);
  if (n != y.size() || n < 2) return line;
  const long double x_mean = std::accumulate(x.begin(), x.end(), 0.0L) / n;
  const long double y_mean = std::accumulate(y.begin(), y.end(), 0.0L) / n;
  long double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - x_mean) * (x[i] - x_mean);
    sxy += (x[i] - x_mean) * (y[i] - y_mean);
  }
  if (!(sxx > 0)) return line;
  line.slope = sxy / sxx;
  line.intercept = y_mean - line.slope * x_mean;
  if (n > 2) {
    long double residual_squares = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const long double residual = y[i] - (line.intercept + line.slope * x[i]);
      residual_squares += residual * residual;
    }
    line.standard_error = std::sqrt(residual_squares / ((n - 2) * sxx));
  }
  return line;
}

std::vector<double> pairwise_slopes(const std::vector<long double>& x,
                                    const std::vector<long double>& y) {
  std::vector<double> slopes;
  for (std::size_t k = 0; k + 1 < std::min(x.size(), y.size()); ++k) {
    const long double dx = x[k] - x[k + 1];
    const long double dy = y[k] - y[k + 1];
    const bool defined = std::isfinite(dx) && std::isfinite(dy) && dx != 0;
    slopes.push_back(defined ? static_cast<double>(dy / dx) : kNaN);
  }
  return slopes;
}

std::string format_digits(long double x, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*Lg", digits, x);
  return buffer;
}

double median_of_finite(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const std::size_t middle = values.size() / 2;
  return values.size() % 2 == 1 ? values[middle] : (values[middle - 1] + values[middle]) / 2;
}

double students_t_two_sided(double confidence, int degrees_of_freedom) {
  const boost::math::students_t_distribution<double> distribution(degrees_of_freedom);
  return boost::math::quantile(boost::math::complement(distribution, (1 - confidence) / 2));
}

void drop_plateau(std::vector<LogPoint>& kept, std::vector<DroppedPoint>& dropped,
                  std::vector<std::string>& notes, const FitOptions& options) {
  const std::size_t keep_at_least = std::max(options.minimum_points, 2);
  while (kept.size() > keep_at_least) {
    std::vector<double> orders = pairwise_orders_of(kept);
    const double last = orders.back();
    orders.pop_back();
    const double rest = median_of_finite(orders);
    const bool plateau =
        last < options.plateau_fraction * rest && rest >= options.plateau_minimum_order;
    if (!plateau) return;
    const std::string numbers =
        "pairwise order " + format_digits(last) + " vs " + format_digits(rest) + " on the rest";
    // A plateau is flat: an error above the floor that still falls like a power of h (at order
    // plateau_minimum_order or more) is a lower-order term showing, the defect's signature, not
    // round-off. Yoshida's composition with one weight written to 6 digits fell like h¹ above the
    // floor, and the rule once dropped those points and quoted the orders before them.
    if (last >= options.plateau_minimum_order) {
      notes.push_back("at the small-h end the error still falls, at pairwise order " +
                      format_digits(last) + " (vs " + format_digits(rest) + " on the rest) with error " +
                      format_from_log(kept.back().log_error) +
                      " above the floor: kept in the fit, as a lower-order term rather than a plateau");
      return;
    }
    if (!kept.back().near_floor) {
      notes.push_back("plateau at the small-h end (" + numbers + ") with error " +
                      format_from_log(kept.back().log_error) + ", more than " +
                      format_digits(options.plateau_floor_factor) +
                      " times the floor: kept in the fit, as a failure to converge rather than "
                      "round-off");
      return;
    }
    if (kept.back().log_error > kept[kept.size() - 2].log_error) {
      notes.push_back("the error grew at the small-h end (" + numbers + ", error " +
                      format_from_log(kept.back().log_error) +
                      "): kept in the fit, as a failure to converge rather than round-off");
      return;
    }
    dropped.emplace_back(kept.back().index, "at the floor (plateau: " + numbers + ")");
    kept.pop_back();
  }
}

// A coarse part proved pre-asymptotic further in than its first point: the pairwise orders from
// some position on — at least settled_tail_orders of them — all lie within the asymptotic
// tolerance of their median (a settled tail), and the order just before them does not; the
// points before the tail go. The leading-point rule above stops at a first order that happens to
// sit near the rest: a stiff FPU chain (16 coordinates, ω = 80, hω = 2 … 0.125, refined) showed
// 1.95, −0.80, 1.23, 1.93, 1.99, 2.00, 2.00, 2.00 and was fitted over all nine points (1.54,
// inconclusive, advice already met); over the settled tail it is 1.99. Only coarse points go, so
// the fit keeps the small-h end, where a lower-order term shows. A tail that does not converge
// (median below plateau_minimum_order) leaves the sweep as it is.
namespace {

constexpr std::size_t settled_tail_orders = 3;

void drop_before_settled_tail(std::vector<LogPoint>& kept, std::vector<DroppedPoint>& dropped,
                              const FitOptions& options) {
  const std::vector<double> orders = pairwise_orders_of(kept);
  if (orders.size() < settled_tail_orders + 1) return;
  const auto settled_from = [&](std::size_t start) {
    const double middle = median_of_finite(std::vector<double>(orders.begin() + static_cast<std::ptrdiff_t>(start),
                                                               orders.end()));
    for (std::size_t k = start; k < orders.size(); ++k)
      if (!(std::fabs(orders[k] - middle) <= options.asymptotic_tolerance)) return kNaN;
    return middle;
  };
  for (std::size_t start = 1; start + settled_tail_orders <= orders.size(); ++start) {
    const double middle = settled_from(start);
    if (std::isnan(middle)) continue;
    // A tail that does not converge (a plateau far above the floor) is a failure to converge,
    // judged over the whole sweep as before (drop_plateau's note), not an asymptotic range.
    if (!(middle >= options.plateau_minimum_order)) return;
    if (!(std::fabs(orders[start - 1] - middle) > options.asymptotic_tolerance)) return;
    for (std::size_t k = 0; k < start; ++k)
      dropped.emplace_back(kept[k].index, "pre-asymptotic (pairwise order " + format_digits(orders[k]) +
                                              " before a settled tail of " +
                                              std::to_string(orders.size() - start) + " orders at " +
                                              format_digits(middle) + ")");
    kept.erase(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(start));
    return;
  }
}

}  // namespace

void drop_pre_asymptotic(std::vector<LogPoint>& kept, std::vector<DroppedPoint>& dropped,
                         const FitOptions& options) {
  const std::size_t keep_at_least = std::max(options.minimum_points, 2);
  while (kept.size() > keep_at_least) {
    const std::vector<double> orders = pairwise_orders_of(kept);
    const double first = orders.front();
    const double rest = median_of_finite(std::vector<double>(orders.begin() + 1, orders.end()));
    if (!(std::fabs(first - rest) > options.asymptotic_tolerance)) break;
    dropped.emplace_back(kept.front().index, "pre-asymptotic (pairwise order " +
                                                 format_digits(first) + " vs " +
                                                 format_digits(rest) + " on the rest)");
    kept.erase(kept.begin());
  }
  drop_before_settled_tail(kept, dropped, options);
  if (!(options.asymptote_tolerance > 0)) return;
  while (kept.size() > keep_at_least) {
    const std::vector<double> orders = pairwise_orders_of(kept);
    const double first = orders.front(), finest = orders.back();
    if (!(std::fabs(first - finest) > options.asymptote_tolerance)) return;
    dropped.emplace_back(kept.front().index, "pre-asymptotic in the refined sweep (pairwise order " +
                                                 format_digits(first) + " vs " + format_digits(finest) +
                                                 " at the finest h)");
    kept.erase(kept.begin());
  }
}

OrderFit fit_order_in_logs(std::vector<LogPoint> points, const FitOptions& options) {
  OrderFit fit;
  fit.confidence = options.confidence;
  // Decreasing h; points without a usable log h go last.
  const auto sort_key = [](const LogPoint& point) {
    return std::isnan(point.log_h) ? -std::numeric_limits<long double>::infinity() : point.log_h;
  };
  std::stable_sort(points.begin(), points.end(),
                   [&](const LogPoint& a, const LogPoint& b) { return sort_key(a) > sort_key(b); });
  for (const LogPoint& point : points) {
    fit.sorted.push_back(point.index);
    fit.log_h.push_back(static_cast<double>(point.log_h));
  }
  fit.pairwise_orders = pairwise_orders_of(points);

  std::vector<LogPoint> kept;
  for (LogPoint& point : points) {
    if (point.masked.empty()) {
      kept.push_back(std::move(point));
    } else {
      fit.dropped.emplace_back(point.index, point.masked);
    }
  }
  drop_plateau(kept, fit.dropped, fit.notes, options);
  // The leading points (largest h first) that are neither masked nor dropped at the floor.
  for (const LogPoint& point : points) {
    const bool at_floor = !point.masked.empty() ||
                          std::none_of(kept.begin(), kept.end(),
                                       [&](const LogPoint& k) { return k.index == point.index; });
    if (at_floor) break;
    ++fit.above_floor;
  }
  drop_pre_asymptotic(kept, fit.dropped, options);
  std::sort(fit.dropped.begin(), fit.dropped.end(),
            [](const DroppedPoint& a, const DroppedPoint& b) { return a.first < b.first; });

  std::vector<long double> log_h, log_error;
  for (const LogPoint& point : kept) {
    fit.used.push_back(point.index);
    log_h.push_back(point.log_h);
    log_error.push_back(point.log_error);
  }
  std::sort(fit.used.begin(), fit.used.end());
  const std::vector<double> kept_orders = pairwise_orders_of(kept);
  const std::size_t finest = std::min<std::size_t>(std::max(options.finest_orders, 1), kept_orders.size());
  fit.finest_orders.assign(kept_orders.end() - finest, kept_orders.end());
  if (kept.size() < 2) {
    fit.reason = "only " + std::to_string(kept.size()) + " usable point" +
                 (kept.size() == 1 ? "" : "s") + " of " + std::to_string(points.size()) +
                 "; a fit needs 2";
    return fit;
  }
  const LeastSquaresLine line = least_squares_line(log_h, log_error);
  if (!std::isfinite(line.slope)) {
    fit.reason = "the " + std::to_string(kept.size()) + " usable points share one step size";
    return fit;
  }
  fit.ok = true;
  fit.order = static_cast<double>(line.slope);
  fit.log_constant = static_cast<double>(line.intercept);
  if (line.points > 2) {
    fit.standard_error = static_cast<double>(line.standard_error);
    const double half_width =
        students_t_two_sided(options.confidence, line.points - 2) * fit.standard_error;
    fit.confidence_low = fit.order - half_width;
    fit.confidence_high = fit.order + half_width;
  } else {
    fit.confidence_low = -kInfinity;
    fit.confidence_high = kInfinity;
  }
  return fit;
}

bool order_agrees(double order, double predicted, bool exact, double tolerance) {
  return exact ? std::fabs(order - predicted) <= tolerance : order >= predicted - tolerance;
}

}  // namespace vivv
