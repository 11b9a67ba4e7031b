// The flow together with its Jacobian, by the Taylor integrator on the variational equations.
//
// For y = (q, w) the Jacobian Φ(t) = d(q(t), w(t)) / d(q(0), w(0)) solves
//   Φ' = Df(y(t)) Φ,   Φ(0) = I,   f(q, w) = (w, a(q, w)),
// whose column j, (δq^j, δw^j), satisfies δq^j'' = ∂a/∂q δq^j + ∂a/∂w δw^j:
// a second-order system again, recorded by variational_tape
// (core/lagrangian/euler_lagrange_tape.hpp) and integrated with the same Jorba–Zou order
// and steps as the flow, in the same precision. The exact discrete Lagrangian
// shoots with it; the symplecticity claim checks Φ.
#pragma once

#include <vector>

#include "core/lagrangian/euler_lagrange_tape.hpp"
#include "core/lagrangian/state.hpp"
#include "references/taylor_flow.hpp"

namespace vivv {

// F_t(v) and DF_t(v), rows and columns ordered (q_1..q_n, w_1..w_n).
template <class T, int n>
struct FlowWithJacobian {
  explicit FlowWithJacobian(int size)
      : state{Vector<T, n>(size), Vector<T, n>(size)}, jacobian(2 * size, 2 * size) {}
  State<T, n> state;
  Matrix<T, twice(n), twice(n)> jacobian;
};

template <TapeRecordable System>
class TaylorVariationalFlow {
 public:
  using T = typename System::Scalar;
  static constexpr int N = System::dimension;

  // Step tolerance as for TaylorFlow; the steps also resolve Φ.
  TaylorVariationalFlow(const System& system, const T& tolerance)
      : n(dimension_of(system)), columns(2 * n), extended(n * (1 + columns)),
        integrator_(variational_tape(euler_lagrange_tape(system)), tolerance) {}

  const int n;         // coordinates
  const int columns;   // 2n
  const int extended;  // dimension of (q, δq¹ … δq^{2n}): n (1 + 2n)

  int order() const { return integrator_.order(); }
  TaylorReport report() const { return integrator_.report(); }
  TaylorIntegrator<T>& integrator() { return integrator_; }

  // (F_t(start), DF_t(start)), ending exactly at t.
  FlowWithJacobian<T, N> advance(const State<T, N>& start, const T& t) {
    return split(integrator_.advance(components(start), t));
  }

  // The dense trajectory of (y, Φ) from `start` covering [0, t_end].
  TaylorTrajectory<T> trajectory(const State<T, N>& start, const T& t_end) {
    TaylorTrajectory<T> result(components(start), t_end >= 0 ? 1 : -1);
    integrator_.extend(result, t_end);
    return result;
  }

  // (q, δq¹…δq^{2n}, w, δw¹…δw^{2n}) with Φ(0) = I: δq^j = e_j (j < n), δw^j = e_{j−n} (j ≥ n).
  std::vector<T> components(const State<T, N>& v) const {
    std::vector<T> y(2 * extended, T(0));
    for (int i = 0; i < n; ++i) {
      y[i] = v.q[i];
      y[extended + i] = v.w[i];
      y[n + i * n + i] = 1;                            // δq^i_i, column i < n
      y[extended + n + (n + i) * n + i] = 1;           // δw^{n+i}_i
    }
    return y;
  }

  // The state and Jacobian held in the components y.
  FlowWithJacobian<T, N> split(const std::vector<T>& y) const {
    FlowWithJacobian<T, N> result(n);
    for (int i = 0; i < n; ++i) {
      result.state.q[i] = y[i];
      result.state.w[i] = y[extended + i];
    }
    for (int j = 0; j < columns; ++j) {
      for (int i = 0; i < n; ++i) {
        result.jacobian(i, j) = y[n + j * n + i];
        result.jacobian(n + i, j) = y[extended + n + j * n + i];
      }
    }
    return result;
  }

 private:
  TaylorIntegrator<T> integrator_;
};

}  // namespace vivv
