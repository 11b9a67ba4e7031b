// Systems sized at run time (any_size): a chain of n coordinates written as a formula, in double,
// long double, float128 and MPFR.
//   n = 1, 2: L's value and derivatives, the Euler–Lagrange acceleration, the midpoint rule's
//             discrete Legendre transforms and their Hessian blocks against the chain's closed
//             forms to a few ulps, and a DEL step solved, in every scalar (every system of every
//             size runs at the run-time size);
//   n = 7:    every derivative against central differences of values, and a DEL step solved;
//   n = 64:   first and second derivatives against differences and a DEL step solved, in every
//             scalar (from L's sparse derivatives).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/qxq/discrete_lagrangian.hpp"
#include "tests/chain_formula.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(AnySizeTest, AllScalars);

using testing::chain;
using testing::chain_state;
using testing::distance;

// The chain's numbers in closed form (M = I, no w·q coupling, S the springs' energy ½ qᵀ K q with
// K tridiagonal 2, −1; for n = 1 the two end springs are one, K = 2):
//   L = |w|²/2 − S(q) − Σ q_i⁴/4,  L_q = −K q − q³,  L_qq = −K − 3 diag(q²),  a = L_q;
// the midpoint rule, m = (q_b + q_e)/2, v = (q_e − q_b)/h:
//   p_begin = v − (h/2) L_q(m),  p_end = v + (h/2) L_q(m),
//   ∂p_begin/∂q_b = −I/h − (h/4) L_qq(m),  ∂p_begin/∂q_e = I/h − (h/4) L_qq(m),  ∂p_end/∂q_e = I/h + (h/4) L_qq(m).
template <class T>
void expect_closed_form_numbers(int n) {
  using std::abs;
  using Vec = Vector<T, any_size>;
  using Mat = Matrix<T, any_size, any_size>;
  const auto system = make_formula_system<T, any_size>(chain(n));
  ASSERT_EQ(system.size(), n);
  const T tolerance = 64 * epsilon<T>() * 16;  // entries up to 1/h = 8
  const State<T, any_size> x = chain_state<T, any_size>(n);
  Mat K = Mat::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    K(i, i) = 2;
    if (i + 1 < n) K(i, i + 1) = K(i + 1, i) = -1;
  }
  const auto L_q = [&](const Vec& q) { return Vec(-K * q - Vec(q.array().cube().matrix())); };
  const auto L_qq = [&](const Vec& q) { return Mat(-K - Mat(3 * q.array().square().matrix().asDiagonal())); };
  const Mat I = Mat::Identity(n, n);

  const auto d = lagrangian_derivatives(system, x.q, x.w);
  const T value = x.w.squaredNorm() / 2 - x.q.dot(K * x.q) / 2 - x.q.array().square().square().sum() / 4;
  EXPECT_LE(abs(T(d.value - value)), tolerance);
  EXPECT_LE(distance(d.dL_dq, L_q(x.q)), tolerance);
  EXPECT_LE(distance(d.dL_dw, x.w), tolerance);
  EXPECT_LE(distance(d.d2L_dw2, I), tolerance);
  EXPECT_LE(distance(d.d2L_dwdq, Mat(Mat::Zero(n, n))), tolerance);
  EXPECT_LE(distance(euler_lagrange_acceleration(system, x.q, x.w), L_q(x.q)), tolerance);

  QxQDiscretization<T> midpoint;
  midpoint.rule = QxQRule::midpoint;
  const T h = T(1) / 8;
  const Vec x1 = x.q + h * x.w;
  const Vec m = (x.q + x1) / 2, v = (x1 - x.q) / h;
  const auto legendre = discrete_legendre(system, midpoint, x.q, x1, h);
  EXPECT_LE(distance(legendre.p_begin, Vec(v - h / 2 * L_q(m))), tolerance);
  EXPECT_LE(distance(legendre.p_end, Vec(v + h / 2 * L_q(m))), tolerance);
  EXPECT_LE(distance(legendre.dp_begin_dq_b, Mat(-I / h - h / 4 * L_qq(m))), tolerance);
  EXPECT_LE(distance(legendre.dp_begin_dq_e, Mat(I / h - h / 4 * L_qq(m))), tolerance);
  EXPECT_LE(distance(legendre.dp_end_dq_e, Mat(I / h + h / 4 * L_qq(m))), tolerance);
  const auto [x2, report] = del_step(system, matched_scheme(midpoint), x.q, x1, h);
  ASSERT_TRUE(report.converged);
  EXPECT_LE(distance(p_end(system, midpoint, x.q, x1, h), p_begin(system, midpoint, x1, x2, h)), T(1024) * epsilon<T>());
}

TYPED_TEST(AnySizeTest, OneAndTwoCoordinatesGiveTheChainsClosedForms) {
  expect_closed_form_numbers<TypeParam>(1);
  expect_closed_form_numbers<TypeParam>(2);
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
