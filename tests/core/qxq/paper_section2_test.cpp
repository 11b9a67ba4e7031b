// The statements of the paper's worked example (§2.3–2.5) that are formulas
// rather than claims, checked against the code in double, quad and MPFR. Their
// names contain "Paper": ctest runs them under the label "paper" too.
//
// The example: L = ½ g(q) w² − V(q), L_h(q+, q−) = h L(q−, (q+ − q−)/h) + a h (q+ − q−)
// (left rectangle plus twin term), and in TQ form L_h(q, v) = h L(q, v) + a h² v.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/autodiff/jet.hpp"
#include "core/tq/tq_evolution.hpp"
#include "tests/core/qxq/paper_discrete_lagrangian.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

template <class T>
class PaperSection2Test : public testing::ScalarTest<T> {
 protected:

  // The example in TQ form (§2.4): linear psi, θ = 0, L_h = h L(q, v) + a h² v.
  static TQDiscretization<T> tq_example(const T& a) {
    TQDiscretization<T> d;
    d.psi = CurveFamily::linear;
    d.theta = 0;
    d.lagrangian = TQLagrangianKind::pullback;
    d.qxq.rule = QxQRule::left_rectangle;
    d.twin = testing::paper_discrete_lagrangian(a).twin;
    return d;
  }
  // Pairwise orders log(e_k/e_{k+1}) / log 2 of errors at halving steps.
  static std::vector<double> halving_orders(const std::vector<T>& errors) {
    using std::log2;
    std::vector<double> orders;
    for (std::size_t k = 0; k + 1 < errors.size(); ++k)
      orders.push_back(static_cast<double>(log2(T(errors[k] / errors[k + 1]))));
    return orders;
  }
};
TYPED_TEST_SUITE(PaperSection2Test, testing::Scalars, testing::ScalarNames);

// §2.3: with q_1 − q_0 = O(h) the DEL implies the printed second-difference form
//   (q_2 − 2q_1 + q_0)/h² = −(V'(q_0) + g'(q_0)(q_1 − q_0)²/(2h²))/g(q_0) + O(h),
// which is order 1 against the Euler–Lagrange equation q'' = −(V'(q) + g'(q) w²/2)/g(q):
// with q_1 = q_0 + h w the printed right side is the Euler–Lagrange acceleration at (q_0, w),
// and the DEL's q_2 (solved by the code) meets it at order 1. A sign slip (+ instead of −)
// stays O(1) away.
TYPED_TEST(PaperSection2Test, PaperSecondDifferenceFormIsOrderOne) {
  using T = TypeParam;
  using std::abs, std::sin;
  PaperExample<T> system;
  const T q0 = T(1) / 2, w = T(3) / 4, a = 1;
  auto g = [&](const T& q) { return system.g(q); };
  auto dg = [&](const T& q) { return 2 * system.g2 * q; };
  auto dV = [&](const T& q) { return system.k * sin(q) + system.m * q; };
  const T acceleration = -(dV(q0) + dg(q0) * w * w / 2) / g(q0);
  std::vector<T> errors;
  for (int j = 4; j <= 9; ++j) {
    const T h = T(1) / (1 << j);
    Vector<T, 1> q_0(q0), q_1(q0 + h * w);
    auto [q_2, report] = del_step(system, matched_scheme(testing::paper_discrete_lagrangian(a)), q_0, q_1, h);
    ASSERT_TRUE(report.converged) << report.failure;
    const T second_difference = (q_2[0] - 2 * q_1[0] + q_0[0]) / (h * h);
    const T delta = q_1[0] - q_0[0];
    const T printed = -(dV(q0) + dg(q0) * delta * delta / (2 * h * h)) / g(q0);
    EXPECT_LE(abs(T(printed - acceleration)), this->working_tolerance() * 4) << "h = " << h;
    const T slipped = -(-dV(q0) + dg(q0) * delta * delta / (2 * h * h)) / g(q0);
    EXPECT_GT(abs(T(second_difference - slipped)), T(1) / 2) << "a sign slip must be seen";
    errors.push_back(abs(T(second_difference - printed)));
  }
  for (double order : this->halving_orders(errors)) EXPECT_NEAR(order, 1, 0.1);
  EXPECT_LT(errors.back(), T(1) / 100);
}

// §2.5: the blown-up principle at h = 0, Ŝ_0(v) = L(q̄, v) + L(q̄, z − v), has the critical
// point v = ṽ = z/2 with second derivative 2 g(q̄) > 0 — computed by automatic
// differentiation of the code's L at random (q̄, z). A point off the diagonal is not critical.
TYPED_TEST(PaperSection2Test, PaperBlownUpPrincipleHasTheSymmetricNondegenerateCriticalPoint) {
  using T = TypeParam;
  using J = Jet<T, 1>;
  using std::abs;
  PaperExample<T> system;
  std::mt19937 random(3);
  for (int trial = 0; trial < 10; ++trial) {
    const T q_bar = this->uniform(random, -2, 2), z = this->uniform(random, -3, 3);
    auto blown_up = [&](const T& v) {
      const J velocity = J::variable(v, 0);
      return system.lagrangian(Point<J, 1>{J(q_bar)}, Point<J, 1>{velocity}) +
             system.lagrangian(Point<J, 1>{J(q_bar)}, Point<J, 1>{J(z) - velocity});
    };
    const J at_critical = blown_up(z / 2);
    EXPECT_LE(abs(at_critical.gradient[0]), this->working_tolerance() * (1 + abs(z)));
    EXPECT_LE(abs(T(at_critical.second(0, 0) - 2 * system.g(q_bar))), this->working_tolerance() * 8);
    EXPECT_GT(at_critical.second(0, 0), T(0));
    EXPECT_GT(abs(blown_up(z / 2 + T(1) / 4).gradient[0]), T(1) / 10);
  }
}

// §2.5: the critical point persists for small h and its h = 0 limit is the identity: at
// fixed q̄ = (q_0 + q_2)/2 and z = (q_2 − q_0)/h the blown-up critical pair (v, ṽ) of the
// example's TQ form tends to w = w̃ = z/2 at order 1 in h, and ṽ − v to 0 — the graph of
// the identity map.
TYPED_TEST(PaperSection2Test, PaperCriticalPointPersistsWithTheIdentityAsItsLimit) {
  using T = TypeParam;
  using std::abs, std::max;
  PaperExample<T> system;
  const T q_bar = T(1) / 2, z = T(3) / 2;
  std::vector<T> deviation, asymmetry;
  for (int j = 3; j <= 8; ++j) {
    const T h = T(1) / (1 << j);
    Vector<T, 1> q_minus(q_bar - h * z / 2), q_plus(q_bar + h * z / 2);
    auto pair = tq_critical_pair(system, this->tq_example(T(1)), this->tq_example(T(1)), q_minus, q_plus, h);
    ASSERT_TRUE(pair.report.converged) << pair.report.failure;
    deviation.push_back(max(abs(T(pair.v.w[0] - z / 2)), abs(T(pair.v_next.w[0] - z / 2))));
    asymmetry.push_back(abs(T(pair.v_next.w[0] - pair.v.w[0])));
  }
  for (double order : this->halving_orders(deviation)) EXPECT_NEAR(order, 1, 0.15);
  for (double order : this->halving_orders(asymmetry)) EXPECT_NEAR(order, 1, 0.15);
  EXPECT_LT(deviation.back(), T(1) / 50);
}

}  // namespace
}  // namespace vivv
