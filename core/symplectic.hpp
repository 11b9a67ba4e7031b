// Symplecticity of one-step maps on (q, p) (docs/theory.md (structure)).
//
// The DEL of L_d is, on (q, p), the map (q_k, p_k) ↦ (q_{k+1}, p_{k+1}) with
//   p_k     = p_begin[L_d](q_k, q_{k+1})    (solved for q_{k+1}),
//   p_{k+1} = p_end[L~_d](q_k, q_{k+1}),
// L~_d the past side (= L_d unless the DEL is mismatched). Its Jacobian follows
// from the implicit function theorem with the blocks of the Hessians of L_d and
// L~_d (core/discrete_lagrangian.hpp): writing B_b, B_e for ∂p_begin/∂q_b,
// ∂p_begin/∂q_e of L_d and E_b, E_e for ∂p_end/∂q_b, ∂p_end/∂q_e of L~_d,
//   ∂q_{k+1}/∂(q_k, p_k) = B_e⁻¹·(−B_b, I),
//   ∂p_{k+1}/∂(q_k, p_k) = (E_b, 0) + E_e·∂q_{k+1}/∂(q_k, p_k).
// A map with Jacobian J is symplectic when JᵀΩJ = Ω, Ω = [[0, I], [−I, 0]]:
// for L~_d = L_d the mixed Hessian block is shared and the identity holds
// exactly (Marsden–West §1.3.2); for two different rules the defect is the
// difference of their mixed blocks.
#pragma once

#include "core/discrete_lagrangian.hpp"

namespace vivv {

// The Jacobian ∂(q_{k+1}, p_{k+1})/∂(q_k, p_k) of the DEL's (q, p) map from the
// derivatives of L_d (future) and L~_d (past) at (q_k, q_{k+1}).
template <class T, int n>
Matrix<T, 2 * n, 2 * n> del_map_jacobian(const DiscreteLegendre<T, n>& future, const DiscreteLegendre<T, n>& past) {
  Matrix<T, n, 2 * n> right;  // (−B_b, I)
  right.template leftCols<n>() = -future.dp_begin_dq_b;
  right.template rightCols<n>().setIdentity();
  const Matrix<T, n, 2 * n> dq_next = future.dp_begin_dq_e.partialPivLu().solve(right);
  Matrix<T, 2 * n, 2 * n> jacobian;
  jacobian.template topRows<n>() = dq_next;
  jacobian.template bottomRows<n>() = past.dp_end_dq_e * dq_next;
  jacobian.template bottomLeftCorner<n, n>() += past.dp_end_dq_b;
  return jacobian;
}

// max |a_ij|.
template <class T, int rows, int cols>
T max_entry(const Matrix<T, rows, cols>& a) {
  using std::abs, std::max;
  T largest = 0;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) largest = max(largest, T(abs(a(i, j))));
  return largest;
}

// max |(JᵀΩJ − Ω)_ij|: zero for a symplectic map.
template <class T, int m>
T symplecticity_defect(const Matrix<T, m, m>& jacobian) {
  static_assert(m % 2 == 0, "a map on (q, p) has an even dimension");
  constexpr int n = m / 2;
  Matrix<T, m, m> omega = Matrix<T, m, m>::Zero();
  omega.template topRightCorner<n, n>().setIdentity();
  omega.template bottomLeftCorner<n, n>() = -Matrix<T, n, n>::Identity();
  return max_entry<T, m, m>(Matrix<T, m, m>(jacobian.transpose() * omega * jacobian - omega));
}

}  // namespace vivv
