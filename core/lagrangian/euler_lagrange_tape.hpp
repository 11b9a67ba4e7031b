// The Euler–Lagrange acceleration of a Lagrangian system as a tape (issue 3).
//
// euler_lagrange_tape records, once, the expression
//   a(q, w) = M⁻¹ (dL/dq − (d²L/dw dq) w),   M = d²L/dw²     (docs/theory.md)
// by evaluating the system's own generic L with S = Jet<TapeScalar<T>, 2n>
// (so dL/dq, M and d²L/dw dq are recorded too) and solving M a = rhs by
// Gaussian elimination on the tape. No per-system series: any catalogue L
// that core/ can differentiate yields its Taylor coefficients through
// core/autodiff/taylor_expansion.hpp.
//
// The elimination pivots on structure only (a tape fixes one sequence of
// operations, recorded before any value is known): the diagonal entry is the
// pivot unless it is identically zero, and then the first row below whose
// entry in that column is not — so a regular but indefinite M, as of
// L = w1 w2 − V (M = [[0, 1], [1, 0]]), is solved, not refused. That is stable
// for a definite mass matrix — every catalogue system has one. A column with no
// such entry is rejected while recording (M is then singular for every state);
// a pivot that vanishes at a visited state gives non-finite coefficients, which
// the flow reports.
//
// variational_tape extends a tape for x'' = a(x, x') in R^m by the
// variational equations of its 2m first-order columns: with x = (q, δq¹…δq^{2m})
// and v = (w, δw¹…δw^{2m}),
//   δq^j'' = ∂a/∂q · δq^j + ∂a/∂w · δw^j,
// recorded by replaying the tape in first-order jets whose seeds are the tape
// variables δq^j, δw^j. Starting from the identity, (δq^j, δw^j)(t) is column
// j of the flow's Jacobian d(q(t), w(t)) / d(q(0), w(0)).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/autodiff/jet.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "core/autodiff/tape.hpp"

