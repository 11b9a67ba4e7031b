// Systems sized at run time (any_size): a chain of n coordinates written as a formula, in double,
// long double, float128 and MPFR.
//   n = 1, 2: in MPFR, whose systems of 1 and 2 coordinates vivv runs at compile-time sizes, and in
//             double, the run-time path gives the compile-time path's numbers (values,
//             derivatives, discrete Legendre transforms and their Hessian blocks, a DEL step, the
//             Euler–Lagrange acceleration, and in MPFR an odeint step and its Jacobian), to a few
//             ulps. Each scalar costs 30 to 40 s of this file's compile time at -O0 (docs/build.md);
//             long double and float128 take double's code path and are checked at run-time size
//             below;
//   n = 7:    every derivative against central differences of values, and a DEL step solved;
//   n = 64:   first and second derivatives against differences and a DEL step solved, in every
//             scalar (from L's sparse derivatives).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/maps/odeint_map.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/qxq/discrete_lagrangian.hpp"
#include "tests/chain_formula.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

template <class T>
class AnySizeTest : public testing::ScalarTest<T> {};
TYPED_TEST_SUITE(AnySizeTest, testing::AllScalars, testing::ScalarNames);

using testing::chain;
using testing::chain_state;
using testing::distance;

template <class T, int n>
void expect_same_numbers_at_fixed_and_run_time_size() {
  const FormulaSystemDefinition definition = chain(n);
  const auto fixed = make_formula_system<T, n>(definition);
  const auto sized = make_formula_system<T, any_size>(definition);
  ASSERT_EQ(sized.size(), n);
  const T tolerance = 64 * epsilon<T>();
  const State<T, n> x = chain_state<T, n>(n);
  const State<T, any_size> y = chain_state<T, any_size>(n);

  const auto a = lagrangian_derivatives(fixed, x.q, x.w);
  const auto b = lagrangian_derivatives(sized, y.q, y.w);
  EXPECT_LE(abs(T(a.value - b.value)), tolerance);
  EXPECT_LE(distance(a.dL_dq, b.dL_dq), tolerance);
  EXPECT_LE(distance(a.dL_dw, b.dL_dw), tolerance);
  EXPECT_LE(distance(a.d2L_dw2, b.d2L_dw2), tolerance);
  EXPECT_LE(distance(a.d2L_dwdq, b.d2L_dwdq), tolerance);
  EXPECT_LE(distance(euler_lagrange_acceleration(fixed, x.q, x.w), euler_lagrange_acceleration(sized, y.q, y.w)),
            tolerance);

  QxQDiscretization<T> midpoint;
  midpoint.rule = QxQRule::midpoint;
  const T h = T(1) / 8;
  const Vector<T, n> x1 = x.q + h * x.w;
  const Vector<T, any_size> y1 = y.q + h * y.w;
  const auto c = discrete_legendre(fixed, midpoint, x.q, x1, h);
  const auto d = discrete_legendre(sized, midpoint, y.q, y1, h);
  EXPECT_LE(distance(c.p_begin, d.p_begin), tolerance);
  EXPECT_LE(distance(c.p_end, d.p_end), tolerance);
  EXPECT_LE(distance(c.dp_begin_dq_b, d.dp_begin_dq_b), tolerance);
  EXPECT_LE(distance(c.dp_begin_dq_e, d.dp_begin_dq_e), tolerance);
  EXPECT_LE(distance(c.dp_end_dq_e, d.dp_end_dq_e), tolerance);
  const auto [x2, fixed_report] = del_step(fixed, matched_scheme(midpoint), x.q, x1, h);
  const auto [y2, sized_report] = del_step(sized, matched_scheme(midpoint), y.q, y1, h);
  ASSERT_TRUE(fixed_report.converged && sized_report.converged);
  EXPECT_EQ(fixed_report.iterations, sized_report.iterations);
  EXPECT_LE(distance(x2, y2), tolerance);

  // odeint's maps come from the library's instantiations (harness/CMakeLists.txt): fixed sizes 1 and 2
  // exist in MPFR alone, the only scalar whose systems run at those sizes; the run-time size in
  // every scalar is checked against differences in tests/references/any_size_reference_test.cpp.
  if constexpr (is_mpfr_v<T>) {
    const auto fixed_map = make_odeint_map<T, n>("velocity_verlet", separable_form(fixed, x));
    const auto sized_map = make_odeint_map<T, any_size>("velocity_verlet", separable_form(sized, y));
    EXPECT_LE(distance(fixed_map->step(x, h).q, sized_map->step(y, h).q), tolerance);
    EXPECT_LE(distance(fixed_map->jacobian(x, h), sized_map->jacobian(y, h)), tolerance);
  }
}

template <class T>
class FixedAndRunTimeSizeTest : public testing::ScalarTest<T> {};
using FixedSizeScalars = ::testing::Types<double, mpfr_real>;
TYPED_TEST_SUITE(FixedAndRunTimeSizeTest, FixedSizeScalars, testing::ScalarNames);

TYPED_TEST(FixedAndRunTimeSizeTest, OneAndTwoCoordinatesGiveTheFixedSizesNumbers) {
  expect_same_numbers_at_fixed_and_run_time_size<TypeParam, 1>();
  expect_same_numbers_at_fixed_and_run_time_size<TypeParam, 2>();
}

