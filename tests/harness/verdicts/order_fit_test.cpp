#include "harness/verdicts/order_fit.hpp"

#include <gtest/gtest.h>

#include "tests/harness/verdicts/synthetic_sweeps.hpp"
#include "tests/test_scalars.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace vivv {
namespace {

using namespace sweeps;


// ---------------------------------------------------------------- the statistics alone

TEST(OrderFitStatistics, LeastSquaresLineMatchesTheHandComputation) {
  // x = (0, 1, 2), y = (0, 1, 1): x̄ = 1, ȳ = 2/3, Sxx = 2, Sxy = 1, so slope 1/2, intercept 1/6;
  // residuals (−1/6, 1/3, −1/6), Σ r² = 1/6, standard error sqrt((1/6) / (1 · 2)) = sqrt(1/12).
  const LeastSquaresLine line = least_squares_line({0, 1, 2}, {0, 1, 1});
  EXPECT_NEAR(static_cast<double>(line.slope), 0.5, 1e-15);
  EXPECT_NEAR(static_cast<double>(line.intercept), 1.0 / 6, 1e-15);
  EXPECT_NEAR(static_cast<double>(line.standard_error), std::sqrt(1.0 / 12), 1e-15);
  EXPECT_EQ(line.points, 3);
}

TEST(OrderFitStatistics, TwoPointsGiveASlopeButNoStandardError) {
  const LeastSquaresLine line = least_squares_line({0, 2}, {1, 4});
  EXPECT_NEAR(static_cast<double>(line.slope), 1.5, 1e-15);
  EXPECT_TRUE(std::isnan(line.standard_error));
  // Equal x: no line at all.
  EXPECT_TRUE(std::isnan(least_squares_line({1, 1, 1}, {0, 1, 2}).slope));
}

TEST(OrderFitStatistics, PairwiseSlopesAreNaNWhereUndefined) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> slopes = pairwise_slopes({3, 2, 2, 0}, {6, 4, -inf, 0});
  ASSERT_EQ(slopes.size(), 3u);
  EXPECT_DOUBLE_EQ(slopes[0], 2);
  EXPECT_TRUE(std::isnan(slopes[1]));  // equal x and a zero error
  EXPECT_TRUE(std::isnan(slopes[2]));  // a zero error
}

TEST(OrderFitStatistics, MedianSkipsValuesThatAreNotFinite) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(median_of_finite({3, nan, 1, 2}), 2);
  EXPECT_DOUBLE_EQ(median_of_finite({4, 1, nan, 2, 3}), 2.5);
  EXPECT_TRUE(std::isnan(median_of_finite({nan})));
}

TEST(OrderFitStatistics, StudentQuantilesMatchTheTables) {
  // Two-sided 95%: t = 12.706 for 1 degree of freedom, 2.228 for 10 (standard tables).
  EXPECT_NEAR(students_t_two_sided(0.95, 1), 12.7062047, 1e-6);
  EXPECT_NEAR(students_t_two_sided(0.95, 10), 2.2281389, 1e-6);
}

// ---------------------------------------------------------------- fits in every scalar

template <class T>
class OrderFitTest : public ::testing::Test {
 protected:
  OrderFitTest() {
    // 100 digits: errors of 1e-70 still carry 30 significant digits.
    if constexpr (is_mpfr_v<T>) guard_.emplace(100);
  }
  std::optional<PrecisionGuard> guard_;
};
using Scalars = ::testing::Types<double, quad, mpfr_real>;
TYPED_TEST_SUITE(OrderFitTest, Scalars, testing::ScalarNames);

// One row of the recovery table: e = C h^p (1 + c h) on the given steps.
struct PowerLawRow {
  std::string order;                   // p
  std::string constant;                // C
  std::string correction;              // c
  std::vector<std::string> steps;      // explicit steps, any order; or, if empty,
  std::string first = "", ratio = "";  // h_k = first / ratio^k
  int count = 0;                       //   for k < count
};

