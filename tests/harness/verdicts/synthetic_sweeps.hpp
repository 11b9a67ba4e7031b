// Synthetic sweeps for the order fit's tests (tests/harness/verdicts/order_fit_test.cpp,
// order_verdict_test.cpp and not_yet_asymptotic_test.cpp): step sizes, power laws, errors with given
// pairwise orders, the checks the verdict tests share and their fixture.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "harness/verdicts/order_fit.hpp"
#include "tests/test_scalars.hpp"

namespace vivv::sweeps {

// Allowance for rounding in the fitted order and its intercept. The data are exact to the
// precision of T (relative error <= 1e-15 for double) and the logarithms (|log e| < 200 here)
// are rounded to long double (relative 1e-19), so every log e is off by at most ~1e-14; with
// the spreads of log h used below (>= 1) the slope moves by less than 1e-13.
constexpr double kRounding = 1e-10;

// ---------------------------------------------------------------- synthetic sweeps

// h parsed from decimal strings, in T.
template <class T>
std::vector<T> steps_from(const std::vector<std::string>& texts) {
  std::vector<T> h;
  for (const std::string& text : texts) h.push_back(from_decimal<T>(text));
  return h;
}

// h_k = first / ratio^k, k = 0 .. count − 1.
template <class T>
std::vector<T> geometric_steps(const std::string& first, const std::string& ratio, int count) {
  std::vector<T> h{from_decimal<T>(first)};
  for (int k = 1; k < count; ++k) h.push_back(h.back() / from_decimal<T>(ratio));
  return h;
}

// e = C h^p (1 + c h): a power law with a small higher-order term.
template <class T>
std::vector<T> power_law(const std::vector<T>& h, const T& constant, const T& order,
                         const T& correction) {
  using std::pow;
  std::vector<T> error;
  for (const T& step : h) error.push_back(constant * pow(step, order) * (1 + correction * step));
  return error;
}

// e_0 = 1, e_{k+1} = e_k / 2^{p_k}: on halving steps, a sweep whose pairwise orders are p_k.
template <class T>
std::vector<T> errors_with_pairwise_orders(const std::vector<std::string>& orders) {
  using std::pow;
  std::vector<T> error{T(1)};
  for (const std::string& order : orders)
    error.push_back(error.back() / pow(T(2), from_decimal<T>(order)));
  return error;
}

template <class T>
T largest(const std::vector<T>& values) {
  return *std::max_element(values.begin(), values.end());
}

// log h in long double, computed in T.
template <class T>
std::vector<long double> logs(const std::vector<T>& values) {
  using std::log;
  std::vector<long double> result;
  for (const T& value : values) result.push_back(static_cast<long double>(log(value)));
  return result;
}

// Σ_{i<j} (x_i − x_j)(y_i − y_j) / Σ_{i<j} (x_i − x_j)²: the least-squares slope written as the
// weighted mean of the pairwise slopes, an oracle independent of the fit's centred sums.
inline long double weighted_pairwise_slope(const std::vector<long double>& x,
                                    const std::vector<long double>& y) {
  long double numerator = 0, denominator = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = i + 1; j < x.size(); ++j) {
      numerator += (x[i] - x[j]) * (y[i] - y[j]);
      denominator += (x[i] - x[j]) * (x[i] - x[j]);
    }
  }
  return numerator / denominator;
}

inline std::vector<int> indices_of(const std::vector<DroppedPoint>& dropped) {
  std::vector<int> indices;
  for (const auto& [index, why] : dropped) indices.push_back(index);
  return indices;
}

inline std::vector<int> all_indices(std::size_t count) {
  std::vector<int> indices(count);
  for (std::size_t i = 0; i < count; ++i) indices[i] = static_cast<int>(i);
  return indices;
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Decided against the prediction: not a pass, and not inconclusive either.
inline void expect_fails(const OrderVerdict& verdict) {
  EXPECT_FALSE(verdict.holds) << verdict.explanation;
  EXPECT_FALSE(verdict.inconclusive) << verdict.explanation;
}

// Not a pass, inconclusive, the explanation naming `why` and what decides it naming --refine.
inline void expect_inconclusive_until_refined(const OrderVerdict& verdict, const std::string& why) {
  EXPECT_FALSE(verdict.holds) << verdict.explanation;
  EXPECT_TRUE(verdict.inconclusive) << verdict.explanation;
  EXPECT_TRUE(contains(verdict.explanation, why)) << verdict.explanation;
  EXPECT_TRUE(contains(verdict.to_decide, "--refine")) << verdict.to_decide;
}

// The order verdict's tests run in double, quad and MPFR (at 100 digits).
template <class T>
class SweepVerdictTest : public ::testing::Test {
 protected:
  SweepVerdictTest() {
    if constexpr (is_mpfr_v<T>) guard_.emplace(100);
  }
  std::optional<PrecisionGuard> guard_;
};
using VerdictScalars = ::testing::Types<double, quad, mpfr_real>;

}  // namespace vivv::sweeps
