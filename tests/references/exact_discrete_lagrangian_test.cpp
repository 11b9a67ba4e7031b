// The exact discrete Lagrangian (docs/theory.md (Q × Q), issue 3): the harmonic
// oscillator's closed form, Legendre transforms equal to the reference momenta
// at both ends, the Hamilton–Jacobi relations p_begin = −∂L_d^E/∂q_b,
// p_end = ∂L_d^E/∂q_e by central differences, and a wrong series coefficient
// that these checks must catch.
#include "references/exact_discrete_lagrangian.hpp"

#include <gtest/gtest.h>

#include "cases/systems.hpp"
#include "references/closed_forms.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

using testing::ten_to_minus;

template <class T>
Vector<T, 1> one(const T& x) {
  Vector<T, 1> v;
  v[0] = x;
  return v;
}

TEST(ExactDiscreteLagrangianTest, HarmonicOscillatorClosedForm) {
  // L_d^E = ω ((q_b² + q_e²) cos ωh − 2 q_b q_e) / (2 sin ωh).
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(50);
  HarmonicOscillator<T> oscillator;
  oscillator.omega = T(3) / 2;
  ExactDiscreteLagrangian<HarmonicOscillator<T>> exact(oscillator, tolerance);
  const T q_b = T(1) / 3, q_e = T(-1) / 2;
  for (const T& h : {T(1) / 10, T(1), T(-3) / 2}) {
    auto result = exact(one(q_b), one(q_e), h);
    ASSERT_TRUE(result.converged);
    const T& omega = oscillator.omega;
    T expected = omega * ((q_b * q_b + q_e * q_e) * cos(omega * h) - 2 * q_b * q_e) /
                 (2 * sin(omega * h));
    EXPECT_LE(abs(result.value - expected), tolerance) << "h = " << h;
    // p_end = ∂L_d^E/∂q_e = ω (q_e cos ωh − q_b) / sin ωh.
    T p_end = omega * (q_e * cos(omega * h) - q_b) / sin(omega * h);
    EXPECT_LE(abs(result.p_end[0] - p_end), tolerance) << "h = " << h;
  }
}

// q_b = q(0), q_e = q(h) on a pendulum solution: p_begin = w(0), p_end = w(h) (p = w).
template <class T>
T pendulum_legendre_defect(ExactDiscreteLagrangian<Pendulum<T>>& exact, const T& h) {
  using std::max;
  Pendulum<T> pendulum;
  State<T, 1> start;
  start.q[0] = T(1);
  start.w[0] = T(1) / 2;
  State<T, 1> end = pendulum_flow(pendulum, start, h);
  auto result = exact(start.q, end.q, h);
  EXPECT_TRUE(result.converged);
  return max(abs(result.p_begin[0] - start.w[0]), abs(result.p_end[0] - end.w[0]));
}

TEST(ExactDiscreteLagrangianTest, LegendreTransformsAreTheReferenceMomentaAtBothEnds) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(50);
  ExactDiscreteLagrangian<Pendulum<T>> exact(Pendulum<T>{}, tolerance);
  for (const T& h : {T(1) / 100, T(1) / 2, T(2)})
    EXPECT_LE(pendulum_legendre_defect(exact, h), tolerance) << "h = " << h;
}

TEST(ExactDiscreteLagrangianTest, HamiltonJacobiRelationsHoldForThePaperExample) {
  // p_begin = −∂L_d^E/∂q_b and p_end = ∂L_d^E/∂q_e, central differences with δ = 1e-30.
  PrecisionGuard guard(121);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(100);
  PaperExample<T> paper;
  ExactDiscreteLagrangian<PaperExample<T>> exact(paper, tolerance);
  const T q_b = T(7) / 10, q_e = T(2) / 5, h = T(3) / 4;
  auto result = exact(one(q_b), one(q_e), h);
  ASSERT_TRUE(result.converged);
  const T delta = ten_to_minus<T>(30);
  T d_begin = (exact(one(T(q_b + delta)), one(q_e), h).value -
               exact(one(T(q_b - delta)), one(q_e), h).value) / (2 * delta);
  T d_end = (exact(one(q_b), one(T(q_e + delta)), h).value -
             exact(one(q_b), one(T(q_e - delta)), h).value) / (2 * delta);
  EXPECT_LE(abs(result.p_begin[0] + d_begin), ten_to_minus<T>(55));
  EXPECT_LE(abs(result.p_end[0] - d_end), ten_to_minus<T>(55));
}

TEST(ExactDiscreteLagrangianTest, NegativeControlWrongSeriesCoefficientIsCaught) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(50);
  ExactDiscreteLagrangian<Pendulum<T>> exact(Pendulum<T>{}, tolerance);
  exact.flow().integrator().expansion().fault_order = 5;
  exact.variational_flow().integrator().expansion().fault_order = 5;
  EXPECT_GT(pendulum_legendre_defect(exact, T(1) / 2), tolerance);
}

}  // namespace
}  // namespace vivv