const std::vector<PowerLawRow>& power_law_table() {
  static const std::vector<PowerLawRow> rows = {
      // Irregular ratios between 1.4 and 1.6, none a power of 2.
      {"1", "3", "0.01", {"0.1", "0.07", "0.05", "0.033", "0.021", "0.015", "0.01", "0.0068"}},
      // The same steps given in increasing order, and a negative correction.
      {"2", "0.5", "-0.02", {"0.0068", "0.01", "0.015", "0.021", "0.033", "0.05", "0.07", "0.1"}},
      // Ratio 7.3 down to h = 7.4e-20: errors reach 2e-67.
      {"3.5", "2", "0.01", {}, "0.1", "7.3", 22},
  };
  return rows;
}

TYPED_TEST(OrderFitTest, RecoversTheOrderOfAPowerLawWithAHigherOrderTerm) {
  using T = TypeParam;
  for (const PowerLawRow& row : power_law_table()) {
    SCOPED_TRACE("p = " + row.order);
    const std::vector<T> h = row.steps.empty() ? geometric_steps<T>(row.first, row.ratio, row.count)
                                               : steps_from<T>(row.steps);
    const T correction = from_decimal<T>(row.correction);
    const std::vector<T> error =
        power_law(h, from_decimal<T>(row.constant), from_decimal<T>(row.order), correction);
    const OrderFit fit = fit_order(h, error, T(0));
    ASSERT_TRUE(fit.ok) << fit.reason;
    // log e = log C + p log h + log(1 + c h); d log(1 + c h) / d log h = c h / (1 + c h), so every
    // pairwise order, and the least-squares slope (a weighted mean of them), is within
    // |c| h_max / (1 − |c| h_max) of p.
    const double c_h = std::fabs(static_cast<double>(correction * largest(h)));
    const double bound = c_h / (1 - c_h) + kRounding;
    const double p = static_cast<double>(from_decimal<T>(row.order));
    EXPECT_NEAR(fit.order, p, bound);
    EXPECT_LE(fit.confidence_low, fit.order);
    EXPECT_GE(fit.confidence_high, fit.order);
    for (double pairwise : fit.pairwise_orders) EXPECT_NEAR(pairwise, p, bound);
    EXPECT_EQ(fit.pairwise_orders.size(), h.size() - 1);
    EXPECT_EQ(fit.used, all_indices(h.size()));
    EXPECT_TRUE(fit.dropped.empty());
    // The sorted indices run through the steps by decreasing h.
    for (std::size_t k = 0; k + 1 < fit.sorted.size(); ++k) {
      EXPECT_GT(h[fit.sorted[k]], h[fit.sorted[k + 1]]);
    }
  }
}

TYPED_TEST(OrderFitTest, ExactPowerLawHasNoStandardErrorAndItsConstant) {
  using T = TypeParam;
  using std::log;
  const std::vector<T> h = geometric_steps<T>("0.2", "2.7", 12);
  const T constant = from_decimal<T>("0.37");
  const OrderFit fit = fit_order(h, power_law(h, constant, T(3), T(0)), T(0));
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_NEAR(fit.order, 3, kRounding);
  EXPECT_NEAR(fit.log_constant, static_cast<double>(log(constant)), kRounding);
  // Residuals are rounding only (see kRounding), so the standard error is too.
  EXPECT_LE(fit.standard_error, kRounding);
  EXPECT_LE(fit.confidence_high - fit.confidence_low, 10 * kRounding);
}

