// The Lagrangian concept and what core/ derives from it (docs/theory.md).
//
// A system supplies L(q, w) once, templated on the scalar S, plus its
// configuration dimension n. Everything else — momentum, Euler–Lagrange
// acceleration, energy — comes from forward-mode automatic differentiation.
#pragma once

#include <array>
#include <concepts>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/autodiff/jet.hpp"
#include "core/autodiff/sparse_hessian.hpp"
#include "core/numerics/linear_solve.hpp"
#include "core/numerics/scalar.hpp"

namespace vivv {

// The evaluations of L in this thread, counted by every system vivv runs (the catalogue's and
// formula systems): a run's cost that does not depend on the machine (its work-precision
// diagram). Counting is one increment per evaluation, in any scalar or jet; a system sized at run
// time counts each run of L's derivative tape as one evaluation (lagrangian_tape below).
inline thread_local long lagrangian_evaluations = 0;
inline void count_lagrangian_evaluation() { ++lagrangian_evaluations; }

// What a system of fixed dimension n writes its L for: `S lagrangian(const Point<S, n>& q, const
// Point<S, n>& w)` (S deduced). A system of any_size takes any container P: `template <class P>
// auto lagrangian(const P& q, const P& w)`, its scalar P::value_type.
template <class S, int n>
using Point = std::array<S, n>;

// Coordinates of `size` components (the fixed ones: n), value-initialized.
template <class S, int n>
Coordinates<S, n> make_point(int size) {
  if constexpr (n == any_size) {
    return Coordinates<S, n>(static_cast<std::size_t>(size));
  } else {
    (void)size;
    return Coordinates<S, n>{};
  }
}

// The same coordinates as a Point (what L takes) and as a Vector (what the solvers take).
template <class S, int n>
Coordinates<S, n> as_point(const Vector<S, n>& v) {
  Coordinates<S, n> p = make_point<S, n>(static_cast<int>(v.size()));
  for (int i = 0; i < static_cast<int>(v.size()); ++i) p[i] = v[i];
  return p;
}

template <class S, int n>
Vector<S, n> as_vector(const Coordinates<S, n>& p) {
  const int size = static_cast<int>(p.size());
  Vector<S, n> v(size);
  for (int i = 0; i < size; ++i) v[i] = p[i];
  return v;
}

// A system's number of coordinates: its compile-time dimension, or (any_size) its own size().
template <class System>
int dimension_of(const System& system) {
  if constexpr (System::dimension == any_size)
    return system.size();
  else
    return (void)system, System::dimension;
}

// A Lagrangian system on Q = R^n with parameters in the scalar Scalar, whose
// L can be evaluated in Scalar and in jets over it.
template <class System>
concept LagrangianSystem = requires(const System& system,
                                    const Coordinates<typename System::Scalar, System::dimension>& x,
                                    const Coordinates<Jet<typename System::Scalar, twice(System::dimension)>,
                                                System::dimension>& jet_x) {
  typename System::Scalar;
  { System::dimension } -> std::convertible_to<int>;
  { system.lagrangian(x, x) } -> std::convertible_to<typename System::Scalar>;
  { system.lagrangian(jet_x, jet_x) };
};

// A vector in a system's scalar and dimension — a configuration, a velocity or a momentum — as
// the solvers take it; in signatures, `const VectorOf<System>& q`.
template <class System>
using VectorOf = Vector<typename System::Scalar, System::dimension>;

// A system sized at run time that carries its L's gradient and sparse Hessian as a tape over
// (q, w) (core/autodiff/sparse_hessian.hpp; a formula system of 3 or more coordinates): its
// derivatives are read from that tape, whose cost grows like L's, instead of from dense jets.
template <class System>
concept SparselyDifferentiated =
    LagrangianSystem<System> && System::dimension == any_size && requires(const System& system) {
      { *system.derivatives } -> std::convertible_to<const SecondDerivativeTape<typename System::Scalar>&>;
    };

// Time. A system whose L depends on t (a formula system whose L uses t: `timed`) carries the time
// its L is evaluated at (`time`): at_time(system, t) is the same system at t, and what reads L at
// a state — momentum, energy, the Euler–Lagrange acceleration — reads it at the system's time. A
// discrete Lagrangian on (q_b, q_e) starts at the system's time t_b and evaluates L at its
// quadrature's times t_b + c·h (core/qxq/discrete_lagrangian.hpp). Every other system is
// autonomous, at time 0, and at_time leaves it as it is.
template <class System>
concept CarriesTime = requires(const System& system) {
  { system.timed } -> std::convertible_to<bool>;
  { system.time } -> std::convertible_to<typename System::Scalar>;
};

template <class System>
bool depends_on_time(const System& system) {
  if constexpr (CarriesTime<System>) return system.timed;
  else return (void)system, false;
}

template <class System>
typename System::Scalar system_time(const System& system) {
  if constexpr (CarriesTime<System>) return system.time;
  else return (void)system, typename System::Scalar(0);
}

template <class System>
System at_time(System system, const typename System::Scalar& t) {
  if constexpr (CarriesTime<System>) system.time = t;
  else (void)t;
  return system;
}

// L(q, w) at time t (an autonomous system's L at any t).
template <class System, class P>
auto lagrangian_at(const System& system, const typename System::Scalar& t, const P& q, const P& w) {
  if constexpr (CarriesTime<System>) return system.lagrangian_at(t, q, w);
  else return (void)t, system.lagrangian(q, w);
}

// The inputs of L's tape, (q, w) and, for an L that depends on t, the time after them (index 2n):
// 2n or 2n + 1 numbers, the time set to the system's, (q, w) to zero.
template <SparselyDifferentiated System>
std::vector<typename System::Scalar> lagrangian_tape_inputs(const System& system, int n) {
  std::vector<typename System::Scalar> x(2 * n + (depends_on_time(system) ? 1 : 0));
  if (depends_on_time(system)) x[2 * n] = system_time(system);
  return x;
}

// L's value, gradient and, with `hessian`, the entries of its sparse Hessian at x = (q, w) (2n
// numbers, and the time after them for an L that depends on t: lagrangian_tape_inputs) from such
// a system's tape: one evaluation of L, counted as the dense path counts one. Its gradient and
// Hessian are over all of its inputs, t's included, so a reader of (q, w)'s entries skips those in
// row 2n. Every reader of L's tape goes through here, so that none forgets the count.
template <SparselyDifferentiated System>
EdgePushed<typename System::Scalar> lagrangian_tape(const System& system, const typename System::Scalar* x,
                                                    bool hessian = true) {
  count_lagrangian_evaluation();
  return hessian ? system.derivatives->evaluate(x) : system.derivatives->evaluate_gradient(x);
}

// The same at (q, w) given apart.
template <SparselyDifferentiated System>
EdgePushed<typename System::Scalar> lagrangian_tape(const System& system, const VectorOf<System>& q,
                                                    const VectorOf<System>& w, bool hessian = true) {
  const int n = static_cast<int>(q.size());
  std::vector<typename System::Scalar> x = lagrangian_tape_inputs(system, n);
  for (int i = 0; i < n; ++i) x[i] = q[i], x[n + i] = w[i];
  return lagrangian_tape(system, x.data(), hessian);
}

// L's value and gradient over (q, w) from such a system's tape.
template <SparselyDifferentiated System>
EdgePushed<typename System::Scalar> sparse_gradient(const System& system, const VectorOf<System>& q,
                                                    const VectorOf<System>& w) {
  return lagrangian_tape(system, q, w, false);
}

// Thrown when d²L/dw² is singular at a state the computation visits.
struct SingularLagrangianError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// L and its first and second derivatives at (q, w).
template <class T, int n>
struct LagrangianDerivatives {
  explicit LagrangianDerivatives(int size)
      : dL_dq(size), dL_dw(size), d2L_dw2(size, size), d2L_dwdq(size, size) {}
  T value;
  Vector<T, n> dL_dq;
  Vector<T, n> dL_dw;
  Matrix<T, n, n> d2L_dw2;   // the mass matrix M
  Matrix<T, n, n> d2L_dwdq;  // entry (i, j) = ∂²L / ∂w_i ∂q_j
};

// dL/dq, dL/dw, d²L/dw², d²L/dw dq at (q, w) by automatic differentiation.
template <LagrangianSystem System>
auto lagrangian_derivatives(const System& system,
                            const VectorOf<System>& q, const VectorOf<System>& w) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q.size());
  if constexpr (SparselyDifferentiated<System>) {
    if (system.derivatives) {
      const EdgePushed<T> L = lagrangian_tape(system, q, w);
      LagrangianDerivatives<T, N> d(n);
      d.d2L_dw2.setZero(), d.d2L_dwdq.setZero();
      d.value = L.value;
      for (int i = 0; i < n; ++i) d.dL_dq[i] = L.gradient[i], d.dL_dw[i] = L.gradient[n + i];
      for (std::size_t e = 0; e < L.hessian.size(); ++e) {
        const auto [r, c] = system.derivatives->pattern[e];  // r >= c
        if (r >= 2 * n) continue;  // an entry in t
        if (c >= n) d.d2L_dw2(r - n, c - n) = d.d2L_dw2(c - n, r - n) = L.hessian[e];
        else if (r >= n) d.d2L_dwdq(r - n, c) = L.hessian[e];
      }
      return d;
    }
  }
  using J = Jet<T, twice(N)>;
  Coordinates<J, N> jet_q = make_point<J, N>(n), jet_w = make_point<J, N>(n);
  for (int i = 0; i < n; ++i) {
    jet_q[i] = J::variable(q[i], i, 2 * n);
    jet_w[i] = J::variable(w[i], n + i, 2 * n);
  }
  const J L = with_size(J(system.lagrangian(jet_q, jet_w)), 2 * n);
  LagrangianDerivatives<T, N> d(n);
  d.value = L.value;
  for (int i = 0; i < n; ++i) {
    d.dL_dq[i] = L.gradient[i];
    d.dL_dw[i] = L.gradient[n + i];
    for (int j = 0; j < n; ++j) {
      d.d2L_dw2(i, j) = L.second(n + i, n + j);
      d.d2L_dwdq(i, j) = L.second(n + i, j);
    }
  }
  return d;
}

