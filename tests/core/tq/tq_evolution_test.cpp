#include "core/tq/tq_evolution.hpp"

#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/lagrangian/euler_lagrange_tape.hpp"
#include "references/closed_forms.hpp"
#include "core/numerics/quadrature.hpp"
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
  // Linear psi (or exact / taylor-r when `psi` says so) with an m-point Gauss–Legendre action.
  static TQDiscretization<T> quadrature(const Pendulum<T>& system, CurveFamily psi, const T& theta, int nodes,
                                        int r = 1) {
    TQDiscretization<T> d;
    d.psi = psi;
    d.r = r;
    d.theta = theta;
    d.acceleration = std::make_shared<const Tape<T>>(euler_lagrange_tape(system));
    d.curve_tolerance = testing::reference_tolerance<T>() / 1000;
    auto rule = gauss_legendre<T>(nodes);
    d.nodes = rule.nodes;
    d.weights = rule.weights;
    return d;
  }
};
TYPED_TEST_SUITE(TQEvolutionTest, testing::Scalars, testing::ScalarNames);

// θ = 0 puts the segment on [0, h]: d−(v) = psi(h, 0, v) = q for every curve family; θ = 1 puts
// it on [−h, 0]: d+(v) = q. At θ = 1/2 neither boundary point is q (the negative control: a
// swapped θ ↔ 1 − θ is seen).
TYPED_TEST(TQEvolutionTest, ThetaZeroStartsTheSegmentAtTheBasePoint) {
  using T = TypeParam;
  using std::abs;
  Pendulum<T> system;
  TangentPoint<T, 1> v{{T(7) / 10}, {T(-1) / 3}};
  const T h = T(1) / 4;
  for (auto [psi, r] : {std::pair{CurveFamily::linear, 1}, std::pair{CurveFamily::taylor, 3}}) {
    auto at_zero = this->quadrature(system, psi, T(0), 2, r);
    auto at_one = this->quadrature(system, psi, T(1), 2, r);
    auto at_half = this->quadrature(system, psi, T(1) / 2, 2, r);
    EXPECT_LE(abs(T(d_minus<T, 1>(at_zero, v, h)[0] - v.q[0])), this->working_tolerance());
    EXPECT_LE(abs(T(d_plus<T, 1>(at_one, v, h)[0] - v.q[0])), this->working_tolerance());
    EXPECT_GT(abs(T(d_minus<T, 1>(at_half, v, h)[0] - v.q[0])), h / 100);
    EXPECT_GT(abs(T(d_plus<T, 1>(at_half, v, h)[0] - v.q[0])), h / 100);
    // And the other end lies h along the curve: d+ at θ = 0 is d− at θ = 1 shifted by the
    // whole interval, so for the linear curve d+(θ = 0) − d−(θ = 1) = 2 h w.
    if (psi == CurveFamily::linear) {
      EXPECT_LE(abs(T(d_plus<T, 1>(at_zero, v, h)[0] - d_minus<T, 1>(at_one, v, h)[0] - 2 * h * v.w[0])),
                this->working_tolerance());
    }
  }
}

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

// Theorem 5.3: the exact discretization (exact psi, its action by Gauss–Legendre on every
// Taylor piece) evolves by the flow itself, here at the large step h = 1/2, against the
// pendulum's closed form. Negative control: the exact psi with a 2-node action misses the
// flow by more than a million times the exact discretization's error.
TYPED_TEST(TQEvolutionTest, ExactDiscretizationEvolvesByTheFlow) {
  using T = TypeParam;
  Pendulum<T> system;
  const T tolerance = testing::reference_tolerance<T>();
  auto exact = this->quadrature(system, CurveFamily::exact, T(1) / 2, 1);
  exact.lagrangian = TQLagrangianKind::exact;
  auto rule = gauss_legendre<T>(taylor_order_for(exact.curve_tolerance) / 2 + 4);
  exact.nodes = rule.nodes, exact.weights = rule.weights;
  auto two_nodes = this->quadrature(system, CurveFamily::exact, T(1) / 2, 2);
  State<T, 1> v{Vector<T, 1>(T(11) / 10), Vector<T, 1>(T(1) / 4)};
  const T h = T(1) / 2;
  auto step = tq_step(system, exact, v, h);
  ASSERT_TRUE(step.report.converged) << step.report.failure;
  State<T, 1> flow = pendulum_flow(system, v, h);
  T error = state_distance(step.next, flow);
  EXPECT_LE(error, 10 * tolerance);
  auto broken = tq_step(system, two_nodes, v, h);
  ASSERT_TRUE(broken.report.converged) << broken.report.failure;
  EXPECT_GT(state_distance(broken.next, flow), 1000000 * std::max<T>(error, epsilon<T>()));
}

// Proof of Theorem 5.4: at fixed end points the critical pairs of linear psi and taylor-2
// psi (order-1 contact) differ by O(h) with equal leading coefficients at v and ṽ, so
// halving h halves Δw and quarters Δw − Δw̃. Negative control: a twin term on the past
// segment only (a mismatched pair) leaves Δw − Δw̃ of order 1.
TYPED_TEST(TQEvolutionTest, CriticalPairsHaveASymmetricResidual) {
  using T = TypeParam;
  using std::log2;
  Pendulum<T> system;
  auto linear = this->quadrature(system, CurveFamily::linear, T(0), 4);
  auto taylor = this->quadrature(system, CurveFamily::taylor, T(0), 4, 2);
  auto twin_past = linear;
  twin_past.twin = TwinTerm<T>{{T(1)}, 1};
  State<T, 1> start{Vector<T, 1>(T(11) / 10), Vector<T, 1>(T(1) / 4)};
  auto measure = [&](const TQDiscretization<T>& past, const T& h) {
    Vector<T, 1> q_minus = start.q, q_plus = pendulum_flow(system, start, T(2 * h)).q;
    auto one = tq_critical_pair(system, past, linear, q_minus, q_plus, h);
    auto two = tq_critical_pair(system, taylor, taylor, q_minus, q_plus, h);
    EXPECT_TRUE(one.report.converged && two.report.converged);
    T dw = two.v.w[0] - one.v.w[0], dw_next = two.v_next.w[0] - one.v_next.w[0];
    return std::pair<T, T>{abs(dw), abs(T(dw - dw_next))};
  };
  T h = T(1) / 64;
  auto [coarse, coarse_residual] = measure(linear, h);
  auto [fine, fine_residual] = measure(linear, T(h / 2));
  EXPECT_NEAR(static_cast<double>(log2(T(coarse / fine))), 1.0, 0.1);
  EXPECT_NEAR(static_cast<double>(log2(T(coarse_residual / fine_residual))), 2.0, 0.1);
  auto [mismatched, mismatched_residual] = measure(twin_past, h);
  auto [mismatched_fine, mismatched_fine_residual] = measure(twin_past, T(h / 2));
  EXPECT_NEAR(static_cast<double>(log2(T(mismatched_residual / mismatched_fine_residual))), 1.0, 0.1);
}

}  // namespace
}  // namespace vivv
