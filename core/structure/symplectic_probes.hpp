// Symplecticity through random vectors: O(n) per step where the dense check is O(n³).
//
// A map with Jacobian J is symplectic when D = JᵀΩJ − Ω vanishes; D is antisymmetric (JᵀΩJ is,
// Ω is), and for vectors ξ, η
//   ξᵀDη = ω(Jξ, Jη) − ω(ξ, η),   ω(a, b) = a_q·b_p − a_p·b_q,
// which needs J only through the products Jξ, Jη: for a DEL map two sparse solves with the LU of
// ∂p_begin/∂q_e, the matrix its Newton solve already factors.
//
// How likely a defect is missed. For ξ, η independent standard Gaussian vectors, write D in its
// real canonical form D = Q·diag(σ_i [[0, 1], [−1, 0]])·Qᵀ (Q orthogonal, σ_1 = ‖D‖₂ the
// largest): Qᵀξ and Qᵀη are again independent standard Gaussians, so ξᵀDη = Σ_i σ_i (a_i d_i −
// b_i c_i) with a, b, c, d independent N(0, 1). Each a d − b c has the Laplace density ½e^{−|x|}
// (characteristic function 1/(1 + t²)), so σ_1's term has a density at most 1/(2σ_1), and so has
// the sum (a convolution of that density with the others' laws is bounded by its bound):
//   P(|ξᵀDη| < t·‖D‖₂) ≤ t   for every antisymmetric D and every t ≥ 0,
// whatever D's rank or pattern; with k independent pairs the largest of the k values is below
// t·‖D‖₂ with probability at most t^k. The check compares |ξᵀDη| with a rounding allowance τ
// that scales with ‖ξ‖‖η‖ (≈ 2n: ω sums 2n products): a step with ‖D‖₂ ≥ τ/t passes all k
// pairs with probability at most t^k. The dense check sees one entry of D at the allowance of one
// entry; the probes see ‖D‖₂ at the allowance of a sum of 2n terms — coarser by up to 2n for a
// defect in one entry, by about √(2n) for a defect spread over the coordinates (a rule's
// truncation, a mismatched DEL), and the truncation's fall with h is judged from the same values.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/numerics/linear_solve.hpp"
#include "core/qxq/sparse_legendre.hpp"
#include "core/structure/dense_limit.hpp"
#include "core/structure/symplectic.hpp"

namespace vivv {

// ω(a, b) = a_q·b_p − a_p·b_q on (q, p) of 2n entries.
template <class T>
T omega(const Vector<T, any_size>& a, const Vector<T, any_size>& b) {
  const Eigen::Index n = a.size() / 2;
  return T(a.head(n).dot(b.tail(n)) - a.tail(n).dot(b.head(n)));
}

// Standard Gaussian vectors from a seeded engine: the draws are doubles, exact in every scalar,
// and the same on every machine for one seed (std::mt19937_64 is specified to the bit; the
// Box–Muller below is written out because std::normal_distribution is not).
class GaussianProbes {
 public:
  explicit GaussianProbes(std::uint64_t seed) : engine_(seed) {}
  template <class T>
  Vector<T, any_size> next(int size) {
    Vector<T, any_size> v(size);
    for (int i = 0; i < size; ++i) v[i] = T(normal());
    return v;
  }

