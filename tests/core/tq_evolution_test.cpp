#include "core/tq_evolution.hpp"

#include "cases/systems.hpp"
#include "core/del_evolution.hpp"
#include "references/gauss_legendre.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

template <class T>
class TQEvolutionTest : public testing::ScalarTest<T> {
 protected:
  static TQDiscretization<T> pulled_back(QxQRule rule, const T& theta, std::optional<TwinTerm<T>> twin = {}) {
    TQDiscretization<T> d;
    d.theta = theta;
    d.lagrangian = TQLagrangianKind::pullback;
    d.qxq.rule = rule;
    d.qxq.twin = twin;
    return d;
  }
};
TYPED_TEST_SUITE(TQEvolutionTest, testing::Scalars, testing::ScalarNames);

// Paper §2.4: in TQ form (linear psi, θ = 0, L_h(q, v) = h L(q, v) + a h² v) the
// TQ Legendre transforms are the printed F±L_h at q− = q, q+ = q + h v.
TYPED_TEST(TQEvolutionTest, PaperExampleTQLegendreTransformsAreThePrintedOnes) {
  using T = TypeParam;
  using std::sin;
  PaperExample<T> system;
  T a = T(3) / 2, h = T(1) / 16;
  auto d = this->pulled_back(QxQRule::left_rectangle, T(0), TwinTerm<T>{{a}, 1});
  TangentPoint<T, 1> v{{T(1) / 2}, {T(3) / 4}};
  auto legendre = tq_legendre(system, d, v, h);
  T q = v.q[0], delta = h * v.w[0];
  T g = system.g(q), dg = 2 * system.g2 * q, dV = system.k * sin(q);
  T f_plus = g * delta / h + a * h;
  T f_minus = g * delta / h + h * dV + a * h - dg * delta * delta / (2 * h);
  EXPECT_LE(abs(T(legendre.p_plus[0] - f_plus)), this->working_tolerance() * 16);
  EXPECT_LE(abs(T(legendre.p_minus[0] - f_minus)), this->working_tolerance() * 16);
}

// Lemma 6.1: for L_h pulled back from L_d, Psi(v) = (d−(v), d+(v)) conjugates
// the TQ evolution to the Q×Q DEL: Psi(F_h(v)) = (q_1, q_2).
TYPED_TEST(TQEvolutionTest, PulledBackEvolutionIsConjugateToTheDel) {
  using T = TypeParam;
  ChargedParticle<T> system;
  for (QxQRule rule : {QxQRule::left_rectangle, QxQRule::midpoint, QxQRule::trapezoid}) {
    for (T theta : {T(0), T(1) / 2, T(1)}) {
      auto d = this->pulled_back(rule, theta);
      T h = T(1) / 10;
      State<T, 2> v{Vector<T, 2>(T(1), T(1) / 2), Vector<T, 2>(T(1) / 4, T(-1) / 2)};
      auto step = tq_step(system, d, v, h);
      ASSERT_TRUE(step.report.converged) << step.report.failure;
      TangentPoint<T, 2> before{{v.q[0], v.q[1]}, {v.w[0], v.w[1]}};
      TangentPoint<T, 2> after{{step.next.q[0], step.next.q[1]}, {step.next.w[0], step.next.w[1]}};
      auto q0 = d_minus<T, 2>(d, before, h), q1 = d_plus<T, 2>(d, before, h);
      auto [q2, report] = del_step(system, matched_scheme(d.qxq), Vector<T, 2>(q0[0], q0[1]),
                                   Vector<T, 2>(q1[0], q1[1]), h);
      ASSERT_TRUE(report.converged);
      auto next_minus = d_minus<T, 2>(d, after, h), next_plus = d_plus<T, 2>(d, after, h);
      for (int i = 0; i < 2; ++i) {
        EXPECT_LE(abs(T(next_minus[i] - q1[i])), this->working_tolerance() * 16);
        EXPECT_LE(abs(T(next_plus[i] - q2[i])), this->working_tolerance() * 16);
      }
    }
  }
}

// Theorem 4.2: F_h(v) − v = O(h), and the h → 0 limit is the identity.
TYPED_TEST(TQEvolutionTest, EvolutionIsNearIdentityForSmallSteps) {
  using T = TypeParam;
  Pendulum<T> system;
  TQDiscretization<T> d;
  d.theta = T(1) / 2;
  auto rule = gauss_legendre<T>(4);
  d.nodes = rule.nodes;
  d.weights = rule.weights;
  State<T, 1> v{Vector<T, 1>(T(1)), Vector<T, 1>(T(2))};
  T previous = 1;
  for (int k = 4; k <= 12; k += 4) {
    T h = T(1) / (1 << k);
    auto step = tq_step(system, d, v, h);
    ASSERT_TRUE(step.report.converged) << step.report.failure;
    T distance = state_distance(step.next, v);
    EXPECT_LE(distance, 4 * h);  // |q̃ − q| ≈ h|w|, |w̃ − w| ≈ h |sin q|
    EXPECT_LT(distance, previous);
    previous = distance;
  }
}

}  // namespace
}  // namespace vivv