// L(q, w) as a jet in w alone, q held constant: ∂L/∂w (Order 1), and ∂²L/∂w² too (Order 2).
// Where nothing else is used — the momentum, the energy, the inverse Legendre transform — this
// carries n + 1 (or 1 + n + n²) numbers instead of lagrangian_derivatives' 1 + 2n + 4n², and
// gives the same numbers bit for bit: a jet's w-entries are never computed from its q-entries.
template <int Order, LagrangianSystem System>
auto lagrangian_in_velocity(const System& system,
                            const VectorOf<System>& q, const VectorOf<System>& w) {
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q.size());
  using J = Jet<typename System::Scalar, N, Order>;
  Coordinates<J, N> jet_q = make_point<J, N>(n), jet_w = make_point<J, N>(n);
  for (int i = 0; i < n; ++i) {
    jet_q[i] = J(q[i]);
    jet_w[i] = J::variable(w[i], i, n);
  }
  return with_size(J(system.lagrangian(jet_q, jet_w)), n);
}

// Momentum p = FL(q, w) = dL/dw.
template <LagrangianSystem System>
auto momentum(const System& system, const VectorOf<System>& q,
              const VectorOf<System>& w) {
  if constexpr (SparselyDifferentiated<System>) {
    if (system.derivatives) {
      const int n = static_cast<int>(q.size());
      const auto L = sparse_gradient(system, q, w);
      VectorOf<System> p(n);
      for (int i = 0; i < n; ++i) p[i] = L.gradient[n + i];
      return p;
    }
  }
  const auto L = lagrangian_in_velocity<1>(system, q, w);
  VectorOf<System> p(q.size());
  for (int i = 0; i < static_cast<int>(q.size()); ++i) p[i] = L.gradient[i];
  return p;
}