 private:
  double normal() {
    if (spare_) {
      spare_ = false;
      return stored_;
    }
    // Box–Muller from two uniforms in (0, 1]: 53-bit fractions of the engine's words (only the
    // angle's uniformity matters for u2: any whole number of turns gives the same law).
    const double u1 = (static_cast<double>(engine_() >> 11) + 1) * 0x1p-53;
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1p-53;
    const double radius = std::sqrt(-2 * std::log(u1)), angle = 6.283185307179586 * u2;
    stored_ = radius * std::sin(angle);
    spare_ = true;
    return radius * std::cos(angle);
  }
  std::mt19937_64 engine_;
  bool spare_ = false;
  double stored_ = 0;
};

// One probe pair through one step: |ξᵀDη| = |ω(Jξ, Jη) − ω(ξ, η)| and what it is judged against.
// `stretch` is max(‖Jξ‖/‖ξ‖, ‖Jη‖/‖η‖), the probes' view of |J|.
template <class T>
struct ProbeDefect {
  T defect = 0;   // |ω(Jξ, Jη) − ω(ξ, η)|
  T norms = 0;    // ‖ξ‖·‖η‖
  T stretch = 0;  // max(‖Jξ‖/‖ξ‖, ‖Jη‖/‖η‖)
};

template <class T>
ProbeDefect<T> probe_defect(const Vector<T, any_size>& xi, const Vector<T, any_size>& eta,
                            const Vector<T, any_size>& j_xi, const Vector<T, any_size>& j_eta) {
  using std::abs, std::max;
  ProbeDefect<T> out;
  out.defect = abs(T(omega(j_xi, j_eta) - omega(xi, eta)));
  const T xi_norm = xi.norm(), eta_norm = eta.norm();
  out.norms = xi_norm * eta_norm;
  out.stretch = nan_max(T(j_xi.norm() / xi_norm), T(j_eta.norm() / eta_norm));
  return out;
}

// The Jacobian of the DEL's (q, p) map applied to vectors, from the sparse blocks of L_d (future)
// and L~_d (past) at (q_k, q_k+1) (core/structure/symplectic.hpp, del_map_jacobian):
//   dq' = B_e⁻¹·(dp − B_b·dq),   dp' = E_b·dq + E_e·dq',
// B_e factored once by a sparse LU: O(the blocks' nonzeros and the LU's fill) a vector.
template <class T>
class DelMapJacobian {
 public:
  DelMapJacobian(const SparseLegendreBlocks<T>& future, const SparseLegendreBlocks<T>& past)
      : future_(future), past_(past) {
    invertible_ = lu_.factor(future.dp_begin_dq_e, T(16) * epsilon<T>());
  }
  // False when ∂p_begin/∂q' is singular (the map has no Jacobian there).
  bool invertible() const { return invertible_; }
  Vector<T, any_size> apply(const Vector<T, any_size>& v) const {
    const Eigen::Index n = v.size() / 2;
    const Vector<T, any_size> dq = lu_.solve(Vector<T, any_size>(v.tail(n) - future_.dp_begin_dq_b * v.head(n)));
    Vector<T, any_size> out(2 * n);
    out << dq, past_.dp_end_dq_b * v.head(n) + past_.dp_end_dq_e * dq;
    return out;
  }

