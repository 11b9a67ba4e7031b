// Galerkin discrete Lagrangians (Marsden–West §2.2.6; Ober-Blöbaum & Saake 2015).
//
// The curve is the polynomial of degree s on τ ∈ [0, 1] through s + 1 control
// values C_0 = q_b, C_1 … C_{s−1}, C_s = q_e at τ_j = j/s (Lagrange basis φ_j).
// With an m-node quadrature (τ_i, b_i) on [0, 1], Gauss–Legendre or
// Gauss–Lobatto, computed in the working precision,
//   S(C) = h Σ_i b_i L(x_i, v_i),  x_i = Σ_j φ_j(τ_i) C_j,  v_i = Σ_j φ'_j(τ_i) C_j / h,
// and L_d(q_b, q_e) = S at the interior values that make it stationary, found
// by Newton on the n(s − 1) equations ∂S/∂C_j = 0 (1 ≤ j ≤ s − 1). Everything
// comes from the blocks of S's gradient G and Hessian H in C, assembled from
// L's own first and second derivatives at the nodes (automatic differentiation):
//   G_j  = h Σ_i b_i (a_ij L_q + d_ij L_w),
//   H_jk = h Σ_i b_i (a_ij a_ik L_qq + a_ij d_ik L_qw + d_ij a_ik L_wq + d_ij d_ik L_ww),
// a_ij = φ_j(τ_i), d_ij = φ'_j(τ_i)/h. By the envelope theorem (∂S/∂C_interior = 0)
//   p_begin = −∂L_d/∂q_b = −G_0,   p_end = ∂L_d/∂q_e = G_s,
// and the second derivatives of L_d are the Schur complement of the interior
// block: ∇²L_d = H_ee − H_ei H_ii⁻¹ H_ie over the end blocks e = {0, s}.
//
// Order: the curve reproduces the solution to O(h^{s+1}), so L_d is of order
// at most 2s; the quadrature is exact to degree 2m − 1 (Gauss) or 2m − 3
// (Lobatto), so it limits the order to 2m or 2m − 2. vivv predicts
// min(2s, 2m) for Gauss and min(2s, 2m − 2) for Lobatto; the Galerkin study
// (cases/studies/galerkin/) measures it.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/qxq/discrete_legendre.hpp"
#include "core/autodiff/jet.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "core/numerics/newton.hpp"
#include "core/numerics/quadrature.hpp"
#include "core/numerics/scalar.hpp"

namespace vivv {

// Degree s of the curve, the quadrature and its number of nodes m.
struct GalerkinSpec {
  int degree = 1;
  bool lobatto = false;
  int nodes = 1;

  // The order vivv predicts: min(2s, 2m) (Gauss) or min(2s, 2m − 2) (Lobatto).
  int predicted_order() const { return std::min(2 * degree, lobatto ? 2 * nodes - 2 : 2 * nodes); }
  std::string describe() const {
    return "degree " + std::to_string(degree) + ", " + std::to_string(nodes) + (lobatto ? " Lobatto" : " Gauss") +
           " nodes";
  }
};

// The quadrature and the basis values at its nodes, computed once in T.
template <class T>
struct GalerkinRule {
  GalerkinSpec spec;
  std::vector<T> weights;
  std::vector<T> nodes;                    // τ_i in [0, 1]: node i is at time t_b + τ_i·h
  std::vector<std::vector<T>> phi, dphi;  // phi[i][j] = φ_j(τ_i), dphi[i][j] = φ'_j(τ_i)

  explicit GalerkinRule(const GalerkinSpec& spec_) : spec(spec_) {
    const int s = spec.degree;
    if (s < 1) throw std::invalid_argument("galerkin: degree must be at least 1, got " + std::to_string(s));
    const GaussLegendreRule<T> quadrature = spec.lobatto ? gauss_lobatto<T>(spec.nodes) : gauss_legendre<T>(spec.nodes);
    weights = quadrature.weights;
    nodes = quadrature.nodes;
    for (const T& tau : quadrature.nodes) {
      std::vector<T> value(s + 1), slope(s + 1);
      for (int j = 0; j <= s; ++j) {
        // φ_j(τ) = Π_{k≠j} (τ − τ_k)/(τ_j − τ_k), φ'_j = Σ_l 1/(τ_j − τ_l) Π_{k≠j,l} (τ − τ_k)/(τ_j − τ_k).
        T product = 1, derivative = 0;
        for (int k = 0; k <= s; ++k) {
          if (k == j) continue;
          const T denominator = T(j - k) / s;
          derivative = derivative * (tau - T(k) / s) / denominator + product / denominator;
          product *= (tau - T(k) / s) / denominator;
        }
        value[j] = product, slope[j] = derivative;
      }
      phi.push_back(value), dphi.push_back(slope);
    }
  }
};

// L's value, gradient and full Hessian at (x, v), by automatic differentiation.
template <class T, int n>
struct LagrangianHessian {
  explicit LagrangianHessian(int size)
      : L_q(size), L_w(size), L_qq(size, size), L_qw(size, size), L_ww(size, size) {}
  T value;
  Vector<T, n> L_q, L_w;
  Matrix<T, n, n> L_qq, L_qw, L_ww;  // L_qw(r, c) = ∂²L/∂q_r∂w_c
};

template <LagrangianSystem System>
auto lagrangian_hessian(const System& system, const VectorOf<System>& x,
                        const VectorOf<System>& v) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(x.size());
  using J = Jet<T, twice(N)>;
  Coordinates<J, N> jet_x = make_point<J, N>(n), jet_v = make_point<J, N>(n);
  for (int i = 0; i < n; ++i) jet_x[i] = J::variable(x[i], i, 2 * n), jet_v[i] = J::variable(v[i], n + i, 2 * n);
  const J L = with_size(J(system.lagrangian(jet_x, jet_v)), 2 * n);
  LagrangianHessian<T, N> d(n);
  d.value = L.value;
  for (int r = 0; r < n; ++r) {
    d.L_q[r] = L.gradient[r], d.L_w[r] = L.gradient[n + r];
    for (int c = 0; c < n; ++c) {
      d.L_qq(r, c) = L.second(r, c);
      d.L_qw(r, c) = L.second(r, n + c);
      d.L_ww(r, c) = L.second(n + r, n + c);
    }
  }
  return d;
}

