// The discrete Euler–Lagrange (DEL) evolution on Q×Q (docs/theory.md (Q × Q), paper eq. 2.5).
//
// (q_{k−1}, q_k) ↦ (q_k, q_{k+1}) solves
//   p_begin[L_d](q_k, q_{k+1}) = p_end[L~_d](q_{k−1}, q_k)
// for q_{k+1}, where L_d is the `future` and L~_d the `past` discretization;
// they are equal except in the mismatched DEL of paper §2.3.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/qxq/discrete_lagrangian.hpp"
#include "core/numerics/newton.hpp"

namespace vivv {

template <class T>
struct DelScheme {
  QxQDiscretization<T> future;  // L_d, on the segment (q_k, q_{k+1})
  QxQDiscretization<T> past;    // L~_d, on the segment (q_{k−1}, q_k)
  bool mismatched = false;      // past differs from future
};

// A scheme whose two sides use the same discrete Lagrangian.
template <class T>
DelScheme<T> matched_scheme(const QxQDiscretization<T>& discretization) {
  return {discretization, discretization, false};
}

// What a run of DEL steps did: the trajectory and the most Newton iterations a step took.
template <class T, int n>
struct DelTrajectory {
  std::vector<Vector<T, n>> q;  // q_0, ..., q_N
  int max_iterations = 0;
};

// One DEL step: q_{k+1} from p_begin[future](q_k, q_{k+1}) = p_end[past](q_{k−1}, q_k),
// by Newton from the linear extrapolation 2 q_k − q_{k−1}. For an L that depends on t, `system`
// is at t_k, the time of q_k: the future segment starts there and the past one h before.
template <LagrangianSystem System>
auto del_step(const System& system, const DelScheme<typename System::Scalar>& scheme,
              const VectorOf<System>& q_previous, const VectorOf<System>& q_current,
              const typename System::Scalar& h) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  Vector<T, n> target = depends_on_time(system)
                            ? p_end(at_time(system, T(system_time(system) - h)), scheme.past, q_previous, q_current, h)
                            : p_end(system, scheme.past, q_previous, q_current, h);
  Vector<T, n> q_next = 2 * q_current - q_previous;
  if constexpr (SparselyDifferentiated<System>) {
    // Sized at run time with L a tape: the Newton matrix is sparse where L's couplings are, and
    // is factored as such (core/qxq/sparse_legendre.hpp, core/numerics/newton.hpp).
    if (sparse_path_applies(system, scheme.future)) {
      auto report = newton_solve<T, n, Eigen::SparseMatrix<T>>(
          q_next,
          [&](const Vector<T, n>& x, Vector<T, n>& residual, Eigen::SparseMatrix<T>& jacobian) {
            auto legendre = sparse_begin_momentum(system, scheme.future, q_current, x, h);
            residual = legendre.p_begin - target;
            jacobian = std::move(legendre.dp_begin_dq_e);
          },
          options_along_a_run());
      return std::pair{q_next, report};
    }
  }
  // Nothing reads the residual at q_{k+1}; the quadratic convergence of a step along a run
  // makes the predicted stop safe (core/numerics/newton.hpp). Both save an L_d evaluation per step.
  auto report = newton_solve<T, n>(
      q_next,
      [&](const Vector<T, n>& x, Vector<T, n>& residual, Matrix<T, n, n>& jacobian) {
        auto legendre = begin_momentum(system, scheme.future, q_current, x, h);
        residual = legendre.p_begin - target;
        jacobian = legendre.dp_begin_dq_e;
      },
      options_along_a_run());
  return std::pair{q_next, report};
}

// q_0, ..., q_N from (q_0, q_1) by N − 1 DEL steps of size h, q_0 at the system's time t_0 and
// q_k at t_0 + k·h. A step whose Newton solve fails is an error naming the step and h.
// `after_step(k, N)`, when given, is called after each step (the harness throttles it into
// progress lines).
template <LagrangianSystem System>
auto del_trajectory(const System& system, const DelScheme<typename System::Scalar>& scheme,
                    const VectorOf<System>& q0, const VectorOf<System>& q1,
                    const typename System::Scalar& h, int steps,
                    const std::function<void(int, int)>& after_step = {}) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  DelTrajectory<T, n> trajectory;
  trajectory.q = {q0, q1};
  trajectory.q.reserve(steps + 1);
  const bool timed = depends_on_time(system);
  const T t0 = system_time(system);
  for (int k = 1; k < steps; ++k) {
    auto [q_next, report] = timed ? del_step(at_time(system, T(t0 + k * h)), scheme, trajectory.q[k - 1], trajectory.q[k], h)
                                  : del_step(system, scheme, trajectory.q[k - 1], trajectory.q[k], h);
    if (!report.converged) {
      // Where the run was when the step failed: a step that fails partway is read against the
      // state it started from, not the initial one.
      require_converged(report, "DEL step " + std::to_string(k) + " of " + std::to_string(steps) +
                                    " with h = " + to_decimal<T>(h, 17) +
                                    " (from t = " + to_decimal<T>(T(t0 + k * h), 8) +
                                    ", q = " + to_decimal_tuple<T, n>(trajectory.q[k]) + ")");
    }
    trajectory.max_iterations = std::max(trajectory.max_iterations, report.iterations);
    trajectory.q.push_back(q_next);
    if (after_step) after_step(k + 1, steps);
  }
  return trajectory;
}

// The q' with p_begin[future](q, q') = p, by Newton from `guess` to full convergence; a failure
// is a SolverError naming `what`. Sparse where L is (as del_step).
template <LagrangianSystem System>
auto next_configuration(const System& system, const QxQDiscretization<typename System::Scalar>& future,
                        const VectorOf<System>& q, const VectorOf<System>& p, VectorOf<System> guess,
                        const typename System::Scalar& h, const std::string& what) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  if constexpr (SparselyDifferentiated<System>) {
    if (sparse_path_applies(system, future)) {
      auto report = newton_solve<T, n, Eigen::SparseMatrix<T>>(
          guess, [&](const Vector<T, n>& x, Vector<T, n>& residual, Eigen::SparseMatrix<T>& jacobian) {
            auto legendre = sparse_begin_momentum(system, future, q, x, h);
            residual = legendre.p_begin - p;
            jacobian = std::move(legendre.dp_begin_dq_e);
          });
      require_converged(report, what);
      return guess;
    }
  }
  auto report = newton_solve<T, n>(
      guess, [&](const Vector<T, n>& x, Vector<T, n>& residual, Matrix<T, n, n>& jacobian) {
        auto legendre = begin_momentum(system, future, q, x, h);
        residual = legendre.p_begin - p;
        jacobian = legendre.dp_begin_dq_e;
      });
  require_converged(report, what);
  return guess;
}

// q_1 from the discrete Legendre transform: p_begin[future](q_0, q_1) = p_0,
// by Newton from q_0 + h·w_0 (q_0 at the system's time).
template <LagrangianSystem System>
auto start_from_momentum(const System& system, const QxQDiscretization<typename System::Scalar>& future,
                         const VectorOf<System>& q0, const VectorOf<System>& w0,
                         const typename System::Scalar& h) {
  using T = typename System::Scalar;
  return next_configuration(system, future, q0, VectorOf<System>(momentum(system, q0, w0)),
                            VectorOf<System>(q0 + h * w0), h,
                            "start from p_begin(q0, q1) = p(0) with h = " + to_decimal<T>(h, 17));
}

}  // namespace vivv