namespace vivv {

// What a column of d²L/dw² with no entry that is not identically zero, on or below its diagonal once
// the columns before it are eliminated, says: M is singular at every state.
inline std::string singular_column_message(int column) {
  return "euler_lagrange_tape: d2L/dw2 is singular at every state: after eliminating the columns before it, "
         "column " + std::to_string(column) + " has no entry that is not identically zero on or below its diagonal";
}

// A system whose L can be evaluated in jets over the recording scalar.
template <class System>
concept TapeRecordable =
    LagrangianSystem<System> &&
    requires(const System& system,
             const Coordinates<Jet<TapeScalar<typename System::Scalar>, twice(System::dimension)>,
                         System::dimension>& x) {
      { system.lagrangian(x, x) };
    };

// The same from L's sparse derivatives (core/autodiff/sparse_hessian.hpp), for a system sized at
// run time: the derivative tape replayed in TapeScalar gives dL/dq and the nonzeros of d²L/dw²
// and d²L/dw dq, and M a = rhs is eliminated on M's sparsity pattern (symmetric, so the rows a
// pivot row updates are the columns it holds), pivoting on structure as above. Its tape grows like
// L's and M's fill-in, where the dense recording is O(n³) (a jet of n² entries through every node).
// After a row exchange the pattern is no longer symmetric, and the rows below that hold a column
// are found by looking at each (O(n) a column, only for an M with identically zero diagonal entries).
//
// An L that depends on t (its tape's inputs (q, w, t), 2n + 1 of them): the tape is over the
// coordinates (q, t) — inputs (q_1 … q_n, t, w_1 … w_n, w_t) — with the outputs (a, 0), so that
// integrating x'' = a(x, x') from (q, t_0, w, 1) keeps t' = 1 and takes L at the time reached:
//   a(t, q, w) = M⁻¹ (dL/dq − (d²L/dw dq) w − (d²L/dw dt) w_t)     (Marsden & West §4).
template <class T>
Tape<T> sparse_euler_lagrange_tape(const SecondDerivativeTape<T>& derivatives) {
  using S = TapeScalar<T>;
  const bool timed = derivatives.inputs % 2 == 1;
  const int n = derivatives.inputs / 2, m = n + (timed ? 1 : 0);
  TapeRecording<T> recording(2 * m);
  std::vector<S> x(derivatives.inputs);  // L's inputs (q, w and t) from the tape's (q, t, w, w_t)
  for (int i = 0; i < n; ++i) x[i] = recording.input(i), x[n + i] = recording.input(m + i);
  if (timed) x[2 * n] = recording.input(n);
  std::vector<S> value;
  derivatives.program.run(x.data(), value);
  const auto output = [&](std::size_t k) { return value[derivatives.program.outputs[k]]; };
  std::vector<std::map<int, S>> M(n);
  std::vector<S> rhs(n);
  for (int i = 0; i < n; ++i) rhs[i] = output(1 + i);
  for (std::size_t e = 0; e < derivatives.pattern.size(); ++e) {
    const auto [r, c] = derivatives.pattern[e];  // r >= c
    const S entry = output(1 + derivatives.inputs + e);
    if (r == 2 * n) {  // ∂²L/∂t∂(q, w, t): only ∂²L/∂w_i∂t enters, times w_t
      if (c >= n && c < 2 * n) rhs[c - n] = rhs[c - n] - entry * recording.input(2 * m - 1);
    } else if (c >= n) {
      M[r - n][c - n] = entry, M[c - n][r - n] = entry;
    } else if (r >= n) {
      rhs[r - n] = rhs[r - n] - entry * x[n + c];  // (d²L/dw_i dq_j) w_j, i = r − n, j = c
    }
  }
  const auto holds = [&](int row, int column) {
    const auto entry = M[row].find(column);
    return entry != M[row].end() && !entry->second.is_constant(0);
  };
  bool symmetric = true;
  std::vector<int> below;
  for (int j = 0; j < n; ++j) {
    if (!holds(j, j)) {
      int exchange = j + 1;
      while (exchange < n && !holds(exchange, j)) ++exchange;
      if (exchange == n) throw SingularLagrangianError(singular_column_message(j));
      std::swap(M[j], M[exchange]);
      std::swap(rhs[j], rhs[exchange]);
      symmetric = false;
    }
    const auto pivot = M[j].find(j);
    below.clear();
    if (symmetric) {
      for (auto it = M[j].upper_bound(j); it != M[j].end(); ++it) below.push_back(it->first);
    } else {
      for (int i = j + 1; i < n; ++i)
        if (M[i].count(j)) below.push_back(i);
    }
    for (const int i : below) {
      const S factor = M[i].at(j) / pivot->second;
      for (auto k = M[j].upper_bound(j); k != M[j].end(); ++k) {
        auto [slot, inserted] = M[i].try_emplace(k->first, S(0));
        slot->second = slot->second - factor * k->second;
      }
      rhs[i] = rhs[i] - factor * rhs[j];
    }
  }
  std::vector<S> acceleration(n);
  for (int i = n - 1; i >= 0; --i) {
    S sum = rhs[i];
    for (auto k = M[i].upper_bound(i); k != M[i].end(); ++k) sum = sum - k->second * acceleration[k->first];
    acceleration[i] = sum / M[i].at(i);
  }
  if (timed) acceleration.push_back(S(T(0)));  // t'' = 0
  return recording.finish(acceleration);
}

// Tape of a(q, w) = M⁻¹ (dL/dq − (d²L/dw dq) w): inputs (q_1..q_n, w_1..w_n), outputs a_1..a_n.
template <TapeRecordable System>
Tape<typename System::Scalar> euler_lagrange_tape(const System& system) {
  using T = typename System::Scalar;
  using S = TapeScalar<T>;
  constexpr int N = System::dimension;
  const int n = dimension_of(system);
  if (depends_on_time(system))
    throw std::logic_error("euler_lagrange_tape: the acceleration of an L that depends on t is a(t, q, w), which "
                           "this tape over (q, w) cannot hold (time_extended_euler_lagrange_tape holds it)");
  if constexpr (SparselyDifferentiated<System>) {
    if (system.derivatives) return sparse_euler_lagrange_tape(*system.derivatives);
  }
  using J = Jet<S, twice(N)>;
  TapeRecording<T> recording(2 * n);
  Coordinates<J, N> q = make_point<J, N>(n), w = make_point<J, N>(n);
  for (int i = 0; i < n; ++i) {
    q[i] = J::variable(recording.input(i), i, 2 * n);
    w[i] = J::variable(recording.input(n + i), n + i, 2 * n);
  }
  const J L = with_size(J(system.lagrangian(q, w)), 2 * n);
  // M a = dL/dq − (d²L/dw dq) w, as an augmented n × (n + 1) matrix.
  std::vector<std::vector<S>> augmented(n, std::vector<S>(n + 1));
  for (int i = 0; i < n; ++i) {
    S rhs = L.gradient[i];
    for (int j = 0; j < n; ++j) {
      augmented[i][j] = L.second(n + i, n + j);
      rhs = rhs - L.second(n + i, j) * recording.input(n + j);
    }
    augmented[i][n] = rhs;
  }
  // Gaussian elimination pivoting on structure (at the top of the file), then back substitution.
  for (int j = 0; j < n; ++j) {
    if (augmented[j][j].is_constant(0)) {
      int exchange = j + 1;
      while (exchange < n && augmented[exchange][j].is_constant(0)) ++exchange;
      if (exchange == n) throw SingularLagrangianError(singular_column_message(j));
      std::swap(augmented[j], augmented[exchange]);
    }
    for (int i = j + 1; i < n; ++i) {
      S factor = augmented[i][j] / augmented[j][j];
      for (int k = j; k <= n; ++k) augmented[i][k] = augmented[i][k] - factor * augmented[j][k];
    }
  }
  std::vector<S> acceleration(n);
  for (int i = n - 1; i >= 0; --i) {
    S sum = augmented[i][n];
    for (int k = i + 1; k < n; ++k) sum = sum - augmented[i][k] * acceleration[k];
    acceleration[i] = sum / augmented[i][i];
  }
  return recording.finish(acceleration);
}

// The acceleration of an L that depends on t as a tape over the coordinates (q, t) with t'' = 0
// (sparse_euler_lagrange_tape): inputs (q_1 … q_n, t, w_1 … w_n, w_t), outputs (a_1 … a_n, 0), for
// the Taylor flow (references/taylor_flow.hpp), which starts it at (q, t_0, w, 1).
template <SparselyDifferentiated System>
Tape<typename System::Scalar> time_extended_euler_lagrange_tape(const System& system) {
  if (!depends_on_time(system) || !system.derivatives)
    throw std::logic_error("time_extended_euler_lagrange_tape: for an L that depends on t, with its derivative tape");
  return sparse_euler_lagrange_tape(*system.derivatives);
}

// Tape of x'' = a(x, x') extended by its variational equations (formula at the top of the file):
// dimension m(1 + 2m) for a tape of dimension m.
template <class T>
Tape<T> variational_tape(const Tape<T>& base) {
  using S = TapeScalar<T>;
  const int m = base.inputs / 2;
  const int columns = 2 * m;
  const int extended = m * (1 + columns);  // dimension of the extended x
  // Component i of δq^j sits at x index m + j m + i; of δw^j at extended + m + j m + i.
  auto position = [&](int j, int i) { return m + j * m + i; };
  auto velocity = [&](int j, int i) { return extended + m + j * m + i; };
  TapeRecording<T> recording(2 * extended);
  // Replay the base tape once per column in dual numbers (value, tangent); the values are
  // recorded once (equal nodes are shared), the tangents once per column.
  struct Dual {
    S value, tangent;
  };
  std::vector<Dual> value(base.nodes.size());
  std::vector<S> accelerations;
  for (int j = -1; j < columns; ++j) {
    for (std::size_t index = 0; index < base.nodes.size(); ++index) {
      using std::cos;
      using std::exp;
      using std::log;
      using std::pow;
      using std::sin;
      using std::sqrt;
      const TapeNode& node = base.nodes[index];
      Dual& r = value[index];
      const Dual& a = node.a >= 0 && node.op != TapeOp::input ? value[node.a] : r;
      const Dual& b = node.b >= 0 ? value[node.b] : r;
      const S c = node.c >= 0 ? S(base.constants[node.c]) : S(0);
      switch (node.op) {
        case TapeOp::input: {
          const int i = node.a % m;
          const bool is_velocity = node.a >= m;
          r.value = recording.input(is_velocity ? extended + i : i);
          r.tangent = j < 0 ? S(0)
                            : recording.input(is_velocity ? velocity(j, i) : position(j, i));
          break;
        }
        case TapeOp::constant: r = {c, S(0)}; break;
        case TapeOp::add: r = {a.value + b.value, a.tangent + b.tangent}; break;
        case TapeOp::sub: r = {a.value - b.value, a.tangent - b.tangent}; break;
        case TapeOp::neg: r = {-a.value, -a.tangent}; break;
        case TapeOp::mul:
          r = {a.value * b.value, a.tangent * b.value + a.value * b.tangent};
          break;
        case TapeOp::square: r = {a.value * a.value, 2 * a.value * a.tangent}; break;
        case TapeOp::div: {
          S quotient = a.value / b.value;
          r = {quotient, (a.tangent - quotient * b.tangent) / b.value};
          break;
        }
        case TapeOp::add_constant: r = {a.value + c, a.tangent}; break;
        case TapeOp::constant_minus: r = {c - a.value, -a.tangent}; break;
        case TapeOp::scale: r = {c * a.value, c * a.tangent}; break;
        case TapeOp::constant_div: {
          S quotient = c / a.value;
          r = {quotient, -quotient * a.tangent / a.value};
          break;
        }
        case TapeOp::sin: r = {sin(a.value), cos(a.value) * a.tangent}; break;
        case TapeOp::cos: r = {cos(a.value), -sin(a.value) * a.tangent}; break;
        case TapeOp::exp: {
          S e = exp(a.value);
          r = {e, e * a.tangent};
          break;
        }
        case TapeOp::log: r = {log(a.value), a.tangent / a.value}; break;
        case TapeOp::sqrt: {
          S root = sqrt(a.value);
          r = {root, a.tangent / (2 * root)};
          break;
        }
        case TapeOp::atan: {
          using std::atan;
          r = {atan(a.value), a.tangent / b.value};  // b = 1 + a²
          break;
        }
        case TapeOp::pow: {
          S p = pow(a.value, c);
          r = {p, c * p / a.value * a.tangent};
          break;
        }
      }
    }
    for (int output : base.outputs) {
      accelerations.push_back(j < 0 ? value[output].value : value[output].tangent);
    }
  }
  return recording.finish(accelerations);
}

}  // namespace vivv