// ∂f/∂x_i by central differences at width ε^(1/3)·max(1, |x_i|), in T: good to about ε^(2/3).
template <class T, class F>
Vector<T, any_size> differences(F&& f, const Vector<T, any_size>& x) {
  using std::abs, std::cbrt, std::max;
  Vector<T, any_size> gradient(x.size());
  for (int i = 0; i < x.size(); ++i) {
    const T width = cbrt(epsilon<T>()) * max(T(1), T(abs(x[i])));
    Vector<T, any_size> up = x, down = x;
    up[i] += width, down[i] -= width;
    gradient[i] = (f(up) - f(down)) / (up[i] - down[i]);
  }
  return gradient;
}

template <class T>
void expect_derivatives_of_values(int n, bool second_derivatives) {
  using std::cbrt;
  const auto system = make_formula_system<T, any_size>(chain(n));
  const State<T, any_size> x = chain_state<T, any_size>(n);
  const T h = T(1) / 8;
  const Vector<T, any_size> x1 = x.q + h * x.w;
  QxQDiscretization<T> midpoint;
  midpoint.rule = QxQRule::midpoint;
  const T allowed = 100 * cbrt(epsilon<T>()) * cbrt(epsilon<T>());
  const auto value = [&](const Vector<T, any_size>& q, const Vector<T, any_size>& w) {
    return T(system.lagrangian(as_point<T, any_size>(q), as_point<T, any_size>(w)));
  };
  const auto discrete = [&](const Vector<T, any_size>& b, const Vector<T, any_size>& e) {
    return T(discrete_lagrangian(system, midpoint, as_point<T, any_size>(b), as_point<T, any_size>(e), h));
  };
  // First derivatives: the momentum and p_begin, p_end from first-order jets.
  const Vector<T, any_size> p = momentum(system, x.q, x.w);
  ASSERT_EQ(p.size(), n);
  EXPECT_LE(distance(p, differences<T>([&](const auto& w) { return value(x.q, w); }, x.w)), allowed);
  const auto momenta = discrete_momenta(system, midpoint, x.q, x1, h);
  EXPECT_LE(distance(momenta.p_begin, Vector<T, any_size>(-differences<T>([&](const auto& b) { return discrete(b, x1); }, x.q))),
            allowed);
  EXPECT_LE(distance(momenta.p_end, differences<T>([&](const auto& e) { return discrete(x.q, e); }, x1)), allowed);
  if (!second_derivatives) return;
  // Second derivatives: rows of the Hessian block ∂p_begin/∂q_e (every row of a short chain; the
  // first, middle and last of a long one), and a DEL step solved.
  const auto legendre = discrete_legendre(system, midpoint, x.q, x1, h);
  ASSERT_EQ(legendre.dp_begin_dq_e.rows(), n);
  for (int j : n <= 8 ? std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7} : std::vector<int>{0, n / 2, n - 1}) {
    if (j >= n) break;
    const auto p_begin_j = [&](const Vector<T, any_size>& e) {
      return T(discrete_momenta(system, midpoint, x.q, e, h).p_begin[j]);
    };
    EXPECT_LE(distance(Vector<T, any_size>(legendre.dp_begin_dq_e.row(j).transpose()), differences<T>(p_begin_j, x1)),
              allowed * 10)
        << "row " << j;
  }
  const auto [x2, report] = del_step(system, matched_scheme(midpoint), x.q, x1, h);
  ASSERT_TRUE(report.converged);
  ASSERT_EQ(x2.size(), n);
  const Vector<T, any_size> past = p_end(system, midpoint, x.q, x1, h);
  const Vector<T, any_size> future = p_begin(system, midpoint, x1, x2, h);
  EXPECT_LE(distance(past, future), T(1024) * epsilon<T>());
}

TYPED_TEST(AnySizeTest, SevenCoordinatesDerivativesAgreeWithDifferencesOfValues) {
  expect_derivatives_of_values<TypeParam>(7, true);
}

TYPED_TEST(AnySizeTest, SixtyFourCoordinatesDerivativesAgreeWithDifferencesOfValues) {
  // Second derivatives and a DEL step in every scalar: they come from L's sparse Hessian
  // (core/qxq/sparse_legendre.hpp), not from a dense jet of 128 variables.
  expect_derivatives_of_values<TypeParam>(64, true);
}

// A run-time sized jet that stays constant until it meets a variable: its derivatives read as
// zeros once sized, and a constant times a variable is the variable scaled.
TEST(DynamicJet, ConstantsMeetVariables) {
  using J = Jet<double, any_size>;
  const J c(3.0), x = J::variable(2.0, 1, 3);
  EXPECT_TRUE(c.is_constant());
  const J product = c * x, sum = c + x, difference = c - x, quotient = c / x;
  EXPECT_EQ(product.gradient, (std::vector<double>{0, 3, 0}));
  EXPECT_EQ(sum.gradient, (std::vector<double>{0, 1, 0}));
  EXPECT_EQ(difference.gradient, (std::vector<double>{0, -1, 0}));
  EXPECT_DOUBLE_EQ(quotient.gradient[1], -3.0 / 4);
  EXPECT_DOUBLE_EQ(quotient.second(1, 1), 2 * 3.0 / 8);
  const J square = x * x;
  EXPECT_DOUBLE_EQ(square.second(1, 1), 2);
  EXPECT_DOUBLE_EQ(square.second(0, 1), 0);
  EXPECT_EQ(with_size(J(5.0), 3).gradient, (std::vector<double>{0, 0, 0}));
}

}  // namespace
}  // namespace vivv
