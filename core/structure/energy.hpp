// The energy of a discrete trajectory (docs/theory.md, energy-behaviour).
//
// A Q×Q trajectory carries momenta p_k = −D1 L_d(q_k, q_{k+1}), not velocities:
// the energy at step k is E(q_k, w_k) = w_k · ∂L/∂w − L with w_k the velocity
// whose momentum ∂L/∂w(q_k, w_k) is p_k (the inverse Legendre transform, by
// Newton from a guess such as the difference quotient).
#pragma once

#include <string>

#include "core/lagrangian/lagrangian.hpp"
#include "core/numerics/newton.hpp"

namespace vivv {

// The w with ∂L/∂w(q, w) = p, by Newton from `guess`; an error if it does not converge.
template <LagrangianSystem System>
auto velocity_for_momentum(const System& system, const VectorOf<System>& q,
                           const VectorOf<System>& p,
                           VectorOf<System> guess) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q.size());
  if constexpr (SparselyDifferentiated<System>) {
    if (system.derivatives) {
      // ∂²L/∂w² from L's sparse Hessian, factored sparse (core/numerics/newton.hpp).
      std::vector<T> x = lagrangian_tape_inputs(system, n);
      for (int i = 0; i < n; ++i) x[i] = q[i];
      auto report = newton_solve<T, N, Eigen::SparseMatrix<T>>(
          guess,
          [&](const Vector<T, N>& w, Vector<T, N>& residual, Eigen::SparseMatrix<T>& jacobian) {
            for (int i = 0; i < n; ++i) x[n + i] = w[i];
            const EdgePushed<T> L = lagrangian_tape(system, x.data());
            std::vector<Eigen::Triplet<T>> mass;
            for (std::size_t e = 0; e < L.hessian.size(); ++e) {
              const auto [r, c] = system.derivatives->pattern[e];
              if (c < n || r >= 2 * n) continue;  // not in w alone
              mass.emplace_back(r - n, c - n, L.hessian[e]);
              if (r != c) mass.emplace_back(c - n, r - n, L.hessian[e]);
            }
            for (int i = 0; i < n; ++i) residual[i] = L.gradient[n + i] - p[i];
            jacobian.resize(n, n);
            jacobian.setFromTriplets(mass.begin(), mass.end());
          },
          options_along_a_run());
      require_converged(report, "inverse Legendre transform w(q, p)");
      return guess;
    }
  }
  auto report = newton_solve<T, N>(
      guess,
      [&](const Vector<T, N>& w, Vector<T, N>& residual, Matrix<T, N, N>& jacobian) {
        const auto L = lagrangian_in_velocity<2>(system, q, w);
        for (int i = 0; i < n; ++i) {
          residual[i] = L.gradient[i] - p[i];
          for (int j = 0; j < n; ++j) jacobian(i, j) = L.second(i, j);
        }
      },
      options_along_a_run());
  require_converged(report, "inverse Legendre transform w(q, p)");
  return guess;
}

}  // namespace vivv