 private:
  const SparseLegendreBlocks<T>& future_;
  const SparseLegendreBlocks<T>& past_;
  SparseFactorization<T> lu_;
  bool invertible_ = false;
};

// max |a_ij| over the stored entries; NaN when one is NaN.
template <class T>
T largest_stored(const Eigen::SparseMatrix<T>& a) {
  using std::abs;
  T largest = 0;
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (typename Eigen::SparseMatrix<T>::InnerIterator it(a, j); it; ++it) largest = nan_max(largest, T(abs(it.value())));
  return largest;
}

// The DEL map's generating form of JᵀΩJ = Ω. With p = p_begin(q, q'), p' = p_end(q, q') and
// ∂p_begin/∂q' invertible, the map is symplectic exactly when p'dq' − p dq is closed:
//   B_b = ∂p_begin/∂q and E_e = ∂p_end/∂q' symmetric, and E_b = ∂p_end/∂q = −B_eᵀ
// (for one L_d: −D11 L_d, D22 L_d and D21 L_d = (D12 L_d)ᵀ; for two rules E_b + B_eᵀ is the
// difference of their mixed blocks). `defect` is the largest entry of E_b + B_eᵀ, B_b − B_bᵀ and
// E_e − E_eᵀ, `size` max(1, the largest entry of the four blocks), both in the balanced
// coordinates of `exponents` (core/structure/symplectic.hpp, balanced: entry (i, j) of a block,
// coordinate j to momentum i, times 2^−(e_i + e_j)). O(the blocks' nonzeros).
template <class T>
struct GeneratingDefect {
  T defect = 0, size = 1;
};

template <class T>
GeneratingDefect<T> generating_defect(const SparseLegendreBlocks<T>& future, const SparseLegendreBlocks<T>& past,
                                      const std::vector<int>& exponents) {
  using Sparse = Eigen::SparseMatrix<T>;
  auto balance = [&](const Sparse& block) {
    if (exponents.empty()) return block;
    Sparse out = block;
    using std::ldexp;
    for (Eigen::Index j = 0; j < out.outerSize(); ++j)
      for (typename Sparse::InnerIterator it(out, j); it; ++it)
        it.valueRef() = ldexp(T(it.value()), -(exponents[it.row()] + exponents[it.col()]));
    return out;
  };
  const Sparse begin_begin = balance(future.dp_begin_dq_b), begin_end = balance(future.dp_begin_dq_e),
               end_begin = balance(past.dp_end_dq_b), end_end = balance(past.dp_end_dq_e);
  GeneratingDefect<T> out;
  out.size = nan_max({T(1), largest_stored(begin_begin), largest_stored(begin_end), largest_stored(end_begin),
                      largest_stored(end_end)});
  out.defect = nan_max({largest_stored(Sparse(end_begin + Sparse(begin_end.transpose()))),
                        largest_stored(Sparse(begin_begin - Sparse(begin_begin.transpose()))),
                        largest_stored(Sparse(end_end - Sparse(end_end.transpose())))});
  return out;
}

// compare_with_differences (core/structure/symplectic.hpp) along directions instead of
// coordinates: for each direction g (Gaussian), the perturbation d_j = δ_j g_j with the widths
// δ_j = ε^{1/3}·max(|x_j|, scale_j), and at τ = 1, 1/2, 1/4 the residual
//   R_τ = (map(x + τd) − map(x − τd) − J·((x + τd) − (x − τd))) / (2τ)
// (J applied to the perturbation as represented, so that rounding the perturbed points is not
// counted against J). R_τ is the truncation O(τ²) plus the outputs' rounding over τ; J may miss
// by 4 × the larger change between the three residuals + √ε·max|J d|, and entry i by 2·r_i/τ
// more where the outputs carry a known rounding r_i. Two directions cost 12 evaluations of the
// map, where the columns cost 12 per coordinate; a wrong J (another step's, a dropped block)
// misses along a random direction with probability one.
template <class T, class Map, class Apply>
JacobianAgreement<T> compare_directions_with_differences(const Map& map, const Apply& apply_jacobian,
                                                         const Vector<T, any_size>& x,
                                                         const Vector<T, any_size>& scale, GaussianProbes& draw,
                                                         int directions, const T& unit,
                                                         const Vector<T, any_size>* output_rounding = nullptr) {
  using std::abs, std::max, std::pow, std::sqrt;
  const T root = pow(unit, T(1) / 3);
  const int size = static_cast<int>(x.size());
  JacobianAgreement<T> out;
  for (int direction = 0; direction < directions; ++direction) {
    const Vector<T, any_size> g = draw.next<T>(size);
    Vector<T, any_size> d(size);
    for (int j = 0; j < size; ++j) {
      T width = max(T(abs(x[j])), T(abs(scale[j])));
      if (width == 0) width = 1;
      d[j] = width * root * g[j];
    }
    Vector<T, any_size> residual[3], along;
    for (int level = 0; level < 3; ++level) {
      const T tau = T(1) / T(1 << level);
      const Vector<T, any_size> up = x + tau * d, down = x - tau * d;
      const Vector<T, any_size> moved = apply_jacobian(Vector<T, any_size>(up - down));
      if (level == 0) along = moved / 2;
      residual[level] = (map(up) - map(down) - moved) / (2 * tau);
    }
    const T change = nan_max(T((residual[0] - residual[1]).cwiseAbs().maxCoeff()),
                             T((residual[1] - residual[2]).cwiseAbs().maxCoeff()));
    const T common = 4 * change + sqrt(unit) * along.cwiseAbs().maxCoeff();
    for (int i = 0; i < size; ++i)
      out.add_entry(T(abs(T(residual[0][i]))),
                    T(common + (output_rounding ? T(2 * abs(T((*output_rounding)[i]))) : T(0))));
  }
  return out;
}

}  // namespace vivv
