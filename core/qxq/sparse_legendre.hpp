// The discrete Legendre transforms of a Q × Q rule from a Lagrangian's sparse derivatives
// (core/autodiff/sparse_hessian.hpp), for systems sized at run time whose L is a tape.
//
// Every built-in rule but Galerkin's is a weighted sum of L at points on the segment,
//   L_d(q_b, q_e) = h Σ_k c_k L((1 − f_k) q_b + f_k q_e, (q_e − q_b)/h)   (+ the twin term),
// with (c, f) = (1, 0) left rectangle, (1, 1) right, (1, 1/2) midpoint, (1, α) alpha,
// (1/2, 0) + (1/2, 1) trapezoid, (1 − β, 0) + (β, 1) weighted; so by the chain rule
//   ∂L_d/∂q_b = Σ c_k [h (1 − f_k) L_q − L_w],   ∂L_d/∂q_e = Σ c_k [h f_k L_q + L_w],
// and ∂²L_d/∂(q_b, q_e)² = Σ_k h c_k Jᵀ ∇²L J with J = ∂(x, v)/∂(q_b, q_e) coordinatewise
// ((1 − f_k, f_k) on x, (−1/h, 1/h) on v). An expression L_d is a tape over (q_b, q_e, h) of its
// own, differentiated directly. The Hessian stays sparse where ∇²L is: a DEL step's Newton
// matrix −∂²L_d/∂q_b∂q_e has the nonzeros of L's couplings, and a step costs what L does.
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <utility>
#include <vector>

#include "core/autodiff/sparse_hessian.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "core/qxq/discrete_legendre.hpp"

