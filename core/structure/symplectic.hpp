// Symplecticity of one-step maps on (q, p) (docs/theory.md (structure)).
//
// The DEL of L_d is, on (q, p), the map (q_k, p_k) ↦ (q_{k+1}, p_{k+1}) with
//   p_k     = p_begin[L_d](q_k, q_{k+1})    (solved for q_{k+1}),
//   p_{k+1} = p_end[L~_d](q_k, q_{k+1}),
// L~_d the past side (= L_d unless the DEL is mismatched). Its Jacobian follows
// from the implicit function theorem with the blocks of the Hessians of L_d and
// L~_d (core/qxq/discrete_lagrangian.hpp): writing B_b, B_e for ∂p_begin/∂q_b,
// ∂p_begin/∂q_e of L_d and E_b, E_e for ∂p_end/∂q_b, ∂p_end/∂q_e of L~_d,
//   ∂q_{k+1}/∂(q_k, p_k) = B_e⁻¹·(−B_b, I),
//   ∂p_{k+1}/∂(q_k, p_k) = (E_b, 0) + E_e·∂q_{k+1}/∂(q_k, p_k).
// A map with Jacobian J is symplectic when JᵀΩJ = Ω, Ω = [[0, I], [−I, 0]]:
// for L~_d = L_d the mixed Hessian block is shared and the identity holds
// exactly (Marsden–West §1.3.2); for two different rules the defect is the
// difference of their mixed blocks.
#pragma once

#include <vector>

#include "core/qxq/discrete_lagrangian.hpp"

