// Newton's method on Eigen matrices, reporting what happened (README (layout)).
//
// Solvers return whether they converged, in how many iterations and with what
// residual; callers that cannot use an unconverged iterate call
// `require_converged`, which turns a failure into a SolverError.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>
#include <utility>

#include <Eigen/SparseCore>

#include "core/numerics/linear_solve.hpp"
#include "core/numerics/scalar.hpp"

namespace vivv {

struct SolverError : std::runtime_error {
  using std::runtime_error::runtime_error;
  // The message already says which step sizes converge (harness/run/run_system_impl.hpp).
  bool step_sizes_probed = false;
};

template <class T>
struct SolveReport {
  bool converged = false;
  int iterations = 0;
  T residual = 0;    // max norm of F at the returned iterate (see evaluate_at_solution)
  T correction = 0;  // max norm of the last Newton correction
  bool stalled = false;  // stopped at the rounding level of the residual (see newton_solve)
  // Every correction at most half the one before, until the rounding level: the start lies
  // where Newton contracts (its quadratic regime), not merely somewhere it happens to converge.
  bool contracting = true;
  std::string failure;
  std::vector<T> corrections;  // max norm of every correction, in order
};

struct NewtonOptions {
  int max_iterations = 60;
  // Stopped as not converging at the first sign of it: a correction `runaway_factor` times
  // the smallest before it, or `stagnation_limit` corrections in a row none below the
  // smallest before them. Newton that converges shrinks its correction (quadratically once
  // close); one that runs away or wanders does not, and each further evaluation can be
  // expensive (an exact psi over a large h integrates the flow from the wandering iterate).
  // Rounding is not mistaken for it: a correction at the residual's rounding level ends
  // the solve as converged first (`stalled`).
  int runaway_factor = 16;
  int stagnation_limit = 3;
  // Converged when each correction component is below correction_ulps · ε · max(scale_i, |x_i|).
  int correction_ulps = 64;
  // Also converged when the error left after a correction c_k, estimated as if the iteration
  // only contracted linearly, θ/(1 − θ)·c_k with θ = c_k/c_{k−1} (Hairer & Wanner, Solving ODEs
  // II, IV.8), is below that tolerance: one evaluation fewer for a solve that converges
  // quadratically (the DEL steps along a run), never an earlier stop for one that does not.
  bool predict_convergence = false;
  // Evaluate F once more at the converged iterate to report its residual. A caller that reads
  // neither the report's residual nor anything its evaluation computed saves that evaluation;
  // the report's residual is then the one before the last correction.
  bool evaluate_at_solution = true;
};

// For a solve repeated along a run whose solution alone is used (a DEL step, the inverse
// Legendre transform at each step): the predicted stop, no evaluation at the solution.
inline NewtonOptions options_along_a_run() {
  NewtonOptions options;
  options.predict_convergence = true;
  options.evaluate_at_solution = false;
  return options;
}

// "a, b, c, …" of the corrections (the first and the last few when there are many).
template <class T>
std::string describe_corrections(const std::vector<T>& corrections) {
  std::string text;
  for (std::size_t i = 0; i < corrections.size(); ++i) {
    if (corrections.size() > 8 && i == 2) {
      text += ", …";
      i = corrections.size() - 5;
      continue;
    }
    text += (i ? ", " : "") + to_decimal<T>(corrections[i], 3);
  }
  return text;
}

namespace newton_detail {

// The Jacobian's storage: dense, or (a system sized at run time, sparse where L is) Eigen's.
template <class T, int m>
Matrix<T, m, m> empty_jacobian(Matrix<T, m, m>*, int count) {
  return zero_matrix<T, m, m>(count, count);
}
template <class T, int m>
Eigen::SparseMatrix<T> empty_jacobian(Eigen::SparseMatrix<T>*, int count) {
  return Eigen::SparseMatrix<T>(count, count);
}

template <class T, int m>
bool all_finite(const Matrix<T, m, m>& jacobian) {
  return jacobian.allFinite();
}
template <class T>
bool all_finite(const Eigen::SparseMatrix<T>& jacobian) {
  for (int k = 0; k < jacobian.outerSize(); ++k)
    for (typename Eigen::SparseMatrix<T>::InnerIterator it(jacobian, k); it; ++it) {
      using std::isfinite;
      if (!isfinite(static_cast<T>(it.value()))) return false;
    }
  return true;
}

}  // namespace newton_detail

// Solves F(x) = 0 from x (updated in place). `evaluate(x, F, J)` fills the
// residual F(x) and its Jacobian J = dF/dx. Iteration: x ← x − J⁻¹ F(x).
// `scale[i]` is the size below which x_i's rounding is not measured: every
// correction component must fall below correction_ulps · ε · max(scale_i, |x_i|).
// The Jacobian is dense (Matrix<T, m, m>) or, given as the third template argument,
// Eigen::SparseMatrix<T>.
template <class T, int m, class Jacobian = Matrix<T, m, m>, class Evaluate>
SolveReport<T> newton_solve(Vector<T, m>& x, Evaluate&& evaluate, const NewtonOptions& options,
                            const Vector<T, m>& scale) {
  using std::isfinite;
  SolveReport<T> report;
  T previous_correction = 0;
  T smallest_correction = 0;
  int without_progress = 0;
  const int count = static_cast<int>(x.size());
  Vector<T, m> residual = zero_vector<T, m>(count);
  Jacobian jacobian = newton_detail::empty_jacobian<T, m>(static_cast<Jacobian*>(nullptr), count);
  for (report.iterations = 1; report.iterations <= options.max_iterations; ++report.iterations) {
    evaluate(x, residual, jacobian);
    // A formula evaluated outside its domain (√ or log of a negative number) gives NaN: say so,
    // rather than "singular Jacobian", which would send the user to the wrong place.
    if (!residual.allFinite() || !newton_detail::all_finite(jacobian)) {
      report.failure = std::string(
          "the residual or its Jacobian is not finite at the iterate (a formula evaluated "
          "outside its domain, such as √ or log of a negative number, or an overflow)");
      report.residual = max_norm<T, m>(residual);
      return report;
    }
    Vector<T, m> correction = zero_vector<T, m>(count);
    if (!solve_linear(jacobian, residual, correction, T(16) * epsilon<T>())) {
      report.failure = "singular Jacobian (the discrete Lagrangian is not regular here)";
      report.residual = max_norm<T, m>(residual);
      return report;
    }
    x -= correction;
    report.correction = max_norm<T, m>(correction);
    report.corrections.push_back(report.correction);
    if (!isfinite(static_cast<T>(report.correction))) {
      report.failure = "the iteration diverged to a non-finite value (corrections " +
                       describe_corrections(report.corrections) + ")";
      return report;
    }
    // The error left after this correction, estimated componentwise (see predict_convergence).
    const T left_factor = options.predict_convergence && report.iterations > 1 &&
                                  report.correction <= previous_correction / 2
                              ? T(report.correction / (previous_correction - report.correction))
                              : T(1);
    bool small = true;
    for (int i = 0; i < count; ++i) {
      using std::abs;
      T size = std::max<T>(scale[i], abs(x[i]));
      small = small &&
              left_factor * abs(correction[i]) <= options.correction_ulps * epsilon<T>() * size;
    }
    // Stalled at the residual's own rounding: the correction no longer halves
    // although it is already far below √ε (quadratic convergence has happened;
    // what is left is noise, e.g. from a difference of configurations over h).
    using std::pow;
    bool stalled = report.iterations > 2 && report.correction >= previous_correction / 2 &&
                   report.correction <= pow(epsilon<T>(), T(3) / 4) * std::max<T>(T(1), max_norm<T, m>(x));
    if (report.iterations > 1 && report.correction > previous_correction / 2 && !small && !stalled)
      report.contracting = false;
    previous_correction = report.correction;
    if (small || stalled) {
      if (options.evaluate_at_solution) evaluate(x, residual, jacobian);
      report.residual = max_norm<T, m>(residual);
      report.converged = true;
      report.stalled = stalled && !small;
      return report;
    }
    if (report.iterations == 1 || report.correction < smallest_correction) {
      smallest_correction = report.correction;
      without_progress = 0;
    } else if (report.correction >= options.runaway_factor * smallest_correction) {
      report.residual = max_norm<T, m>(residual);
      report.failure = "diverging: a correction " + std::to_string(options.runaway_factor) +
                       " times the smallest before it (corrections " + describe_corrections(report.corrections) +
                       ")";
      return report;
    } else if (++without_progress >= options.stagnation_limit) {
      report.residual = max_norm<T, m>(residual);
      report.failure = "not converging: the last " + std::to_string(without_progress) +
                       " corrections were none below the smallest before them (corrections " +
                       describe_corrections(report.corrections) + ")";
      return report;
    }
  }
  report.iterations = options.max_iterations;
  report.residual = max_norm<T, m>(residual);
  report.failure = "no convergence in " + std::to_string(options.max_iterations) +
                   " iterations (corrections " + describe_corrections(report.corrections) + ")";
  return report;
}

// Throws SolverError naming `what` unless the solve converged.
template <class T>
const SolveReport<T>& require_converged(const SolveReport<T>& report, const std::string& what) {
  if (!report.converged) throw SolverError(what + ": Newton failed: " + report.failure);
  return report;
}

// The same with every scale 1.
template <class T, int m, class Jacobian = Matrix<T, m, m>, class Evaluate>
SolveReport<T> newton_solve(Vector<T, m>& x, Evaluate&& evaluate, const NewtonOptions& options = {}) {
  return newton_solve<T, m, Jacobian>(x, std::forward<Evaluate>(evaluate), options, Vector<T, m>::Ones(x.size()));
}

}  // namespace vivv
