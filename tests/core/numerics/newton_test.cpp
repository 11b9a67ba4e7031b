// Newton's stop at the first sign of divergence (core/numerics/newton.hpp): a solve that
// cannot converge ends after a few corrections, saying which, and one that
// converges is not stopped by it.
#include "core/numerics/newton.hpp"

#include <gtest/gtest.h>

#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(NewtonTest, Scalars);

// arctan x = 0: Newton converges from |x0| below about 1.39 and runs away from above it
// (each iterate larger in size than the one before, alternating in sign).
template <class T>
SolveReport<T> solve_arctan(T& x, int* evaluations = nullptr, const NewtonOptions& options = {}) {
  Vector<T, 1> at;
  at[0] = x;
  auto report = newton_solve<T, 1>(at, [&](const Vector<T, 1>& v, Vector<T, 1>& residual, Matrix<T, 1, 1>& jacobian) {
    using std::atan;
    if (evaluations) ++*evaluations;
    residual[0] = atan(v[0]);
    jacobian(0, 0) = 1 / (1 + v[0] * v[0]);
  }, options);
  x = at[0];
  return report;
}

TYPED_TEST(NewtonTest, ConvergesFromInsideTheBasin) {
  using T = TypeParam;
  T x = T(13) / 10;
  auto report = solve_arctan(x);
  ASSERT_TRUE(report.converged) << report.failure;
  using std::abs;
  EXPECT_LE(abs(x), this->working_tolerance());
}

// The negative control: from x0 = 3 the corrections grow (about 12.5, 134, 2.4e4, …); the
// third is more than 16 times the first and the solve stops there instead of running its
// 60 iterations.
TYPED_TEST(NewtonTest, StopsAtTheFirstSignOfDivergence) {
  using T = TypeParam;
  T x = 3;
  int evaluations = 0;
  auto report = solve_arctan(x, &evaluations);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(evaluations, 3);
  EXPECT_NE(report.failure.find("diverging"), std::string::npos) << report.failure;
  EXPECT_NE(report.failure.find("corrections"), std::string::npos) << report.failure;
  EXPECT_EQ(static_cast<int>(report.corrections.size()), report.iterations);
  // With the stop switched off, the same start runs to the iteration limit (or overflows).
  NewtonOptions patient;
  patient.runaway_factor = 1 << 30;
  patient.stagnation_limit = 1000;
  T patient_x = 3;
  int patient_evaluations = 0;
  auto patient_report = solve_arctan(patient_x, &patient_evaluations, patient);
  EXPECT_FALSE(patient_report.converged);
  EXPECT_GT(patient_evaluations, evaluations);
}

// Corrections that neither grow nor shrink: Newton on F = x³ − 2x + 2 from 0 cycles
// 0 → 1 → 0 → … with every correction 1; the third in a row not below the first stops it.
TYPED_TEST(NewtonTest, StopsWhenTheCorrectionsStopShrinking) {
  using T = TypeParam;
  Vector<T, 1> at;
  at[0] = 0;
  int evaluations = 0;
  auto report = newton_solve<T, 1>(at, [&](const Vector<T, 1>& v, Vector<T, 1>& residual, Matrix<T, 1, 1>& jacobian) {
    ++evaluations;
    residual[0] = v[0] * v[0] * v[0] - 2 * v[0] + 2;
    jacobian(0, 0) = 3 * v[0] * v[0] - 2;
  });
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(evaluations, 4);
  EXPECT_NE(report.failure.find("not converging"), std::string::npos) << report.failure;
}

// A formula outside its domain — √(x − 5) at x = 1 — is named as such, not as a singular
// Jacobian (which once sent users to look for a degenerate Lagrangian).
TYPED_TEST(NewtonTest, ANonFiniteResidualIsNamedAsADomainError) {
  using T = TypeParam;
  Vector<T, 1> at;
  at[0] = 1;
  auto report = newton_solve<T, 1>(
      at, [&](const Vector<T, 1>& v, Vector<T, 1>& residual, Matrix<T, 1, 1>& jacobian) {
        using std::sqrt;
        residual[0] = sqrt(T(v[0] - 5));
        jacobian(0, 0) = 1 / (2 * residual[0]);
      });
  EXPECT_FALSE(report.converged);
  EXPECT_NE(report.failure.find("not finite"), std::string::npos) << report.failure;
  EXPECT_EQ(report.failure.find("singular"), std::string::npos) << report.failure;
}

// x² = a from x0: quadratic convergence to √a when a > 0, only linear (each correction half the
// one before) to the double root when a = 0.
template <class T>
SolveReport<T> solve_square(T& x, const T& a, int& evaluations, const NewtonOptions& options) {
  Vector<T, 1> at;
  at[0] = x;
  auto report = newton_solve<T, 1>(
      at,
      [&](const Vector<T, 1>& v, Vector<T, 1>& residual, Matrix<T, 1, 1>& jacobian) {
        ++evaluations;
        residual[0] = v[0] * v[0] - a;
        jacobian(0, 0) = 2 * v[0];
      },
      options);
  x = at[0];
  return report;
}

// The options for solves along a run: the predicted stop saves an iteration of a quadratically
// converging solve, the skipped evaluation at the solution one more, and the root is as accurate.
TYPED_TEST(NewtonTest, ThePredictedStopSavesEvaluationsOfAQuadraticSolve) {
  using T = TypeParam;
  using std::abs;
  using std::sqrt;
  T plain = T(3) / 2, predicted = plain;
  int plain_evaluations = 0, predicted_evaluations = 0;
  ASSERT_TRUE(solve_square(plain, T(2), plain_evaluations, {}).converged);
  ASSERT_TRUE(
      solve_square(predicted, T(2), predicted_evaluations, options_along_a_run()).converged);
  EXPECT_LE(predicted_evaluations, plain_evaluations - 2);
  EXPECT_LE(abs(T(predicted - sqrt(T(2)))), this->working_tolerance());
}

// The negative control: a solve converging only linearly (θ = 1/2) is not stopped earlier than
// the plain rule stops it; only the evaluation at the solution is saved.
TYPED_TEST(NewtonTest, ThePredictedStopWaitsForALinearlyConvergingSolve) {
  using T = TypeParam;
  T plain = 1, predicted = 1;
  int plain_evaluations = 0, predicted_evaluations = 0;
  // Halving to the rounding level takes about 150 iterations at 60 digits.
  NewtonOptions plain_options, predicted_options = options_along_a_run();
  plain_options.max_iterations = predicted_options.max_iterations = 400;
  ASSERT_TRUE(solve_square(plain, T(0), plain_evaluations, plain_options).converged);
  ASSERT_TRUE(solve_square(predicted, T(0), predicted_evaluations, predicted_options).converged);
  EXPECT_EQ(predicted_evaluations, plain_evaluations - 1);
  EXPECT_EQ(predicted, plain);
}

}  // namespace
}  // namespace vivv