// Energy E = dL/dw · w − L.
template <LagrangianSystem System>
auto energy(const System& system, const VectorOf<System>& q,
            const VectorOf<System>& w) {
  using T = typename System::Scalar;
  if constexpr (SparselyDifferentiated<System>) {
    if (system.derivatives) {
      const int n = static_cast<int>(q.size());
      const auto L = sparse_gradient(system, q, w);
      T energy = -L.value;
      for (int i = 0; i < n; ++i) energy += L.gradient[n + i] * w[i];
      return energy;
    }
  }
  const auto L = lagrangian_in_velocity<1>(system, q, w);
  T energy = -L.value;
  for (int i = 0; i < static_cast<int>(q.size()); ++i) energy += L.gradient[i] * w[i];
  return energy;
}

// The same as euler_lagrange_acceleration below, from L's sparse derivatives: M and d²L/dw dq as
// sparse matrices, M factored sparse, with the dense path's test of a singular M.
template <SparselyDifferentiated System>
auto sparse_euler_lagrange_acceleration(const System& system, const VectorOf<System>& q, const VectorOf<System>& w) {
  using T = typename System::Scalar;
  using std::isfinite;
  const int n = static_cast<int>(q.size());
  const EdgePushed<T> L = lagrangian_tape(system, q, w);
  if (!isfinite(L.value))
    throw SingularLagrangianError("L(q, w) is not finite at q = " + to_decimal<T>(q[0]) + ", w = " +
                                  to_decimal<T>(w[0]) + ": the state is outside the Lagrangian's domain");
  Vector<T, any_size> rhs(n);
  for (int i = 0; i < n; ++i) rhs[i] = L.gradient[i];
  std::vector<Eigen::Triplet<T>> mass;
  for (std::size_t e = 0; e < L.hessian.size(); ++e) {
    const auto [r, c] = system.derivatives->pattern[e];  // r >= c
    if (r == 2 * n) {
      // An L that depends on t: d/dt ∂L/∂w holds ∂²L/∂w∂t too (Marsden & West §4).
      if (c >= n && c < 2 * n) rhs[c - n] -= L.hessian[e];
    } else if (c >= n) {
      mass.emplace_back(r - n, c - n, L.hessian[e]);
      if (r != c) mass.emplace_back(c - n, r - n, L.hessian[e]);
    } else if (r >= n) {
      rhs[r - n] -= L.hessian[e] * w[c];
    }
  }
  Eigen::SparseMatrix<T> M(n, n);
  M.setFromTriplets(mass.begin(), mass.end());
  Vector<T, any_size> acceleration = zero_vector<T, any_size>(n);
  if (!solve_linear(M, rhs, acceleration, T(1024 * epsilon<T>())))
    throw SingularLagrangianError("the Lagrangian is not regular: d2L/dw2 is singular at q = " + to_decimal<T>(q[0]) +
                                  ", w = " + to_decimal<T>(w[0]) + (n > 1 ? " (first components)" : ""));
  return acceleration;
}