TYPED_TEST(OrderFitTest, NoisyPowerLawHasAPositiveStandardError) {
  using T = TypeParam;
  // e_k = h_k² (1 ± 5%), alternating, with h_k = 0.1 / 3^k. The noise δ_k = log(1 ± 0.05) moves
  // each pairwise order by at most (log 1.05 − log 0.95) / log 3 = 0.091, so they differ by at
  // most 0.18 < asymptotic_tolerance and no point is dropped.
  const std::vector<T> h = geometric_steps<T>("0.1", "3", 10);
  std::vector<T> error = power_law(h, T(1), T(2), T(0));
  const T noise = from_decimal<T>("0.05");
  for (std::size_t k = 0; k < error.size(); ++k) error[k] *= k % 2 == 0 ? 1 + noise : 1 - noise;
  const OrderFit fit = fit_order(h, error, T(0));
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_EQ(fit.used, all_indices(h.size()));
  // The slope is the noise-free 2 plus Σ(x − x̄)δ / Σ(x − x̄)², at most max|δ| Σ|x − x̄| / Sxx.
  const std::vector<long double> x = logs(h);
  long double x_mean = 0, spread = 0, sxx = 0;
  for (long double value : x) x_mean += value / x.size();
  for (long double value : x) {
    spread += std::fabs(value - x_mean);
    sxx += (value - x_mean) * (value - x_mean);
  }
  const double noise_bound = static_cast<double>(-std::log(0.95L) * spread / sxx);
  EXPECT_NEAR(fit.order, 2, noise_bound + kRounding);
  EXPECT_NEAR(fit.order, static_cast<double>(weighted_pairwise_slope(x, logs(error))), kRounding);
  // An alternating sequence is not a line in x, so the residuals (|δ| ≈ 0.05 each) are not
  // rounding: the standard error is far above kRounding.
  EXPECT_GT(fit.standard_error, 1e-3);
  EXPECT_LT(fit.confidence_low, fit.order);
  EXPECT_GT(fit.confidence_high, fit.order);
}

// e = C h^p (1 + c h) with p = 2 on h_k = 0.1 / 5.3^k, k < 25: errors from 1e-2 down to 1e-38.
template <class T>
struct FloorSweep {
  std::vector<T> h = geometric_steps<T>("0.1", "5.3", 25);
  std::vector<T> law = power_law(h, T(1), T(2), from_decimal<T>("0.01"));
};

TYPED_TEST(OrderFitTest, DropsExactlyThePointsAtTheFloorAndStillRecoversTheOrder) {
  using T = TypeParam;
  const FloorSweep<T> sweep;
  const T floor = from_decimal<T>("1e-30");
  std::vector<T> error;
  std::vector<int> flattened;
  for (std::size_t k = 0; k < sweep.h.size(); ++k) {
    if (sweep.law[k] <= floor) flattened.push_back(static_cast<int>(k));
    error.push_back(std::max(sweep.law[k], floor));  // the error flattens at 1e-30
  }
  ASSERT_GE(flattened.size(), 3u);  // the sweep does reach the floor
  const OrderFit fit = fit_order(sweep.h, error, floor);
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_EQ(indices_of(fit.dropped), flattened);
  for (const auto& [index, why] : fit.dropped) {
    EXPECT_TRUE(contains(why, "at the floor (error 1e-30 <= floor 1e-30)")) << why;
  }
  EXPECT_EQ(fit.used.size() + flattened.size(), sweep.h.size());
  EXPECT_NEAR(fit.order, 2, 0.01 * 0.1 / (1 - 0.01 * 0.1) + kRounding);  // c h_max, as above
}

// The law up to index `last`, then flat at the error there: a plateau the floor does not name.
template <class T>
std::vector<T> with_plateau_after(const std::vector<T>& law, std::size_t last) {
  std::vector<T> error = law;
  for (std::size_t k = last + 1; k < error.size(); ++k) error[k] = law[last];
  return error;
}

