// energy-behaviour (Hairer–Lubich–Wanner ch. IX–X; Marsden–West §1.3.4): a
// variational integrator is symplectic, so by backward error analysis it
// conserves a modified energy exponentially long, and the energy error
// |E_k − E_0| stays bounded, O(h^r), without drift. A method that is not
// symplectic (the mismatched midpoint/trapezoid DEL) drifts: its error grows
// with t. The claim's measurement is the running maximum M(t) of |E_k − E_0|:
// bounded means M has stopped growing by the second half of the run.
//
// At each h: E_k = E(q_k, w_k) with w_k from p_k = −D1 L_d(q_k, q_{k+1}) by the
// inverse Legendre transform (core/energy.hpp). The slope b of M over the second
// half [T/2, T] (least squares) predicts a growth b·T/2 there; the claim holds
// if that growth is at most a quarter of M(T/2) — linear drift gives 1, a random
// walk about 0.4, a bounded oscillation near 0 — or if M stays at the rounding
// floor N × ulps × ε × max_k |p_k · w_k| (an exact discretization).
#pragma once

#include "core/energy.hpp"
#include "harness/claim.hpp"
#include "harness/claims/global_order.hpp"

namespace vivv {

struct EnergyBehaviourClaim : Claim<EnergyBehaviourClaim> {
  static constexpr const char* id = "energy-behaviour";
  static constexpr const char* source = "Hairer–Lubich–Wanner ch. IX (backward error analysis); Marsden–West §1.3.4";
  static constexpr const char* prediction =
      "the energy error |E_k − E_0| stays bounded without drift: its running maximum grows over the second half "
      "of the run by at most a quarter of its value at T/2";
  static constexpr int ulps = 1024;
  static constexpr double growth_allowed = 0.25;

  template <LagrangianSystem System>
  static ClaimResult evaluate(const CaseContext<System>& context) {
    using T = typename System::Scalar;
    constexpr int n = System::dimension;
    using std::abs;
    using std::max;
    ClaimResult claim = result();
    PerStepCheck<T> check;
    std::vector<T> largest_error;
    if (context.map) {
      visit_map_trajectories(context, "energy-behaviour: energy", [&](const T& h, const auto& x) {
        std::vector<T> energies;
        T size = 0;
        for (std::size_t k = 0; k + 1 < x.size(); ++k) {
          energies.push_back(energy(context.system, x[k].q, x[k].w));
          size = max(size, T(abs(T(momentum(context.system, x[k].q, x[k].w).dot(x[k].w)))));
        }
        largest_error.push_back(judge(check, h, energies, size));
      });
      claim.evidence["energy"] = "E_k = E(q_k, w_k) along the states of " + context.map->name();
    } else {
      visit_trajectories(context, "energy-behaviour: energy", [&](const T& h, const auto& q) {
        std::vector<T> energies;
        T size = 0;
        for (std::size_t k = 0; k + 1 < q.size(); ++k) {
          const Vector<T, n> p = momentum_at_step(context, q, k, h);
          const Vector<T, n> w = velocity_for_momentum(context.system, q[k], p, Vector<T, n>((q[k + 1] - q[k]) / h));
          energies.push_back(energy(context.system, q[k], w));
          size = max(size, T(abs(T(p.dot(w)))));
        }
        largest_error.push_back(judge(check, h, energies, size));
      });
      claim.evidence["energy"] = "E_k = E(q_k, w_k), w_k from p_k = p_begin[L_d](q_k, q_k+1) by the inverse "
                                 "Legendre transform";
      claim.evidence["mismatched_del"] = context.scheme.mismatched;
    }
    claim.series.push_back(sweep_series(context, "max_k |E_k − E_0| (bounded energy error, fitted, not judged)",
                                        largest_error, std::nullopt));
    claim.evidence["drift_rule"] = "least-squares slope b of the running maximum M over [T/2, T]; holds if b·T/2 <= " +
                                   std::to_string(growth_allowed) + " × M(T/2), or M at the rounding floor N × " +
                                   std::to_string(ulps) + " ulps × max_k |p_k·w_k|";
    check.conclude_claim(claim, context, "growth of max |E_k − E_0| over [T/2, T]",
                         "the energy error is bounded: its running maximum stops growing at every h",
                         "the energy error drifts: its running maximum keeps growing with t (see per-step evidence)");
    return claim;
  }

 private:
  // The verdict at one h from E_0 … E_{N−1} and max_k |p_k·w_k|: the running maximum M of
  // |E_k − E_0|, its least-squares slope over the second half against growth_allowed × M(T/2)
  // or the rounding floor. Returns max_k |E_k − E_0|.
  template <class T>
  static T judge(PerStepCheck<T>& check, const T& h, const std::vector<T>& energies, const T& size) {
    using std::abs;
    using std::max;
    const int N = static_cast<int>(energies.size());
    const T first = energies.front();
    std::vector<T> running_max(N);
    T largest = 0;
    for (int k = 0; k < N; ++k) {
      largest = max(largest, T(abs(T(energies[k] - first))));
      running_max[k] = largest;
    }
    // Least-squares slope of M(t_k) over the second half.
    const int from = N / 2;
    T mean_t = 0, mean_m = 0;
    for (int k = from; k < N; ++k) mean_t += k * h, mean_m += running_max[k];
    mean_t /= (N - from), mean_m /= (N - from);
    T covariance = 0, variance = 0;
    for (int k = from; k < N; ++k) {
      covariance += (k * h - mean_t) * (running_max[k] - mean_m);
      variance += (k * h - mean_t) * (k * h - mean_t);
    }
    const T slope = variance > 0 ? T(covariance / variance) : T(0);
    const T growth = slope * T(N - 1 - from) * h;
    const T level = running_max[from];
    const T rounding = T(N) * ulps * epsilon<T>() * max(size, T(abs(first)));
    const bool at_floor = largest <= rounding;
    check.add(h, growth, max(T(growth_allowed * level), rounding),
              {{"N", N},
               {"E_0", to_decimal<T>(first)},
               {"max_energy_error", to_decimal<T>(largest)},
               {"running_max_at_half", to_decimal<T>(level)},
               {"slope", to_decimal<T>(slope)},
               {"relative_growth", level > 0 ? to_decimal<T>(T(growth / level)) : std::string("0")},
               {"rounding_floor", to_decimal<T>(rounding)},
               {"at_floor", at_floor}});
    return largest;
  }
};

}  // namespace vivv
