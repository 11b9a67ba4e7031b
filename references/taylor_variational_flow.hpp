// The flow together with its Jacobian, by the Taylor integrator on the variational equations.
//
// For y = (q, w) the Jacobian Φ(t) = d(q(t), w(t)) / d(q(0), w(0)) solves
//   Φ' = Df(y(t)) Φ,   Φ(0) = I,   f(q, w) = (w, a(q, w)),
// whose column j, (δq^j, δw^j), satisfies δq^j'' = ∂a/∂q δq^j + ∂a/∂w δw^j:
// a second-order system again, recorded by variational_tape
// (core/lagrangian/euler_lagrange_tape.hpp) and integrated with the same Jorba–Zou order
// and steps as the flow, in the same precision. The exact discrete Lagrangian
// shoots with it; the symplecticity claim checks Φ.
//
// For an L that depends on t the flow is that of (q, t) with t'' = 0 (references/taylor_flow.hpp,
// flow_tape), started at the system's time: Φ is carried over the m = n + 1 components, the time's
// rows and columns are dropped from the Jacobian returned, and the time is left out of the step
// control (TaylorIntegrator::clock), as for the flow.
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
      : n(dimension_of(system)), m(n + (depends_on_time(system) ? 1 : 0)), columns(2 * m),
        extended(m * (1 + columns)), time(system_time(system)),
        integrator_(variational_tape(flow_tape(system)), tolerance) {
    if (m > n) integrator_.clock = n;
  }

  const int n;         // coordinates
  const int m;         // the flow's components: n, or n + 1 with the time
  const int columns;   // 2m
  const int extended;  // dimension of (x, δx¹ … δx^{2m}): m (1 + 2m)
  const T time;        // where a trajectory starts, for an L that depends on t

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

  // (x, δx¹…δx^{2m}, x', δx'¹…δx'^{2m}) with Φ(0) = I: δx^j = e_j (j < m), δx'^j = e_{j−m} (j ≥ m);
  // x = q, or (q, t) with t' = 1 for an L that depends on t.
  std::vector<T> components(const State<T, N>& v) const {
    std::vector<T> y(2 * extended, T(0));
    for (int i = 0; i < n; ++i) y[i] = v.q[i], y[extended + i] = v.w[i];
    if (m > n) y[n] = time, y[extended + n] = 1;
    for (int i = 0; i < m; ++i) {
      y[m + i * m + i] = 1;                   // δx^i_i, column i < m
      y[extended + m + (m + i) * m + i] = 1;  // δx'^{m+i}_i
    }
    return y;
  }

  // The state and Jacobian held in the components y: (q, w) and d(q, w)/d(q, w), the time's rows
  // and columns left out.
  FlowWithJacobian<T, N> split(const std::vector<T>& y) const {
    FlowWithJacobian<T, N> result(n);
    for (int i = 0; i < n; ++i) {
      result.state.q[i] = y[i];
      result.state.w[i] = y[extended + i];
    }
    for (int j = 0; j < 2 * n; ++j) {
      const int column = j < n ? j : m + (j - n);
      for (int i = 0; i < n; ++i) {
        result.jacobian(i, j) = y[m + column * m + i];
        result.jacobian(n + i, j) = y[extended + m + column * m + i];
      }
    }
    return result;
  }

 private:
  TaylorIntegrator<T> integrator_;
};

}  // namespace vivv