namespace vivv {

// The Jacobian ∂(q_{k+1}, p_{k+1})/∂(q_k, p_k) of the DEL's (q, p) map from the
// derivatives of L_d (future) and L~_d (past) at (q_k, q_{k+1}).
template <class T, int N>
Matrix<T, twice(N), twice(N)> del_map_jacobian(const DiscreteLegendre<T, N>& future, const DiscreteLegendre<T, N>& past) {
  const int n = static_cast<int>(future.p_begin.size());
  Matrix<T, N, twice(N)> right(n, 2 * n);  // (−B_b, I)
  right.leftCols(n) = -future.dp_begin_dq_b;
  right.rightCols(n).setIdentity();
  const Matrix<T, N, twice(N)> dq_next = future.dp_begin_dq_e.partialPivLu().solve(right);
  Matrix<T, twice(N), twice(N)> jacobian(2 * n, 2 * n);
  jacobian.topRows(n) = dq_next;
  jacobian.bottomRows(n) = past.dp_end_dq_e * dq_next;
  jacobian.bottomLeftCorner(n, n) += past.dp_end_dq_b;
  return jacobian;
}

// max |a_ij|; NaN when an entry is NaN (a Jacobian whose JᵀΩJ overflowed must not measure 0).
template <class T, int rows, int cols>
T max_entry(const Matrix<T, rows, cols>& a) {
  using std::abs;
  T largest = 0;
  for (int i = 0; i < a.rows(); ++i)
    for (int j = 0; j < a.cols(); ++j) largest = nan_max(largest, T(abs(a(i, j))));
  return largest;
}

// max |(JᵀΩJ − Ω)_ij|: zero for a symplectic map. Formed densely (16 n³ multiplications): from
// J's n × n blocks it would take 4 n³, but its other rounding moved which step symplecticity
// judges, and on the stiff Fermi–Pasta–Ulam chain that step's exact midpoint Jacobian missed
// central differences of its map (9.7e-7 against an allowance of 6.2e-7 in double, at widths δ
// and 4δ alike): compare_with_differences's rounding estimate must be made sound first.
template <class T, int m>
T symplecticity_defect(const Matrix<T, m, m>& jacobian) {
  static_assert(m == any_size || m % 2 == 0, "a map on (q, p) has an even dimension");
  const int n = static_cast<int>(jacobian.rows()) / 2;
  Matrix<T, m, m> omega = zero_matrix<T, m, m>(2 * n, 2 * n);
  omega.topRightCorner(n, n).setIdentity();
  omega.bottomLeftCorner(n, n).setIdentity();
  omega.bottomLeftCorner(n, n) *= T(-1);
  return max_entry<T, m, m>(Matrix<T, m, m>(jacobian.transpose() * omega * jacobian - omega));
}

// A symplectic change of coordinates that balances a Jacobian on (q, p): q̃_i = 2^e_i q_i,
// p̃_i = 2^−e_i p_i, so that J̃ = S J S⁻¹ with S = diag(2^e, 2^−e), entry by entry
// J̃_ij = 2^(g_i − g_j) J_ij, g = (e, −e). S is symplectic, so J̃ᵀΩJ̃ = Ω exactly when JᵀΩJ = Ω,
// and powers of two scale without rounding. With e_i ≈ log2 √M_ii (M the mass matrix) a body of
// mass m has ∂q̃/∂p̃ ≈ h instead of h/m: the outer solar system's Pluto (m = 7.7·10⁻⁹ of the Sun)
// gave entries of 2.6·10⁹ whose rounding, ε·|J|², swamped |Ω| = 1 in double.
template <class T, int m>
Matrix<T, m, m> balanced(const Matrix<T, m, m>& jacobian, const std::vector<int>& exponents) {
  using std::ldexp;
  const int n = static_cast<int>(jacobian.rows()) / 2;
  if (exponents.empty()) return jacobian;
  auto g = [&](int i) { return i < n ? exponents[i] : -exponents[i - n]; };
  Matrix<T, m, m> out = jacobian;
  for (int j = 0; j < 2 * n; ++j)
    for (int i = 0; i < 2 * n; ++i)
      if (g(i) != g(j)) out(i, j) = ldexp(T(jacobian(i, j)), g(i) - g(j));
  return out;
}

// Whether a Jacobian belongs to the map it is claimed for: central differences D_δ of the map
// itself at x, at widths δ, δ/2 and δ/4 per coordinate, δ_j = ε^{1/3}·max(|x_j|, scale_j) —
// `scale` the size of each coordinate along the run, so that a momentum passing near zero at a
// turning point is not perturbed by a width its rounding swamps. `jacobian` is compared with
// D_δ, whose error is its truncation t (O(δ²)) and the map's rounding r over δ: the changes
// |D_δ − D_δ/2| ≈ |3t/4 ± r·(1 + 2)| and |D_δ/2 − D_δ/4| ≈ r·(2 + 4) carry both (the rounding
// grows as the width shrinks, so the second change measures it even when the first happens to
// cancel), and J may differ from D_δ by 4 × the larger change + √ε·|J|. Calibrated on midpoint,
// trapezoid and Galerkin DELs and odeint's steppers on the pendulum, Duffing, Kepler and
// Hénon–Heiles in double, long double, float128 and MPFR. A Jacobian of another step or of a
// step of h/2, of the other side of a mismatched DEL, or with a block dropped misses by O(h) or
// more. ε is `unit`: T's unit roundoff, or a double's for a map that computes in double while
// vivv computes in a wider T.
template <class T>
struct JacobianAgreement {
  T mismatch = 0;  // max |J − D_δ|
  T allowed = 0;   // 4·max(|D_δ − D_δ/2|, |D_δ/2 − D_δ/4|) + √ε·max |J|
  bool holds = true;
};

template <class T, int m, class Map>
JacobianAgreement<T> compare_with_differences(const Map& map, const Vector<T, m>& x,
                                              const Matrix<T, m, m>& jacobian,
                                              const Vector<T, m>& scale,
                                              const T& unit = epsilon<T>()) {
  using std::abs, std::max, std::pow, std::sqrt;
  const T root = pow(unit, T(1) / 3);
  auto differences = [&](const T& fraction) {
    const int size = static_cast<int>(x.size());
    Matrix<T, m, m> d(size, size);
    for (int j = 0; j < size; ++j) {
      T width = max(T(abs(x[j])), T(abs(scale[j])));
      if (width == 0) width = 1;
      width *= root * fraction;
      Vector<T, m> up = x, down = x;
      up[j] += width;
      down[j] -= width;
      d.col(j) = (map(up) - map(down)) / (up[j] - down[j]);
    }
    return d;
  };
  const Matrix<T, m, m> coarse = differences(T(1)), middle = differences(T(1) / 2),
                        fine = differences(T(1) / 4);
  JacobianAgreement<T> out;
  out.mismatch = max_entry<T, m, m>(Matrix<T, m, m>(jacobian - coarse));
  const T change = nan_max(max_entry<T, m, m>(Matrix<T, m, m>(coarse - middle)),
                           max_entry<T, m, m>(Matrix<T, m, m>(middle - fine)));
  out.allowed = 4 * change + sqrt(unit) * max_entry<T, m, m>(jacobian);
  out.holds = out.mismatch <= out.allowed;
  return out;
}

}  // namespace vivv