// S, with its gradient G and Hessian H in the control values C_first … C_last (block j − first):
// the interior ones (1 … s − 1) while Newton solves for them, all of them (0 … s) once at the
// solution. With the weights folded into one side, H_jk = [a'_j I, d'_j I] ∇²L [a_k I; d_k I]
// (a'_j = h b_i a_ij, d'_j = h b_i d_ij); each product is formed once, H's lower triangle is its
// upper one mirrored, and the arithmetic works in place through two scratch numbers: for MPFR
// every temporary is an allocation, and this assembly, not L, once made a step cost 8.6 times its
// L evaluations (bench/galerkin_benchmark.cpp).
template <class T>
struct GalerkinAction {
  T value;
  Eigen::Matrix<T, Eigen::Dynamic, 1> gradient;
  Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic> hessian;
};

template <LagrangianSystem System>
GalerkinAction<typename System::Scalar> galerkin_action(
    const System& system, const GalerkinRule<typename System::Scalar>& rule,
    const std::vector<VectorOf<System>>& C, const typename System::Scalar& h, int first, int last) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(C.front().size());
  const int s = rule.spec.degree, blocks = last - first + 1;
  GalerkinAction<T> S{
      T(0), Eigen::Matrix<T, Eigen::Dynamic, 1>::Zero(n * blocks),
      Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>::Zero(n * blocks, n * blocks)};
  std::vector<T> a(blocks), d(blocks), a_weighted(blocks), d_weighted(blocks);
  // M_k = ∇²L [a_k I; d_k I]: rows 0 … n − 1 the q-rows, n … 2n − 1 the w-rows.
  std::vector<Eigen::Matrix<T, twice(N), N>> M(blocks, Eigen::Matrix<T, twice(N), N>::Zero(2 * n, n));
  Vector<T, N> x(n), v(n);
  T scratch, term;
  for (std::size_t i = 0; i < rule.weights.size(); ++i) {
    for (int r = 0; r < n; ++r) {
      x[r] = 0, v[r] = 0;
      for (int j = 0; j <= s; ++j) {
        scratch = C[j][r];
        scratch *= rule.phi[i][j];
        x[r] += scratch;
        scratch = C[j][r];
        scratch *= rule.dphi[i][j];
        v[r] += scratch;
      }
      v[r] /= h;
    }
    // At the node's time t_b + τ_i·h, for an L that depends on t (t_b the system's time).
    const auto L = depends_on_time(system)
                       ? lagrangian_hessian(at_time(system, T(system_time(system) + rule.nodes[i] * h)), x, v)
                       : lagrangian_hessian(system, x, v);
    T hb = h;
    hb *= rule.weights[i];
    scratch = L.value;
    scratch *= hb;
    S.value += scratch;
    for (int b = 0; b < blocks; ++b) {
      a[b] = rule.phi[i][first + b];
      d[b] = rule.dphi[i][first + b];
      d[b] /= h;
      a_weighted[b] = a[b];
      a_weighted[b] *= hb;
      d_weighted[b] = d[b];
      d_weighted[b] *= hb;
      for (int r = 0; r < n; ++r) {
        scratch = L.L_q[r];
        scratch *= a_weighted[b];
        term = L.L_w[r];
        term *= d_weighted[b];
        scratch += term;
        S.gradient[n * b + r] += scratch;
        for (int c = 0; c < n; ++c) {
          T& q_row = M[b](r, c);
          q_row = L.L_qq(r, c);
          q_row *= a[b];
          term = L.L_qw(r, c);
          term *= d[b];
          q_row += term;
          T& w_row = M[b](n + r, c);
          w_row = L.L_qw(c, r);
          w_row *= a[b];
          term = L.L_ww(r, c);
          term *= d[b];
          w_row += term;
        }
      }
    }
    for (int j = 0; j < blocks; ++j)
      for (int k = j; k < blocks; ++k)
        for (int r = 0; r < n; ++r)
          for (int c = (k == j ? r : 0); c < n; ++c) {
            scratch = M[k](r, c);
            scratch *= a_weighted[j];
            term = M[k](n + r, c);
            term *= d_weighted[j];
            scratch += term;
            S.hessian(n * j + r, n * k + c) += scratch;
          }
  }
  for (int row = 0; row < n * blocks; ++row)
    for (int column = row + 1; column < n * blocks; ++column)
      S.hessian(column, row) = S.hessian(row, column);
  return S;
}

