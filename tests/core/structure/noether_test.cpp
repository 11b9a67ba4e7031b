// The discrete Noether theorem and the energy of a discrete trajectory, in
// double, quad and MPFR: the midpoint DEL of a rotation invariant Lagrangian
// conserves p_k · ξ(q_k) to rounding over a thousand steps; a Lagrangian that
// declares the rotation but breaks it does not (the negative control); the
// inverse Legendre transform inverts p = ∂L/∂w where the mass matrix depends on q.
#include "core/structure/noether.hpp"

#include <gtest/gtest.h>

#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/structure/energy.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(NoetherTest, Scalars);

// Kepler with a term ε q1² in its potential that rotations do not leave alone, declaring
// the rotation anyway.
template <class T>
struct BrokenKepler : Kepler<T> {
  T epsilon = T(1) / 100;
  template <class S>
  S lagrangian(const Point<S, 2>& q, const Point<S, 2>& w) const {
    return Kepler<T>::lagrangian(q, w) - epsilon * q[0] * q[0];
  }
};

// max_k |J_k − J_0| along N midpoint DEL steps from an eccentric Kepler state, and the
// largest |p_k|·|ξ(q_k)|.
template <class System>
std::pair<typename System::Scalar, typename System::Scalar> momentum_map_drift(const System& system, int N) {
  using T = typename System::Scalar;
  using std::abs;
  using std::max;
  QxQDiscretization<T> midpoint;
  midpoint.rule = QxQRule::midpoint;
  const T h = T(1) / 50;
  Vector<T, 2> q0(T(1) / 2, T(0)), q1(T(1) / 2, T(3) / 2 * h);
  const auto trajectory = del_trajectory(system, matched_scheme(midpoint), q0, q1, h, N);
  T first = 0, drift = 0, size = 0;
  for (int k = 0; k < N; ++k) {
    const Vector<T, 2> p = discrete_legendre(system, midpoint, trajectory.q[k], trajectory.q[k + 1], h).p_begin;
    const T J = momentum_map(system, trajectory.q[k], p);
    if (k == 0) first = J;
    drift = max(drift, T(abs(T(J - first))));
    size = max(size, T(p.cwiseAbs().maxCoeff() * symmetry_generator(system, trajectory.q[k]).cwiseAbs().maxCoeff()));
  }
  return {drift, size};
}

TYPED_TEST(NoetherTest, MidpointConservesTheAngularMomentumOfKepler) {
  using T = TypeParam;
  const int N = 1000;
  auto [drift, size] = momentum_map_drift(Kepler<T>{}, N);
  EXPECT_LE(drift, N * 1024 * epsilon<T>() * size) << to_decimal<T>(drift);
  EXPECT_TRUE(has_symmetry(Kepler<T>{}));
  EXPECT_FALSE(has_symmetry(HenonHeiles<T>{}));
}

TYPED_TEST(NoetherTest, ABrokenSymmetryDrifts) {
  using T = TypeParam;
  const int N = 1000;
  auto [drift, size] = momentum_map_drift(BrokenKepler<T>{}, N);
  EXPECT_GT(drift, T(1) / 1000) << to_decimal<T>(drift);  // far above any rounding
}

TYPED_TEST(NoetherTest, InverseLegendreRecoversTheVelocityOfTheDoublePendulum) {
  using T = TypeParam;
  DoublePendulum<T> system;
  system.m2 = T(3) / 2;
  const Vector<T, 2> q(T(7) / 10, T(-12) / 10), w(T(-3) / 10, T(9) / 10);
  const Vector<T, 2> p = momentum(system, q, w);
  const Vector<T, 2> recovered = velocity_for_momentum(system, q, p, Vector<T, 2>::Zero());
  EXPECT_LE(T((recovered - w).cwiseAbs().maxCoeff()), this->working_tolerance());
}

}  // namespace
}  // namespace vivv
