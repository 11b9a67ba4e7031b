// Modified energies of the midpoint and trapezoid rules (backward error
// analysis; docs/theory.md, "Modified energy").
//
// For L = ½|w|² − U(q) the two rules' DELs are, on (q, p) with
// p_k = −D1 L_d(q_k, q_{k+1}), known one-step methods for H = ½|p|² + U(q):
//   midpoint  L_d = h L((q_b + q_e)/2, (q_e − q_b)/h): the implicit midpoint rule
//             (an implicit Euler half step to the midpoint, an explicit one on);
//   trapezoid L_d = h (½|Δq/h|² − (U(q_b) + U(q_e))/2): Störmer–Verlet,
//             velocity form (kick, drift, kick).
// Each conserves a modified energy H̃ = H + h² H₂ + O(h⁴), with H₂ a quadratic
// form in U', U'' and p (Hairer–Lubich–Wanner IX.3; Vermeeren 2017):
//   midpoint   H₂ = −(1/24) (pᵀU''p + |U'|²),
//   trapezoid  H₂ =  (1/12) pᵀU''p − (1/24) |U'|².
// Derivation by the harmonic oscillator (U = q²/2, H₂ = c₁p² + c₂q²): the
// modified flow rotates at ω̃ = 2√((½ + c₁h²)(½ + c₂h²)) = 1 + (c₁ + c₂)h² + O(h⁴),
// which must be the map's exact frequency — (2/h)·arctan(h/2) = 1 − h²/12 for
// midpoint, (2/h)·arcsin(h/2) = 1 + h²/24 for trapezoid — and H̃ must be
// (a function of) the map's exact quadratic invariant — H itself for midpoint
// (c₁ = c₂), p² + (1 − h²/4)q² for trapezoid (c₂ − c₁ = −1/8). Hence
// c₁ = c₂ = −1/24, and c₁ = 1/12, c₂ = −1/24. A nonlinear system (the
// pendulum) then checks the form: H̃ is conserved to O(h⁴), H only to O(h²)
// (tests/core/structure/modified_energy_test.cpp).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "core/qxq/discrete_lagrangian.hpp"
#include "core/autodiff/jet.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "core/lagrangian/state.hpp"

namespace vivv {

// U'(q) and U''(q) of U(q) = −L(q, 0), by automatic differentiation.
template <class T, int n>
struct PotentialDerivatives {
  explicit PotentialDerivatives(int size) : gradient(size), hessian(size, size) {}
  T value;
  Vector<T, n> gradient;
  Matrix<T, n, n> hessian;
};

template <LagrangianSystem System>
auto potential_derivatives(const System& system, const VectorOf<System>& q) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q.size());
  using J = Jet<T, N>;
  Coordinates<J, N> jet_q = make_point<J, N>(n), zero = make_point<J, N>(n);
  for (int i = 0; i < n; ++i) jet_q[i] = J::variable(q[i], i, n), zero[i] = J(T(0));
  const J L = with_size(J(system.lagrangian(jet_q, zero)), n);
  PotentialDerivatives<T, N> U(n);
  U.value = -L.value;
  for (int i = 0; i < n; ++i) {
    U.gradient[i] = -L.gradient[i];
    for (int j = 0; j < n; ++j) U.hessian(i, j) = -L.second(i, j);
  }
  return U;
}

// The coefficients of H₂ = (pUp · pᵀU''p + UU · |U'|²) / 24 for a rule, in 24ths (exact in any T).
struct ModifiedEnergyForm {
  int pUp, UU;
};

// The form of `rule` (midpoint or trapezoid), as derived at the top of the file.
inline ModifiedEnergyForm modified_energy_form(QxQRule rule) {
  if (rule == QxQRule::midpoint) return {-1, -1};
  if (rule == QxQRule::trapezoid) return {2, -1};
  throw std::invalid_argument("modified energy: derived for the midpoint and trapezoid rules only, not " +
                              rule_name(rule));
}

// H(q, p) = ½|p|² + U(q) and H̃ = H + h² (pUp · pᵀU''p + UU · |U'|²) / 24, for L = ½|w|² − U(q).
template <class T>
struct ModifiedEnergy {
  T H, modified;
};

template <LagrangianSystem System>
auto modified_energy(const System& system, const ModifiedEnergyForm& form,
                     const VectorOf<System>& q,
                     const VectorOf<System>& p, const typename System::Scalar& h) {
  using T = typename System::Scalar;
  const auto U = potential_derivatives(system, q);
  const T H = p.squaredNorm() / 2 + U.value;
  const T correction = (form.pUp * T(p.dot(U.hessian * p)) + form.UU * T(U.gradient.squaredNorm())) / 24;
  return ModifiedEnergy<T>{H, T(H + h * h * correction)};
}

// Where L = ½|w|² − U(q) fails among `samples`: a mass matrix ∂²L/∂w² other than I, a w–q
// coupling ∂²L/∂w∂q, or a term linear in w, ∂L/∂w(q, 0) ≠ 0 (then p ≠ w, and H = ½|p|² + U is
// not the energy), each to 1024 ulps of its scale; a NaN is a failure too. Empty when every
// sample is of that form. Several samples along the motion, because one can be fooled: a mass
// 1 + (x − 1.1)² is 1 at x = 1.1, and a null term 0.3·w leaves both second derivatives alone.
template <LagrangianSystem System>
std::string unit_mass_defect(
    const System& system,
    const std::vector<State<typename System::Scalar, System::dimension>>& samples) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  using std::max;
  T speed = 0;
  for (const auto& x : samples) speed = max(speed, T(max_norm<T, n>(x.w)));
  const T tolerance = 1024 * epsilon<T>();
  for (const auto& x : samples) {
    const auto d = lagrangian_derivatives(system, x.q, x.w);
    const int size = static_cast<int>(x.q.size());
    const T mass =
        Matrix<T, n, n>(d.d2L_dw2 - Matrix<T, n, n>::Identity(size, size)).cwiseAbs().maxCoeff();
    const T coupling = d.d2L_dwdq.cwiseAbs().maxCoeff();
    const T linear = max_norm<T, n>(momentum(system, x.q, zero_vector<T, n>(size)));
    const std::string at = " at q = " + to_decimal<T>(x.q[0], 6) + (size > 1 ? ", …" : "") +
                           ", w = " + to_decimal<T>(x.w[0], 6) + (size > 1 ? ", …" : "");
    if (!(mass <= tolerance))
      return "|d2L/dw2 - I| = " + to_decimal<T>(mass, 3) + at + " (a mass matrix other than I)";
    if (!(coupling <= tolerance * max(T(1), speed)))
      return "|d2L/dw dq| = " + to_decimal<T>(coupling, 3) + at + " (L couples w and q)";
    if (!(linear <= tolerance * max(T(1), speed)))
      return "|dL/dw(q, 0)| = " + to_decimal<T>(linear, 3) + at +
             " (a term linear in w: p = w + dL/dw(q, 0) is not w)";
  }
  return "";
}

}  // namespace vivv