TYPED_TEST(OrderFitTest, DropsAPlateauNearTheFloor) {
  using T = TypeParam;
  const FloorSweep<T> sweep;
  const std::size_t last = 17;  // 7 flat points after it
  const std::vector<T> error = with_plateau_after(sweep.law, last);
  // A floor 5 times below the plateau (within plateau_floor_factor = 10): round-off.
  const OrderFit fit = fit_order(sweep.h, error, T(sweep.law[last] / 5));
  ASSERT_TRUE(fit.ok) << fit.reason;
  // Pairwise orders: 2 (within c h_max) up to `last`, then exactly 0; the last pairwise order
  // is 0 < plateau_fraction · 2 while more than half the rest are 2, so the rule drops the
  // flat points one by one and stops at `last`, whose pairwise order is 2.
  std::vector<int> flat;
  for (std::size_t k = last + 1; k < sweep.h.size(); ++k) flat.push_back(static_cast<int>(k));
  EXPECT_EQ(indices_of(fit.dropped), flat);
  for (const auto& [index, why] : fit.dropped) {
    EXPECT_TRUE(contains(why, "at the floor (plateau: pairwise order 0 vs 2 on the rest)")) << why;
  }
  EXPECT_NEAR(fit.order, 2, 0.01 * 0.1 / (1 - 0.01 * 0.1) + kRounding);
  EXPECT_TRUE(fit.notes.empty());
}

TYPED_TEST(OrderFitTest, KeepsAPlateauFarAboveTheFloorAndTheOrderFails) {
  using T = TypeParam;
  const FloorSweep<T> sweep;
  const std::size_t last = 13;  // 11 flat points: the error stops converging at 1.5e-21
  const std::vector<T> error = with_plateau_after(sweep.law, last);
  // A floor 1e20 below the plateau: not round-off, a failure to converge.
  const OrderFit fit = fit_order(sweep.h, error, T(sweep.law[last] / from_decimal<T>("1e20")));
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_TRUE(fit.dropped.empty());
  EXPECT_EQ(fit.used, all_indices(sweep.h.size()));
  ASSERT_EQ(fit.notes.size(), 1u);
  EXPECT_TRUE(contains(fit.notes[0], "failure to converge")) << fit.notes[0];
  // The fit is the plain least-squares slope over everything, far below 2.
  const long double expected = weighted_pairwise_slope(logs(sweep.h), logs(error));
  EXPECT_NEAR(fit.order, static_cast<double>(expected), kRounding);
  ASSERT_LT(expected, 2 - 0.25);  // a property of the constructed data
  EXPECT_FALSE(judge_order(fit, 2, false, 0.25).holds);
}

// A plateau 1000 times above the floor is no longer round-off (the floor is itself a thousand
// times the rounding a correct method shows): the points stay, and the order fails. Once the
// plateau rule reached 1e6 times the floor, and a midpoint rule converging to the wrong solution
// in double passed global-order at 4.10 with its stalled points dropped.
TYPED_TEST(OrderFitTest, KeepsAPlateauAThousandTimesAboveTheFloor) {
  using T = TypeParam;
  const FloorSweep<T> sweep;
  const std::size_t last = 17;
  const std::vector<T> error = with_plateau_after(sweep.law, last);
  const OrderFit fit = fit_order(sweep.h, error, T(sweep.law[last] / 1000));
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_TRUE(fit.dropped.empty());
  ASSERT_EQ(fit.notes.size(), 1u);
  EXPECT_TRUE(contains(fit.notes[0], "failure to converge")) << fit.notes[0];
  EXPECT_FALSE(judge_order(fit, 2, false, 0.2).holds);
}

// A last error that grew is never dropped as round-off, however near the floor: a scheme whose
// error turns back up is converging to something else.
TYPED_TEST(OrderFitTest, KeepsAnErrorThatGrewNearTheFloor) {
  using T = TypeParam;
  const FloorSweep<T> sweep;
  const std::size_t last = 17;
  std::vector<T> error(sweep.law.begin(), sweep.law.begin() + last + 2);
  std::vector<T> h(sweep.h.begin(), sweep.h.begin() + last + 2);
  error[last + 1] = 4 * error[last];  // grew fourfold, to 8 times the floor below
  const OrderFit fit = fit_order(h, error, T(error[last] / 2));
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_TRUE(fit.dropped.empty());
  ASSERT_EQ(fit.notes.size(), 1u);
  EXPECT_TRUE(contains(fit.notes[0], "the error grew")) << fit.notes[0];
  const OrderVerdict verdict = judge_order(fit, 2, false, 0.2);
  expect_fails(verdict);
}

