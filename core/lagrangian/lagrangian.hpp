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

#include "core/autodiff/jet.hpp"
#include "core/numerics/scalar.hpp"

namespace vivv {

// The evaluations of L in this thread, counted by every system vivv runs (the catalogue's and
// formula systems): a run's cost that does not depend on the machine (its work-precision
// diagram). Counting is one increment per evaluation, in any scalar or jet.
inline thread_local long lagrangian_evaluations = 0;
inline void count_lagrangian_evaluation() { ++lagrangian_evaluations; }

template <class S, int n>
using Point = std::array<S, n>;

// The same coordinates as a Point (what L takes) and as a Vector (what the solvers take).
template <class S, int n>
Point<S, n> as_point(const Vector<S, n>& v) {
  Point<S, n> p;
  for (int i = 0; i < n; ++i) p[i] = v[i];
  return p;
}

template <class S, int n>
Vector<S, n> as_vector(const Point<S, n>& p) {
  Vector<S, n> v;
  for (int i = 0; i < n; ++i) v[i] = p[i];
  return v;
}

// A Lagrangian system on Q = R^n with parameters in the scalar Scalar, whose
// L can be evaluated in Scalar and in jets over it.
template <class System>
concept LagrangianSystem = requires(const System& system,
                                    const Point<typename System::Scalar, System::dimension>& x,
                                    const Point<Jet<typename System::Scalar, 2 * System::dimension>,
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

// Thrown when d²L/dw² is singular at a state the computation visits.
struct SingularLagrangianError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// L and its first and second derivatives at (q, w).
template <class T, int n>
struct LagrangianDerivatives {
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
  constexpr int n = System::dimension;
  using J = Jet<T, 2 * n>;
  Point<J, n> jet_q, jet_w;
  for (int i = 0; i < n; ++i) {
    jet_q[i] = J::variable(q[i], i);
    jet_w[i] = J::variable(w[i], n + i);
  }
  J L = system.lagrangian(jet_q, jet_w);
  LagrangianDerivatives<T, n> d;
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
  using J = Jet<typename System::Scalar, System::dimension, Order>;
  Point<J, System::dimension> jet_q, jet_w;
  for (int i = 0; i < System::dimension; ++i) {
    jet_q[i] = J(q[i]);
    jet_w[i] = J::variable(w[i], i);
  }
  return J(system.lagrangian(jet_q, jet_w));
}

// Momentum p = FL(q, w) = dL/dw.
template <LagrangianSystem System>
auto momentum(const System& system, const VectorOf<System>& q,
              const VectorOf<System>& w) {
  const auto L = lagrangian_in_velocity<1>(system, q, w);
  VectorOf<System> p;
  for (int i = 0; i < System::dimension; ++i) p[i] = L.gradient[i];
  return p;
}

// Energy E = dL/dw · w − L.
template <LagrangianSystem System>
auto energy(const System& system, const VectorOf<System>& q,
            const VectorOf<System>& w) {
  using T = typename System::Scalar;
  const auto L = lagrangian_in_velocity<1>(system, q, w);
  T energy = -L.value;
  for (int i = 0; i < System::dimension; ++i) energy += L.gradient[i] * w[i];
  return energy;
}

// Euler–Lagrange acceleration q'' = M⁻¹ (dL/dq − (d²L/dw dq) w), docs/theory.md.
// A singular (or numerically singular) mass matrix is an error naming the state.
template <LagrangianSystem System>
auto euler_lagrange_acceleration(const System& system,
                                 const VectorOf<System>& q, const VectorOf<System>& w) {
  using T = typename System::Scalar;
  using std::abs;
  using std::isfinite;
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
                                  (System::dimension > 1 ? " (first components)" : ""));
  }
  Vector<T, System::dimension> rhs = d.dL_dq - d.d2L_dwdq * w;
  return Vector<T, System::dimension>(lu.solve(rhs));
}

}  // namespace vivv