namespace vivv {

// Which second derivatives of L_d to compute: none, the q_b–q_e block alone (what the DEL's
// Newton solve reads: a quarter of the entries), or all four blocks.
enum class SecondDerivatives { none, begin_end_block, all };

// L_d's value, gradient in (q_b, q_e) (2n entries) and, when asked, its Hessian there as
// triplets of the full 2n × 2n matrix (duplicates to be summed; with begin_end_block, only the
// triplets of rows q_b and columns q_e).
template <class T>
struct SparseDiscreteDerivatives {
  T value = 0;
  Vector<T, any_size> gradient;
  std::vector<Eigen::Triplet<T>> hessian;
};

// Whether L_d's derivatives come from the sparse path: a sparsely differentiated system and a
// rule it applies to (Galerkin's extremal is not). `Discretization` is a QxQDiscretization
// (core/qxq/discrete_lagrangian.hpp): its segment_points(), expression_derivatives and twin.
template <LagrangianSystem System, class Discretization>
bool sparse_path_applies(const System& system, const Discretization& discretization) {
  if constexpr (SparselyDifferentiated<System>) {
    return system.derivatives != nullptr &&
           (!discretization.segment_points().empty() || discretization.expression_derivatives != nullptr);
  } else {
    return (void)system, (void)discretization, false;
  }
}

// L_d and its derivatives at (q_b, q_e) from the sparse derivatives of L (or of the expression).
template <SparselyDifferentiated System, class Discretization>
SparseDiscreteDerivatives<typename System::Scalar> sparse_discrete_derivatives(
    const System& system, const Discretization& discretization,
    const VectorOf<System>& q_b, const VectorOf<System>& q_e, const typename System::Scalar& h,
    SecondDerivatives wanted) {
  using T = typename System::Scalar;
  const int n = static_cast<int>(q_b.size());
  SparseDiscreteDerivatives<T> d;
  d.gradient = zero_vector<T, any_size>(2 * n);
  const bool second_derivatives = wanted != SecondDerivatives::none;
  const bool block_only = wanted == SecondDerivatives::begin_end_block;
  const auto points = discretization.segment_points();
  if (points.empty()) {
    const SecondDerivativeTape<T>& tape = *discretization.expression_derivatives;
    std::vector<T> x(tape.inputs);  // (q_b, q_e, h) and, for an L that depends on time, t_b
    for (int i = 0; i < n; ++i) x[i] = q_b[i], x[n + i] = q_e[i];
    x[2 * n] = h;
    if (tape.inputs == 2 * n + 2) x[2 * n + 1] = system_time(system);
    const EdgePushed<T> L = second_derivatives ? tape.evaluate(x.data()) : tape.evaluate_gradient(x.data());
    d.value = L.value;
    for (int k = 0; k < 2 * n; ++k) d.gradient[k] = L.gradient[k];
    for (std::size_t e = 0; e < L.hessian.size(); ++e) {
      const auto [r, c] = tape.pattern[e];
      if (r >= 2 * n) continue;  // an entry in h (or t_b)
      if (!block_only || (c < n && r >= n)) d.hessian.emplace_back(c, r, L.hessian[e]);  // (q_b, q_e) when blocked
      if (!block_only && r != c) d.hessian.emplace_back(r, c, L.hessian[e]);
    }
  } else {
    const SecondDerivativeTape<T>& tape = *system.derivatives;
    std::vector<T> x = lagrangian_tape_inputs(system, n);
    const bool timed = depends_on_time(system);
    for (int i = 0; i < n; ++i) x[n + i] = (q_e[i] - q_b[i]) / h;
    for (const auto& [weight, fraction] : points) {
      for (int i = 0; i < n; ++i) x[i] = (1 - fraction) * q_b[i] + fraction * q_e[i];
      if (timed) x[2 * n] = system_time(system) + fraction * h;  // the point's time, t_b + f·h
      const EdgePushed<T> L = lagrangian_tape(system, x.data(), second_derivatives);
      d.value += h * weight * L.value;
      for (int i = 0; i < n; ++i) {
        d.gradient[i] += weight * (h * (1 - fraction) * L.gradient[i] - L.gradient[n + i]);
        d.gradient[n + i] += weight * (h * fraction * L.gradient[i] + L.gradient[n + i]);
      }
      if (!second_derivatives) continue;
      // Input u of L (q_a or w_a) moves with q_b[a] and q_e[a] at these rates.
      const T on_x[2] = {1 - fraction, fraction}, on_v[2] = {-1 / h, 1 / h};
      const T scale = h * weight;
      for (std::size_t e = 0; e < L.hessian.size(); ++e) {
        const auto [u, t] = tape.pattern[e];
        if (u >= 2 * n) continue;  // an entry in the time, which q_b and q_e do not move
        const int a = u % n, b = t % n;
        const T* rate_u = u < n ? on_x : on_v;
        const T* rate_t = t < n ? on_x : on_v;
        const T entry = scale * L.hessian[e];
        if (block_only) {  // rows q_b (rate index 0), columns q_e (rate index 1), both orders
          d.hessian.emplace_back(a, n + b, rate_u[0] * rate_t[1] * entry);
          if (u != t) d.hessian.emplace_back(b, n + a, rate_u[1] * rate_t[0] * entry);
          continue;
        }
        for (int su = 0; su < 2; ++su)
          for (int st = 0; st < 2; ++st) {
            const T value = rate_u[su] * rate_t[st] * entry;
            d.hessian.emplace_back(su * n + a, st * n + b, value);
            if (u != t) d.hessian.emplace_back(st * n + b, su * n + a, value);
          }
      }
    }
  }
  if (discretization.twin) {
    using std::pow;
    const T scale = pow(h, discretization.twin->power);
    for (int i = 0; i < n; ++i) {
      d.value += scale * discretization.twin->a[i] * (q_e[i] - q_b[i]);
      d.gradient[i] -= scale * discretization.twin->a[i];
      d.gradient[n + i] += scale * discretization.twin->a[i];
    }
  }
  return d;
}

// p_begin = −∂L_d/∂q_b and its derivative −∂²L_d/∂q_b∂q_e, sparse: what a DEL step's Newton
// solve reads.
template <class T>
struct SparseBeginMomentum {
  Vector<T, any_size> p_begin;
  Eigen::SparseMatrix<T> dp_begin_dq_e;
};

template <SparselyDifferentiated System, class Discretization>
SparseBeginMomentum<typename System::Scalar> sparse_begin_momentum(
    const System& system, const Discretization& discretization,
    const VectorOf<System>& q_b, const VectorOf<System>& q_e, const typename System::Scalar& h) {
  using T = typename System::Scalar;
  const int n = static_cast<int>(q_b.size());
  const SparseDiscreteDerivatives<T> L = sparse_discrete_derivatives(system, discretization, q_b, q_e, h,
                                                                       SecondDerivatives::begin_end_block);
  SparseBeginMomentum<T> d;
  d.p_begin = -L.gradient.head(n);
  std::vector<Eigen::Triplet<T>> block;
  for (const auto& entry : L.hessian)
    if (entry.row() < n && entry.col() >= n) block.emplace_back(entry.row(), entry.col() - n, -entry.value());
  d.dp_begin_dq_e.resize(n, n);
  d.dp_begin_dq_e.setFromTriplets(block.begin(), block.end());
  return d;
}

// The four blocks of discrete_legendre, dense, from the sparse derivatives (no dense jet).
template <SparselyDifferentiated System, class Discretization>
DiscreteLegendre<typename System::Scalar, any_size> sparse_discrete_legendre(
    const System& system, const Discretization& discretization,
    const VectorOf<System>& q_b, const VectorOf<System>& q_e, const typename System::Scalar& h) {
  using T = typename System::Scalar;
  const int n = static_cast<int>(q_b.size());
  const SparseDiscreteDerivatives<T> L = sparse_discrete_derivatives(system, discretization, q_b, q_e, h, SecondDerivatives::all);
  DiscreteLegendre<T, any_size> d(n);
  d.value = L.value;
  d.p_begin = -L.gradient.head(n);
  d.p_end = L.gradient.tail(n);
  for (const auto& entry : L.hessian) {
    const int r = static_cast<int>(entry.row()), c = static_cast<int>(entry.col());
    if (r < n && c < n) d.dp_begin_dq_b(r, c) -= entry.value();
    if (r < n && c >= n) d.dp_begin_dq_e(r, c - n) -= entry.value();
    if (r >= n && c < n) d.dp_end_dq_b(r - n, c) += entry.value();
    if (r >= n && c >= n) d.dp_end_dq_e(r - n, c - n) += entry.value();
  }
  return d;
}

// The discrete Legendre transforms with their four derivative blocks kept sparse: what
// symplecticity's probes (core/structure/symplectic_probes.hpp) apply, O(nonzeros) a step where
// the dense blocks of sparse_discrete_legendre hold 4n² numbers.
template <class T>
struct SparseLegendreBlocks {
  Vector<T, any_size> p_begin, p_end;
  Eigen::SparseMatrix<T> dp_begin_dq_b, dp_begin_dq_e, dp_end_dq_b, dp_end_dq_e;
};

template <SparselyDifferentiated System, class Discretization>
SparseLegendreBlocks<typename System::Scalar> sparse_legendre_blocks(
    const System& system, const Discretization& discretization,
    const VectorOf<System>& q_b, const VectorOf<System>& q_e, const typename System::Scalar& h) {
  using T = typename System::Scalar;
  const int n = static_cast<int>(q_b.size());
  const SparseDiscreteDerivatives<T> L = sparse_discrete_derivatives(system, discretization, q_b, q_e, h, SecondDerivatives::all);
  SparseLegendreBlocks<T> d;
  d.p_begin = -L.gradient.head(n);
  d.p_end = L.gradient.tail(n);
  std::vector<Eigen::Triplet<T>> blocks[4];  // begin–begin, begin–end, end–begin, end–end
  for (const auto& entry : L.hessian) {
    const int r = static_cast<int>(entry.row()), c = static_cast<int>(entry.col());
    const int block = 2 * (r >= n) + (c >= n);
    const T value = r < n ? T(-entry.value()) : T(entry.value());  // p_begin = −∂L_d/∂q_b
    blocks[block].emplace_back(r % n, c % n, value);
  }
  Eigen::SparseMatrix<T>* out[4] = {&d.dp_begin_dq_b, &d.dp_begin_dq_e, &d.dp_end_dq_b, &d.dp_end_dq_e};
  for (int b = 0; b < 4; ++b) {
    out[b]->resize(n, n);
    out[b]->setFromTriplets(blocks[b].begin(), blocks[b].end());  // duplicates summed
  }
  return d;
}

}  // namespace vivv
