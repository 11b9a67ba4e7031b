// Newton's method on Eigen matrices, reporting what happened (DESIGN §2).
//
// Solvers return whether they converged, in how many iterations and with what
// residual; callers that cannot use an unconverged iterate call
// `require_converged`, which turns a failure into a SolverError.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/scalar.hpp"

namespace vivv {

struct SolverError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <class T>
struct SolveReport {
  bool converged = false;
  int iterations = 0;
  T residual = 0;    // max norm of F at the returned iterate
  T correction = 0;  // max norm of the last Newton correction
  std::string failure;
};

struct NewtonOptions {
  int max_iterations = 60;
  // Converged when the correction is below correction_ulps · ε · max(1, |x|).
  int correction_ulps = 64;
};

// Solves F(x) = 0 from x (updated in place). `evaluate(x, F, J)` fills the
// residual F(x) and its Jacobian J = dF/dx. Iteration: x ← x − J⁻¹ F(x).
template <class T, int m, class Evaluate>
SolveReport<T> newton_solve(Vector<T, m>& x, Evaluate&& evaluate, const NewtonOptions& options = {}) {
  using std::isfinite;
  SolveReport<T> report;
  Vector<T, m> residual = Vector<T, m>::Zero();
  Matrix<T, m, m> jacobian = Matrix<T, m, m>::Zero();
  for (report.iterations = 1; report.iterations <= options.max_iterations; ++report.iterations) {
    evaluate(x, residual, jacobian);
    Eigen::FullPivLU<Matrix<T, m, m>> lu(jacobian);
    lu.setThreshold(T(16) * epsilon<T>());
    if (!lu.isInvertible()) {
      report.failure = "singular Jacobian (the discrete Lagrangian is not regular here)";
      report.residual = max_norm<T, m>(residual);
      return report;
    }
    Vector<T, m> correction = lu.solve(residual);
    x -= correction;
    report.correction = max_norm<T, m>(correction);
    T scale = std::max<T>(T(1), max_norm<T, m>(x));
    if (!isfinite(static_cast<T>(report.correction))) {
      report.failure = "the iteration diverged to a non-finite value";
      return report;
    }
    if (report.correction <= options.correction_ulps * epsilon<T>() * scale) {
      evaluate(x, residual, jacobian);
      report.residual = max_norm<T, m>(residual);
      report.converged = true;
      return report;
    }
  }
  report.iterations = options.max_iterations;
  report.residual = max_norm<T, m>(residual);
  report.failure = "no convergence in " + std::to_string(options.max_iterations) +
                   " iterations (last correction " + to_decimal<T>(report.correction) + ")";
  return report;
}

// Throws SolverError naming `what` unless the solve converged.
template <class T>
const SolveReport<T>& require_converged(const SolveReport<T>& report, const std::string& what) {
  if (!report.converged) throw SolverError(what + ": Newton failed: " + report.failure);
  return report;
}

}  // namespace vivv