TYPED_TEST(OrderFitTest, DropsPreAsymptoticPointsWithAReason) {
  using T = TypeParam;
  using std::pow;
  // e = h² + D h⁵ with D = 1e6. For h >= 0.5, D h³ >= 1.25e5: the h⁵ term dominates, and the
  // pairwise orders there are 5 within 1e-4. From h = 0.5 to h = 1e-3 the order is at least
  // log((D 0.5⁵) / (2e-6)) / log 500 = 3.78. For h <= 1e-3, D h³ <= 1e-3: orders in [2, 2.003].
  // So each leading point has a pairwise order > 2.25 against a median of the rest of ~2, and
  // exactly the points with D h³ > 1 are pre-asymptotic.
  const std::vector<T> h =
      steps_from<T>({"1", "0.7", "0.5", "0.001", "0.0007", "0.0005", "0.0003", "0.0002", "0.0001"});
  const T big = from_decimal<T>("1e6");
  std::vector<T> error;
  std::vector<int> pre_asymptotic;
  for (std::size_t k = 0; k < h.size(); ++k) {
    error.push_back(pow(h[k], 2) + big * pow(h[k], 5));
    if (big * pow(h[k], 3) > 1) pre_asymptotic.push_back(static_cast<int>(k));
  }
  const OrderFit fit = fit_order(h, error, T(0));
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_EQ(indices_of(fit.dropped), pre_asymptotic);
  for (const auto& [index, why] : fit.dropped) {
    EXPECT_TRUE(contains(why, "pre-asymptotic (pairwise order ")) << why;
    EXPECT_TRUE(contains(why, " vs 2 on the rest)")) << why;
  }
  // Local order 2 + 3 D h³ / (1 + D h³) <= 2 + 3 D h³ at the largest kept step.
  const double h_kept = static_cast<double>(h[fit.used.front()]);
  EXPECT_NEAR(fit.order, 2, 3e6 * h_kept * h_kept * h_kept + kRounding);
  // Without the rule, the pairs straddling the gap (orders >= 3.78, and the largest spreads in
  // log h, hence the largest weights) pull the slope well above 2.
  FitOptions no_trimming;
  no_trimming.asymptotic_tolerance = std::numeric_limits<double>::infinity();
  const OrderFit untrimmed = fit_order(h, error, T(0), no_trimming);
  EXPECT_TRUE(untrimmed.dropped.empty());
  EXPECT_GT(untrimmed.order, 2 + FitOptions{}.asymptotic_tolerance);
}

TYPED_TEST(OrderFitTest, NeverTrimsBelowTheMinimumNumberOfPoints) {
  using T = TypeParam;
  // Three points, the first pre-asymptotic: dropping it would leave 2 < minimum_points.
  const std::vector<T> h = steps_from<T>({"1", "0.001", "0.0001"});
  std::vector<T> error;
  using std::pow;
  for (const T& step : h) error.push_back(pow(step, 2) + from_decimal<T>("1e6") * pow(step, 5));
  const OrderFit fit = fit_order(h, error, T(0));
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_EQ(fit.used.size(), 3u);
  FitOptions two;
  two.minimum_points = 2;
  EXPECT_EQ(fit_order(h, error, T(0), two).used.size(), 2u);
}

TYPED_TEST(OrderFitTest, TwoPointsGiveAnOrderWithAnUnboundedInterval) {
  using T = TypeParam;
  const std::vector<T> h = steps_from<T>({"0.3", "0.1"});
  const OrderFit fit = fit_order(h, power_law(h, T(1), T(2), T(0)), T(0));
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_NEAR(fit.order, 2, kRounding);
  EXPECT_TRUE(std::isnan(fit.standard_error));
  EXPECT_EQ(fit.confidence_low, -std::numeric_limits<double>::infinity());
  EXPECT_EQ(fit.confidence_high, std::numeric_limits<double>::infinity());
}

