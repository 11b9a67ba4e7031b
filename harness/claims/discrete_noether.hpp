// discrete-noether (Marsden–West §1.3.3, discrete Noether theorem): if the
// system has a symmetry with generator ξ and L_d is invariant under it, the DEL
// conserves the discrete momentum map J_k = p_k · ξ(q_k), p_k = −D1 L_d(q_k, q_{k+1})
// — exactly, at every h, so to working precision over the whole run (angular
// momentum for kepler and charged_particle). A discrete Lagrangian that breaks
// the symmetry (an expression adding h·Δq_1·Δq_2, still consistent of order 2)
// drifts at O(h²) per unit time: the claim's negative control.
#pragma once

#include "core/noether.hpp"
#include "harness/claim.hpp"
#include "harness/claims/global_order.hpp"

namespace vivv {

struct DiscreteNoetherClaim : Claim<DiscreteNoetherClaim> {
  static constexpr const char* id = "discrete-noether";
  static constexpr const char* source = "Marsden–West §1.3.3 (discrete Noether theorem)";
  static constexpr const char* prediction =
      "J_k = p_k · ξ(q_k) is the same at every step k, at every h, to working precision (rounding "
      "accumulated over the N steps)";
  // Rounding allowance per step: p_k and ξ(q_k) each carry a few ulps of their size, and the
  // Newton solve a residual at rounding level; N steps add up to N × ulps × ε × max(1, |p|·|ξ|).
  static constexpr int ulps = 1024;

  template <LagrangianSystem System>
  static ClaimResult evaluate(const CaseContext<System>& context) {
    using T = typename System::Scalar;
    constexpr int n = System::dimension;
    using std::abs;
    using std::max;
    ClaimResult claim = result();
    if constexpr (!DeclaresSymmetry<System>) {
      throw std::invalid_argument("discrete-noether: the system declares no symmetry");
    } else {
      if (!has_symmetry(context.system)) throw std::invalid_argument("discrete-noether: the system declares no symmetry");
      PerStepCheck<T> check;
      // J_k and max(1, |p_k|·|ξ(q_k)|) at each step, judged against N × ulps × ε × the largest.
      auto judge = [&](const T& h, const std::vector<Vector<T, n>>& q, const std::vector<Vector<T, n>>& p) {
        const int N = static_cast<int>(p.size());
        T first = 0, drift = 0, size = 1;
        int worst_step = 0;
        for (int k = 0; k < N; ++k) {
          const Vector<T, n> xi = symmetry_generator(context.system, q[k]);
          const T J = p[k].dot(xi);
          if (k == 0) first = J;
          size = max(size, T(max_norm<T, n>(p[k]) * max_norm<T, n>(xi)));
          if (abs(T(J - first)) > drift) drift = abs(T(J - first)), worst_step = k;
        }
        const T tolerance = T(N) * ulps * epsilon<T>() * size;
        check.add(h, drift, tolerance, {{"N", N}, {"J_0", to_decimal<T>(first)}, {"worst_step", worst_step}});
      };
      if (context.map) {
        visit_map_trajectories(context, "discrete-noether: momentum map", [&](const T& h, const auto& x) {
          std::vector<Vector<T, n>> q, p;
          for (std::size_t k = 0; k + 1 < x.size(); ++k)
            q.push_back(x[k].q), p.push_back(momentum(context.system, x[k].q, x[k].w));
          judge(h, q, p);
        });
        claim.evidence["momentum_map"] = "J_k = FL(q_k, w_k) · xi(q_k) along the states of " + context.map->name() +
                                         ", k = 0 … N−1";
      } else {
        visit_trajectories(context, "discrete-noether: momentum map", [&](const T& h, const auto& q) {
          std::vector<Vector<T, n>> p;
          for (std::size_t k = 0; k + 1 < q.size(); ++k) p.push_back(momentum_at_step(context, q, k, h));
          judge(h, q, p);
        });
        claim.evidence["momentum_map"] = "J_k = p_begin[L_d](q_k, q_k+1) · xi(q_k), k = 0 … N−1";
      }
      claim.evidence["tolerance_rule"] = "N × " + std::to_string(ulps) + " ulps × max(1, |p_k|·|xi(q_k)|)";
      check.conclude_claim(claim, context, "max_k |J_k − J_0|",
                           "the discrete momentum map is conserved to working precision at every h",
                           "the discrete momentum map drifts beyond rounding: L_d is not invariant under the "
                           "symmetry (see per-step evidence)");
    }
    return claim;
  }
};

}  // namespace vivv