// Euler–Lagrange acceleration q'' = M⁻¹ (dL/dq − (d²L/dw dq) w − d²L/dw dt), docs/theory.md.
// A singular (or numerically singular) mass matrix is an error naming the state. The dense path's
// jets hold t constant, so an L that depends on t takes the sparse one.
template <LagrangianSystem System>
auto euler_lagrange_acceleration(const System& system,
                                 const VectorOf<System>& q, const VectorOf<System>& w) {
  using T = typename System::Scalar;
  using std::abs;
  using std::isfinite;
  if constexpr (SparselyDifferentiated<System>) {
    if (system.derivatives) return sparse_euler_lagrange_acceleration(system, q, w);
  }
  if (depends_on_time(system))
    throw std::logic_error("euler_lagrange_acceleration: an L that depends on t needs its derivative tape (∂²L/∂w∂t)");
  auto d = lagrangian_derivatives(system, q, w);
  if (!isfinite(d.value))
    throw SingularLagrangianError("L(q, w) is not finite at q = " + to_decimal<T>(q[0]) +
                                  ", w = " + to_decimal<T>(w[0]) +
                                  ": the state is outside the Lagrangian's domain");
  Eigen::FullPivLU<Matrix<T, System::dimension, System::dimension>> lu(d.d2L_dw2);
  T scale = d.d2L_dw2.cwiseAbs().maxCoeff();
  lu.setThreshold(1024 * epsilon<T>());
  if (!(scale > 0) || !lu.isInvertible()) {
    throw SingularLagrangianError("the Lagrangian is not regular: d2L/dw2 is singular at q = " +
                                  to_decimal<T>(q[0]) + ", w = " + to_decimal<T>(w[0]) +
                                  (q.size() > 1 ? " (first components)" : ""));
  }
  Vector<T, System::dimension> rhs = d.dL_dq - d.d2L_dwdq * w;
  return Vector<T, System::dimension>(lu.solve(rhs));
}

}  // namespace vivv