// Two points above the floor and the rest hidden below it: their one pairwise order (1.44 here,
// against a predicted 4) is inconclusive, not a failure, for the hidden points could show the
// slope still on its way. Negative controls: the same two points with nothing hidden (a sweep of
// two) fail; so do four points of an order-1 error above the floor.
TYPED_TEST(OrderFitTest, TwoPointsAboveTheFloorCannotRefuteAnOrder) {
  using T = TypeParam;
  using std::pow;
  const std::vector<T> h = geometric_steps<T>("0.125", "2", 4);
  const std::vector<T> error = {from_decimal<T>("1.74e-8"),
                                T(from_decimal<T>("1.74e-8") / pow(T(2), from_decimal<T>("1.44"))),
                                from_decimal<T>("6.1e-10"), from_decimal<T>("4.5e-11")};
  const OrderVerdict hidden =
      judge_order(fit_order(h, error, from_decimal<T>("2.2e-9")), 4, false, 0.2);
  EXPECT_FALSE(hidden.holds) << hidden.explanation;
  EXPECT_TRUE(hidden.inconclusive) << hidden.explanation;
  EXPECT_TRUE(contains(hidden.explanation, "from two points")) << hidden.explanation;
  const std::vector<T> two(h.begin(), h.begin() + 2), two_errors(error.begin(), error.begin() + 2);
  const OrderVerdict sweep_of_two =
      judge_order(fit_order(two, two_errors, from_decimal<T>("2.2e-9")), 4, false, 0.2);
  expect_fails(sweep_of_two);
  const OrderVerdict order_one = judge_order(
      fit_order(h, power_law(h, T(1), T(1), T(0)), from_decimal<T>("2.2e-9")), 4, false, 0.2);
  expect_fails(order_one);
}

TYPED_TEST(OrderFitTest, ZeroErrorsAreDroppedAndLeaveTheirPairwiseOrderUndefined) {
  using T = TypeParam;
  const std::vector<T> h = steps_from<T>({"0.1", "0.06", "0.04", "0.025", "0.015"});
  std::vector<T> error = power_law(h, T(1), T(1), T(0));
  error[2] = 0;
  const OrderFit fit = fit_order(h, error, T(0));
  ASSERT_TRUE(fit.ok) << fit.reason;
  ASSERT_EQ(fit.dropped.size(), 1u);
  EXPECT_EQ(fit.dropped[0], DroppedPoint(2, "zero error"));
  EXPECT_TRUE(std::isnan(fit.pairwise_orders[1]));
  EXPECT_TRUE(std::isnan(fit.pairwise_orders[2]));
  EXPECT_NEAR(fit.order, 1, kRounding);
}

// A refined sweep: e = h²(1 + h), pairwise orders 2 + O(h) all within the median rule's 0.25,
// so without asymptote_tolerance every point stays; with 0.05 the leading points more than
// 0.05 from the finest pairwise order are dropped as pre-asymptotic and the fit moves toward 2.
TYPED_TEST(OrderFitTest, RefinedSweepDropsLeadingPointsFarFromTheFinestOrder) {
  using T = TypeParam;
  const std::vector<T> h = geometric_steps<T>("0.5", "2", 9);
  const std::vector<T> error = power_law(h, T(1), T(2), T(1));
  const OrderFit plain = fit_order(h, error, T(0));
  FitOptions refined_options;
  refined_options.asymptote_tolerance = 0.05;
  const OrderFit refined = fit_order(h, error, T(0), refined_options);
  ASSERT_TRUE(plain.ok && refined.ok);
  EXPECT_TRUE(plain.dropped.empty());
  EXPECT_FALSE(refined.dropped.empty());
  EXPECT_TRUE(contains(refined.dropped.front().second, "pre-asymptotic in the refined sweep"));
  EXPECT_LT(std::fabs(refined.order - 2), std::fabs(plain.order - 2));
}

// ---------------------------------------------------------------- MPFR beyond long double

