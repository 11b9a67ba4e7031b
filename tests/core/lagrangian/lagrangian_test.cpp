#include "core/lagrangian/lagrangian.hpp"

#include "cases/systems.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(LagrangianTest, Scalars);

// Automatic differentiation of the paper's L = ½ g(q) w² − V(q) against its
// hand-written derivatives, at random points.
TYPED_TEST(LagrangianTest, AutomaticDerivativesMatchHandWrittenOnesForThePaperExample) {
  using T = TypeParam;
  using std::cos, std::sin;
  PaperExample<T> system;
  system.set({T(3) / 2, T(1) / 3, T(2), T(1) / 5});
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial) {
    Vector<T, 1> q(this->uniform(random, -3, 3)), w(this->uniform(random, -2, 2));
    auto d = lagrangian_derivatives(system, q, w);
    T g = system.g0 + system.g2 * q[0] * q[0], dg = 2 * system.g2 * q[0];
    T dV = system.k * sin(q[0]) + system.m * q[0];
    T tolerance = this->working_tolerance() * 10;
    EXPECT_LE(abs(T(d.dL_dq[0] - (dg * w[0] * w[0] / 2 - dV))), tolerance);
    EXPECT_LE(abs(T(d.dL_dw[0] - g * w[0])), tolerance);
    EXPECT_LE(abs(T(d.d2L_dw2(0, 0) - g)), tolerance);
    EXPECT_LE(abs(T(d.d2L_dwdq(0, 0) - dg * w[0])), tolerance);
    // Euler–Lagrange: q'' = −(V' + ½ g' w²)/g (paper §2.2).
    T expected = -(dV + dg * w[0] * w[0] / 2) / g;
    EXPECT_LE(abs(T(euler_lagrange_acceleration(system, q, w)[0] - expected)), tolerance);
  }
}

// The relativistic particle is not quadratic in w: M = m (1 − w²)^(−3/2).
TYPED_TEST(LagrangianTest, RelativisticMassMatrixAndMomentum) {
  using T = TypeParam;
  using std::sqrt;
  RelativisticParticle<T> system;
  Vector<T, 1> q(T(1) / 4), w(T(3) / 5);
  auto d = lagrangian_derivatives(system, q, w);
  T gamma = 1 / sqrt(1 - w[0] * w[0]);
  T tolerance = this->working_tolerance();
  EXPECT_LE(abs(T(d.dL_dw[0] - gamma * w[0])), tolerance);
  EXPECT_LE(abs(T(d.d2L_dw2(0, 0) - gamma * gamma * gamma)), tolerance);
  EXPECT_LE(abs(T(energy(system, q, w) - (gamma + q[0] * q[0] / 2))), tolerance);
}

TYPED_TEST(LagrangianTest, ChargedParticleLorentzForce) {
  using T = TypeParam;
  ChargedParticle<T> system;
  system.set({T(2), T(1) / 2});
  Vector<T, 2> q(T(1), T(-2)), w(T(1) / 2, T(3));
  Vector<T, 2> a = euler_lagrange_acceleration(system, q, w);
  // q'' = B J w − k q with J w = (w2, −w1).
  EXPECT_LE(abs(T(a[0] - (system.B * w[1] - system.k * q[0]))), this->working_tolerance());
  EXPECT_LE(abs(T(a[1] - (-system.B * w[0] - system.k * q[1]))), this->working_tolerance());
}

// Negative control: a Lagrangian with no w² term is not regular.
template <class T>
struct Degenerate {
  using Scalar = T;
  static constexpr int dimension = 1;
  template <class S>
  S lagrangian(const Point<S, 1>& q, const Point<S, 1>& w) const {
    return q[0] * w[0] - q[0] * q[0] / 2;
  }
};

TYPED_TEST(LagrangianTest, SingularMassMatrixIsAClearError) {
  using T = TypeParam;
  Vector<T, 1> q(T(1)), w(T(1));
  EXPECT_THROW(euler_lagrange_acceleration(Degenerate<T>{}, q, w), SingularLagrangianError);
}

}  // namespace
}  // namespace vivv
