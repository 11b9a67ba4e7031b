// The flow's Jacobian from the Taylor variational equations (issue 3): the
// harmonic oscillator's closed form, central differences of the Taylor flow at
// 400 bits, and symplecticity (det DF_t = 1 for n = 1, DF_tᵀ Ω DF_t = Ω in (q, p)).
#include "references/taylor_variational_flow.hpp"

#include <gtest/gtest.h>

#include "cases/systems.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

using testing::ten_to_minus;

TEST(TaylorVariationalFlowTest, HarmonicOscillatorJacobianIsTheRotation) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  HarmonicOscillator<T> oscillator;
  oscillator.omega = T(3) / 2;
  TaylorVariationalFlow<HarmonicOscillator<T>> flow(oscillator, ten_to_minus<T>(53));
  State<T, 1> start;
  start.q[0] = T(1) / 3;
  start.w[0] = T(-2);
  for (const T& t : {T(7), T(-2) / 3}) {
    auto result = flow.advance(start, t);
    const T& omega = oscillator.omega;
    Matrix<T, 2, 2> expected;
    expected << cos(omega * t), sin(omega * t) / omega, -omega * sin(omega * t), cos(omega * t);
    EXPECT_LE((result.jacobian - expected).cwiseAbs().maxCoeff(), ten_to_minus<T>(50)) << t;
  }
}

// DF_t(v) against central differences of F_t with step δ = 1e-30 (error δ² ~ 1e-60).
template <class System>
void expect_jacobian_matches_differences(const System& system,
                                         const State<mpfr_real, System::dimension>& start) {
  using T = mpfr_real;
  constexpr int n = System::dimension;
  const T step_tolerance = ten_to_minus<T>(100);
  TaylorVariationalFlow<System> variational(system, step_tolerance);
  TaylorFlow<System> flow(system, step_tolerance);
  const T t = T(3);
  auto result = variational.advance(start, t);
  EXPECT_LE((state_distance<T, n>(result.state, flow.advance(start, t))), ten_to_minus<T>(95));
  const T delta = ten_to_minus<T>(30);
  for (int j = 0; j < 2 * n; ++j) {
    State<T, n> plus = start, minus = start;
    (j < n ? plus.q[j] : plus.w[j - n]) += delta;
    (j < n ? minus.q[j] : minus.w[j - n]) -= delta;
    State<T, n> f_plus = flow.advance(plus, t), f_minus = flow.advance(minus, t);
    for (int i = 0; i < n; ++i) {
      T dq = (f_plus.q[i] - f_minus.q[i]) / (2 * delta);
      T dw = (f_plus.w[i] - f_minus.w[i]) / (2 * delta);
      EXPECT_LE(abs(result.jacobian(i, j) - dq), ten_to_minus<T>(55)) << i << "," << j;
      EXPECT_LE(abs(result.jacobian(n + i, j) - dw), ten_to_minus<T>(55)) << i << "," << j;
    }
  }
}

TEST(TaylorVariationalFlowTest, JacobianMatchesCentralDifferencesAt400Bits) {
  PrecisionGuard guard(121);
  using T = mpfr_real;
  State<T, 1> one;
  one.q[0] = T(7) / 10;
  one.w[0] = T(-3) / 10;
  expect_jacobian_matches_differences(PaperExample<T>{}, one);
  one.w[0] = T(1) / 2;
  expect_jacobian_matches_differences(RelativisticParticle<T>{}, one);
  State<T, 2> two;
  two.q << T(3) / 10, T(-1) / 5;
  two.w << T(1) / 10, T(2) / 5;
  expect_jacobian_matches_differences(ChargedParticle<T>{}, two);
}

TEST(TaylorVariationalFlowTest, FlowIsSymplectic) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(50);
  // n = 1 and p = g(q) w: d(q, p)/d(q0, p0) has determinant 1, i.e. det DF_t = g(q0)/g(q_t).
  PaperExample<T> paper;
  TaylorVariationalFlow<PaperExample<T>> flow(paper, ten_to_minus<T>(53));
  State<T, 1> start;
  start.q[0] = T(7) / 10;
  start.w[0] = T(-3) / 10;
  auto result = flow.advance(start, T(10));
  T ratio = paper.g(start.q[0]) / paper.g(result.state.q[0]);
  EXPECT_LE(abs(result.jacobian.determinant() - ratio), tolerance);
  // Charged particle: p = w + (B/2)(−q2, q1), so d(q, p)/d(q, w) = [[I, 0], [B/2 J, I]].
  ChargedParticle<T> charged;
  charged.B = T(3) / 2;
  TaylorVariationalFlow<ChargedParticle<T>> flow2(charged, ten_to_minus<T>(53));
  State<T, 2> two;
  two.q << T(3) / 10, T(-1) / 5;
  two.w << T(1) / 10, T(2) / 5;
  auto result2 = flow2.advance(two, T(10));
  Matrix<T, 4, 4> to_momenta = Matrix<T, 4, 4>::Identity();
  to_momenta(2, 1) = -charged.B / 2;
  to_momenta(3, 0) = charged.B / 2;
  Matrix<T, 4, 4> symplectic_map = to_momenta * result2.jacobian * to_momenta.inverse();
  Matrix<T, 4, 4> omega = Matrix<T, 4, 4>::Zero();
  omega.block(0, 2, 2, 2) = Matrix<T, 2, 2>::Identity();
  omega.block(2, 0, 2, 2) = -Matrix<T, 2, 2>::Identity();
  Matrix<T, 4, 4> defect = symplectic_map.transpose() * omega * symplectic_map - omega;
  EXPECT_LE(defect.cwiseAbs().maxCoeff(), tolerance);
}

}  // namespace
}  // namespace vivv