TEST(OrderFitMpfr, ErrorsBelowTheRangeOfLongDoubleStillFit) {
  PrecisionGuard guard(100);
  // h_k = 10^−(1500 + 37k): e = h^3.5 = 10^−(5250 + 129.5k), from 1e-5250 to 1e-6415.5, all
  // below long double's 1e-4951. The logs are taken in MPFR, so only their values (~ −14000,
  // kept to 1e-15 by long double) leave MPFR.
  std::vector<mpfr_real> h;
  std::vector<int> at_floor;  // e <= 1e-6000
  for (int k = 0; k < 10; ++k) {
    h.push_back(from_decimal<mpfr_real>("1e-" + std::to_string(1500 + 37 * k)));
    if (5250 + 129.5 * k >= 6000) at_floor.push_back(k);
  }
  const mpfr_real floor = from_decimal<mpfr_real>("1e-6000");
  const OrderFit fit =
      fit_order(h, power_law(h, mpfr_real(1), mpfr_real(7) / 2, mpfr_real(0)), floor);
  ASSERT_TRUE(fit.ok) << fit.reason;
  EXPECT_NEAR(fit.order, 3.5, 1e-9);
  EXPECT_EQ(indices_of(fit.dropped), at_floor);
  EXPECT_TRUE(contains(fit.dropped.back().second, "<= floor 1e-6000")) << fit.dropped.back().second;
}

}  // namespace
}  // namespace vivv

#include "harness/verdicts/series.hpp"

namespace vivv {
namespace {

// A series whose measured value is not finite at some h is refused (std::domain_error, exit 2
// in vivv run) instead of fitted: an infinite error once fitted into an order, a NaN one read as 0.
TEST(SeriesOfErrors, RefusesANonFiniteError) {
  const std::vector<double> h = {0.5, 0.25, 0.125};
  const std::vector<double> finite = {0.25, 0.0625, 0.015625};
  EXPECT_NO_THROW(make_series<double>("e", h, finite, 1e-14, 2.0, false, 0.2));
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    std::vector<double> error = finite;
    error[1] = bad;
    EXPECT_THROW(make_series<double>("e", h, error, 1e-14, 2.0, false, 0.2), std::domain_error);
  }
}

}  // namespace
}  // namespace vivv

