// Symmetries and the discrete momentum map (Marsden–West §1.3.3, discrete
// Noether theorem).
//
// A system may declare a one-parameter symmetry group of its Lagrangian by its
// infinitesimal generator ξ(q): the member
//   Coordinates<T, n> symmetry_generator(const Coordinates<T, n>& q) const;
// (and, when the symmetry is known only at run time, bool has_symmetry() const).
// If L_d is invariant too, L_d(exp(sξ) q_b, exp(sξ) q_e) = L_d(q_b, q_e), then
// D1 L_d · ξ(q_b) + D2 L_d · ξ(q_e) = 0, and the DEL conserves the discrete
// momentum map J_k = p_k · ξ(q_k), p_k = −D1 L_d(q_k, q_{k+1}).
#pragma once

#include "core/lagrangian/lagrangian.hpp"

namespace vivv {

template <class System>
concept DeclaresSymmetry = requires(const System& system, const Coordinates<typename System::Scalar, System::dimension>& q) {
  { system.symmetry_generator(q) } -> std::convertible_to<Coordinates<typename System::Scalar, System::dimension>>;
};

// Whether `system` has a declared symmetry.
template <LagrangianSystem System>
bool has_symmetry(const System& system) {
  if constexpr (!DeclaresSymmetry<System>) {
    return false;
  } else if constexpr (requires { system.has_symmetry(); }) {
    return system.has_symmetry();
  } else {
    return true;
  }
}

// ξ(q), the symmetry's generator at q (DeclaresSymmetry systems only).
template <LagrangianSystem System>
VectorOf<System> symmetry_generator(
    const System& system, const VectorOf<System>& q) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  return as_vector<T, N>(system.symmetry_generator(as_point<T, N>(q)));
}

// J = p · ξ(q), the momentum map of the symmetry at (q, p).
template <LagrangianSystem System>
typename System::Scalar momentum_map(const System& system, const VectorOf<System>& q,
                                     const VectorOf<System>& p) {
  return p.dot(symmetry_generator(system, q));
}

}  // namespace vivv
