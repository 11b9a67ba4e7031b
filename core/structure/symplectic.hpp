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

#include <limits>
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
// S v (sign 1) or S⁻¹ v (sign −1) for a vector v on (q, p), with S = diag(2^e, 2^−e) as above: what
// the probes apply J̃ = S J S⁻¹ through, without forming J. No exponents: v itself.
template <class T, int m>
Vector<T, m> balanced_vector(Vector<T, m> v, const std::vector<int>& exponents, int sign) {
  using std::ldexp;
  if (exponents.empty()) return v;
  const int n = static_cast<int>(v.size()) / 2;
  for (int i = 0; i < n; ++i) {
    v[i] = ldexp(T(v[i]), sign * exponents[i]);
    v[n + i] = ldexp(T(v[n + i]), -sign * exponents[i]);
  }
  return v;
}

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
//
// The changes miss a rounding that drifts with the width instead of scattering: a DEL step
// q' = q + s(q) solved by Newton lands on the representable q' nearest the solution, and since
// q' moves with q almost one for one (∂q'/∂q ≈ 1), its distance to that nearest number moves by
// (∂q'/∂q − 1)·δ, under an ulp and linearly in δ at every width — the same error in D_δ, D_δ/2
// and D_δ/4, and in p' = p_end(q, q') amplified by ∂p_end/∂q' ≈ 1/h. The midpoint rule on the
// pendulum in double at h = 2.5·10⁻⁴ showed D − J = 4.0·10⁻⁸ in ∂p'/∂(q, p) at all three widths
// (J correct to 7·10⁻¹³ against 40-digit arithmetic), changes of 10⁻¹², and an allowance of
// 1.5·10⁻⁸: vivv's own check said error on a correct method. Where the map's outputs carry a
// known rounding r_i (`output_rounding`: for a DEL step ε·|q'| in q', and in p' ε times the terms
// of p_end, Σ_j |∂p_end/∂(q, q')_ij|·|q_j|), entry (i, j) may differ by that much more, 2·r_i/δ_j;
// the verdict is the entry worst against its own allowance. A wrong Jacobian's O(h) miss stays
// above it while h > ε^{1/3} (r_i/δ_j ≈ ε^{2/3}/h).
template <class T>
struct JacobianAgreement {
  T mismatch = 0;  // |J − D_δ| at the entry worst against its allowance
  T allowed = 0;   // there: 4·max(|D_δ − D_δ/2|, |D_δ/2 − D_δ/4|) + √ε·max |J| + 2·r_i/δ_j
  bool holds = true;

  // One entry's `miss` against its own allowance `bound`: the entry reported is the worst against
  // its allowance, and a NaN anywhere is the worst of all (no comparison with it holds). Entry by
  // entry from the first (holds set true before it).
  void add_entry(const T& miss, const T& bound) {
    using std::isfinite;
    const bool entry_holds = miss <= bound;
    T ratio = bound > 0 ? T(miss / bound) : T(entry_holds ? 0 : 2);
    if (!isfinite(static_cast<T>(ratio))) ratio = std::numeric_limits<T>::max();
    if (ratio > worst_ratio) worst_ratio = ratio, mismatch = miss, allowed = bound;
    holds = holds && entry_holds;
  }

 private:
  T worst_ratio = -1;  // the largest miss/allowance of the entries added
};

template <class T, int m, class Map>
JacobianAgreement<T> compare_with_differences(const Map& map, const Vector<T, m>& x,
                                              const Matrix<T, m, m>& jacobian,
                                              const Vector<T, m>& scale,
                                              const T& unit = epsilon<T>(),
                                              const Vector<T, m>* output_rounding = nullptr) {
  using std::abs, std::max, std::pow, std::sqrt;
  const T root = pow(unit, T(1) / 3);
  const int size = static_cast<int>(x.size());
  Vector<T, m> widths(size);
  for (int j = 0; j < size; ++j) {
    T width = max(T(abs(x[j])), T(abs(scale[j])));
    if (width == 0) width = 1;
    widths[j] = width * root;
  }
  auto differences = [&](const T& fraction) {
    Matrix<T, m, m> d(size, size);
    for (int j = 0; j < size; ++j) {
      const T width = widths[j] * fraction;
      Vector<T, m> up = x, down = x;
      up[j] += width;
      down[j] -= width;
      d.col(j) = (map(up) - map(down)) / (up[j] - down[j]);
    }
    return d;
  };
  const Matrix<T, m, m> coarse = differences(T(1)), middle = differences(T(1) / 2),
                        fine = differences(T(1) / 4);
  const T change = nan_max(max_entry<T, m, m>(Matrix<T, m, m>(coarse - middle)),
                           max_entry<T, m, m>(Matrix<T, m, m>(middle - fine)));
  const T common = 4 * change + sqrt(unit) * max_entry<T, m, m>(jacobian);
  JacobianAgreement<T> out;
  out.mismatch = max_entry<T, m, m>(Matrix<T, m, m>(jacobian - coarse));
  out.allowed = common;
  out.holds = out.mismatch <= out.allowed;
  if (!output_rounding) return out;
  // Entry by entry against its own allowance.
  out = JacobianAgreement<T>();
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
      out.add_entry(T(abs(T(jacobian(i, j) - coarse(i, j)))),
                    T(common + 2 * abs(T((*output_rounding)[i])) / widths[j]));
  return out;
}

// The rounding of a DEL step's outputs, for compare_with_differences: q' to within an ulp of its
// size, p' = p_end(q, q') to within ε of its terms (|p'|, and ∂p_end/∂(q, q') times q and q'),
// each coordinate at least its size along the run (`scale`, on (q, p)). `end` is the discrete
// Legendre transform of the side that gives p_end at (q, q').
template <class T, int n, int m>
Vector<T, m> del_step_rounding(const DiscreteLegendre<T, n>& end, const Vector<T, n>& q,
                               const Vector<T, n>& q_next, const Vector<T, m>& scale, const T& unit) {
  using std::abs, std::max;
  const int size = static_cast<int>(q.size());
  Vector<T, m> rounding(2 * size);
  for (int i = 0; i < size; ++i) {
    rounding[i] = unit * max(T(abs(q_next[i])), T(abs(scale[i])));
    T terms = max(T(abs(end.p_end[i])), T(abs(scale[size + i])));
    for (int j = 0; j < size; ++j)
      terms += abs(T(end.dp_end_dq_b(i, j))) * max(T(abs(q[j])), T(abs(scale[j]))) +
               abs(T(end.dp_end_dq_e(i, j))) * max(T(abs(q_next[j])), T(abs(scale[j])));
    rounding[size + i] = unit * terms;
  }
  return rounding;
}

}  // namespace vivv