// L_d, p_begin, p_end and their derivatives at (q_b, q_e): the interior values by Newton from
// the straight line, then the envelope theorem and the Schur complement (top of the file).
// A Newton solve that does not converge is a SolverError naming the step.
template <LagrangianSystem System>
DiscreteLegendre<typename System::Scalar, System::dimension> galerkin_legendre(
    const System& system, const GalerkinRule<typename System::Scalar>& rule,
    const VectorOf<System>& q_b, const VectorOf<System>& q_e, const typename System::Scalar& h) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q_b.size());
  using std::abs;
  using std::max;
  const int s = rule.spec.degree;
  std::vector<Vector<T, N>> C(s + 1);
  for (int j = 0; j <= s; ++j) C[j] = q_b + (T(j) / s) * (q_e - q_b);
  const int interior = n * (s - 1);
  // Newton on the interior values, with the interior blocks of G and H alone; converged when the
  // error left after a correction, estimated as in core/numerics/newton.hpp (predict_convergence), is at
  // the rounding level.
  T previous = 0;
  for (int iteration = 0; interior > 0; ++iteration) {
    if (iteration == 60)
      throw SolverError("Galerkin interior solve (" + rule.spec.describe() + ") at h = " + to_decimal<T>(h, 17) +
                        ": Newton did not converge in 60 iterations");
    const GalerkinAction<T> inner = galerkin_action(system, rule, C, h, 1, s - 1);
    const Eigen::Matrix<T, Eigen::Dynamic, 1> correction =
        inner.hessian.fullPivLu().solve(inner.gradient);
    T size = 1;
    for (int j = 1; j < s; ++j) {
      C[j] -= correction.segment(n * (j - 1), n);
      size = max(size, T(C[j].cwiseAbs().maxCoeff()));
    }
    const T largest = correction.cwiseAbs().maxCoeff();
    using std::isfinite;
    if (!isfinite(largest))
      throw SolverError("Galerkin interior solve (" + rule.spec.describe() + ") at h = " + to_decimal<T>(h, 17) +
                        ": Newton diverged (the action's interior Hessian is singular)");
    const T left = iteration > 0 && largest <= previous / 2
                       ? T(largest * largest / (previous - largest))
                       : largest;
    if (left <= 64 * epsilon<T>() * size) break;
    previous = largest;
  }
  const GalerkinAction<T> S = galerkin_action(system, rule, C, h, 0, s);
  // Reduced Hessian over the end blocks: H_ee − H_ei H_ii⁻¹ H_ie.
  Eigen::Matrix<T, twice(N), twice(N)> ends(2 * n, 2 * n);
  Eigen::Matrix<T, twice(N), Eigen::Dynamic> ends_interior(2 * n, interior);
  const int last = n * s;
  ends.block(0, 0, n, n) = S.hessian.block(0, 0, n, n);
  ends.block(0, n, n, n) = S.hessian.block(0, last, n, n);
  ends.block(n, 0, n, n) = S.hessian.block(last, 0, n, n);
  ends.block(n, n, n, n) = S.hessian.block(last, last, n, n);
  if (interior > 0) {
    ends_interior.topRows(n) = S.hessian.block(0, n, n, interior);
    ends_interior.bottomRows(n) = S.hessian.block(last, n, n, interior);
    const Eigen::Matrix<T, Eigen::Dynamic, twice(N)> solved =
        S.hessian.block(n, n, interior, interior).fullPivLu().solve(Eigen::Matrix<T, Eigen::Dynamic, twice(N)>(ends_interior.transpose()));
    ends -= ends_interior * solved;
  }
  DiscreteLegendre<T, N> d(n);
  d.value = S.value;
  d.p_begin = -S.gradient.segment(0, n);
  d.p_end = S.gradient.segment(last, n);
  d.dp_begin_dq_b = -ends.block(0, 0, n, n);
  d.dp_begin_dq_e = -ends.block(0, n, n, n);
  d.dp_end_dq_b = ends.block(n, 0, n, n);
  d.dp_end_dq_e = ends.block(n, n, n, n);
  return d;
}

}  // namespace vivv