namespace vivv {
namespace {

// The floor keeps rounding and the reference apart (harness/verdicts/series.hpp). Errors below a floor of
// 1e-7:
// - the reference sets that floor (its tolerance): inconclusive, naming the digits that would
//   resolve the smallest error (an order-4 rule declared order 8 once passed this way);
// - the working precision sets it and the errors are above its rounding level 1e-10: inconclusive;
// - every error at the rounding level and the reference no limit: vanishes, a lower bound holds,
//   an exact order cannot be confirmed (inconclusive).
TEST(SeriesOfErrors, ErrorsBelowAFloorAreInconclusiveUnlessTheyVanishToRounding) {
  const std::vector<double> h = {1.0 / 512, 1.0 / 1024, 1.0 / 2048};
  const std::vector<double> falling = {4.8e-12, 3.0e-13, 1.9e-14};
  const std::vector<double> between = {4.8e-8, 3.0e-9, 1.9e-10};  // below 1e-7, above 1e-7 / 1000
  const Floor<double> reference_floor{1e-10, 1e-7, 1, 2048};
  const Series by_reference = make_series<double>("e", h, falling, reference_floor, 8.0, true, 0.2);
  ASSERT_TRUE(by_reference.holds.has_value());
  EXPECT_FALSE(*by_reference.holds);
  EXPECT_TRUE(by_reference.inconclusive);
  EXPECT_NE(by_reference.explanation.find("which the reference's accuracy sets"), std::string::npos)
      << by_reference.explanation;
  EXPECT_NE(by_reference.to_decide.find("\"digits\": "), std::string::npos)
      << by_reference.to_decide;
  // 1000 x max(1e10, 2 N) x 10^-D <= 1.9e-14 / 1000: D >= 10 + 6 + 14 - log10(1.9) = 29.7.
  EXPECT_NE(by_reference.to_decide.find("\"digits\": 30"), std::string::npos)
      << by_reference.to_decide;

  const Floor<double> rounding_floor{1e-7, 0, 1, 2048};
  const Series by_rounding = make_series<double>("e", h, between, rounding_floor, 2.0, false, 0.2);
  EXPECT_TRUE(by_rounding.inconclusive) << by_rounding.explanation;
  EXPECT_NE(by_rounding.explanation.find("between the floor and the rounding level"),
            std::string::npos)
      << by_rounding.explanation;

  const std::vector<double> vanishing = {3e-11, 1e-11, 5e-12};  // below 1e-7 / 1000
  const Series vanishes = make_series<double>("e", h, vanishing, rounding_floor, 2.0, false, 0.2);
  ASSERT_TRUE(vanishes.holds.has_value());
  EXPECT_TRUE(*vanishes.holds) << vanishes.explanation;
  EXPECT_FALSE(vanishes.inconclusive);
  EXPECT_TRUE(make_series<double>("e", h, vanishing, rounding_floor, 2.0, true, 0.2).inconclusive);
  // With the reference the limit, even errors at the rounding level do not vanish; errors of
  // exactly 0 have no logarithm, and the advice is the most digits a case may use.
  EXPECT_TRUE(
      make_series<double>("e", h, vanishing, reference_floor, 2.0, false, 0.2).inconclusive);
  const Series zeros =
      make_series<double>("e", h, std::vector<double>(3, 0.0), reference_floor, 2.0, false, 0.2);
  EXPECT_TRUE(zeros.inconclusive);
  EXPECT_NE(zeros.to_decide.find("\"digits\": 1000"), std::string::npos) << zeros.to_decide;

  // A program that computes in double ("precision": "double") is refused any other scalar or
  // digits: what would decide names only what its case accepts, larger steps.
  for (Floor<double> fixed : {reference_floor, rounding_floor}) {
    fixed.precision_fixed = true;
    const Series in_double = make_series<double>("e", h, between, fixed, 2.0, false, 0.2);
    EXPECT_TRUE(in_double.inconclusive) << in_double.explanation;
    EXPECT_EQ(in_double.to_decide.find("\"digits\""), std::string::npos) << in_double.to_decide;
    EXPECT_EQ(in_double.to_decide.find("mpfr"), std::string::npos) << in_double.to_decide;
    EXPECT_NE(in_double.to_decide.find("larger steps"), std::string::npos) << in_double.to_decide;
  }
}

// conclude(): a failing series makes the claim fail and decides it, even beside an
// inconclusive one; an inconclusive series alone makes it inconclusive; the claim carries the
// decisive series' index and detection limit.
TEST(SeriesOfErrors, AFailureOutranksAnInconclusiveSeriesAndDecidesTheClaim) {
  Series passing, undecided, failing;
  passing.label = "a", passing.holds = true, passing.detection_limit = "limit a";
  undecided.label = "b", undecided.holds = false, undecided.inconclusive = true,
  undecided.explanation = "why b";
  undecided.detection_limit = "limit b";
  failing.label = "c", failing.holds = false, failing.explanation = "why c",
  failing.detection_limit = "limit c";
  ClaimResult both;
  both.series = {passing, undecided, failing};
  conclude(both);
  EXPECT_EQ(both.verdict, "fail");
  EXPECT_EQ(both.decisive_series, 2);
  EXPECT_EQ(both.detection_limit, "limit c");
  EXPECT_EQ(both.explanation, "c: why c");
  ClaimResult open;
  open.series = {passing, undecided};
  conclude(open);
  EXPECT_EQ(open.verdict, "inconclusive");
  EXPECT_EQ(open.decisive_series, 1);
  ClaimResult holds;
  holds.series = {passing};
  conclude(holds);
  EXPECT_EQ(holds.verdict, "pass");
  EXPECT_EQ(holds.decisive_series, 0);
  EXPECT_EQ(holds.detection_limit, "limit a");
}

}  // namespace
}  // namespace vivv
