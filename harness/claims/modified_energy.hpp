// modified-energy (backward error analysis; Hairer–Lubich–Wanner IX.3,
// Vermeeren 2017): for L = ½|w|² − U(q) the midpoint and trapezoid rules
// conserve H̃ = H + h² H₂ to O(h⁴) over the whole run, while H itself is
// conserved only to O(h²). H₂ is derived in core/structure/modified_energy.hpp and
// checked there against the harmonic oscillator's exact modified frequencies.
// An order alone cannot tell H̃'s O(h⁴) truncation from a drift h⁴·t over a fixed T (a DEL
// whose two sides differ at O(h⁴) once passed at 3.99), so H̃ − H̃_0 also goes through
// energy-behaviour's drift test: averaged over the motion's returns, it must not drift.
// Negative controls: a mismatched DEL (not symplectic, no modified energy)
// and, in the unit tests, H₂ with a wrong sign — both leave H̃ at O(h²).
#pragma once

#include "core/structure/modified_energy.hpp"
#include "harness/claims/claim.hpp"
#include "harness/claims/energy_behaviour.hpp"
#include "harness/claims/global_order.hpp"

namespace vivv {

struct ModifiedEnergyClaim : Claim<ModifiedEnergyClaim> {
  static constexpr const char* id = "modified-energy";
  static constexpr const char* series_rules[] = {"order", "floor", "none", "energy-drift"};
  static constexpr const char* source = "Hairer–Lubich–Wanner IX.3; Vermeeren 2017 (modified Lagrangians)";
  static constexpr const char* prediction =
      "for L = ½|w|² − U(q), max_k |H̃_k − H̃_0| = O(h⁴) with H̃ = H + h² H₂ (midpoint: H₂ = −(pᵀU''p "
      "+ |U'|²)/24; "
      "trapezoid: H₂ = pᵀU''p/12 − |U'|²/24), while max_k |H_k − H_0| is only O(h²); and H̃ − H̃_0, "
      "averaged "
      "over the motion's returns, does not drift";

  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>&) {
    return 4;
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    using std::abs;
    using std::max;
    // The form of L checked along the motion: the initial and final states, their mixtures and
    // reversals, and the state at T/2 of the reference flow.
    const State<T, N>& x0 = context.initial;
    const State<T, N>& xT = context.final_state;
    const std::vector<State<T, N>> samples = {
        x0,
        xT,
        context.exact(context.final_time / 2),
        {x0.q, xT.w},
        {xT.q, x0.w},
        {x0.q, Vector<T, N>(-x0.w)},
        {Vector<T, N>((x0.q + xT.q) / 2), Vector<T, N>((x0.w + xT.w) / 2)}};
    if (const std::string why = modified_energy_inapplicable(context.spec); !why.empty())
      throw ClaimNotApplicable(why);
    if (const std::string defect = unit_mass_defect(context.system, samples); !defect.empty())
      throw ClaimNotApplicable(
          "modified-energy is derived for L = ½|w|² − U(q), and this Lagrangian is not of that form "
          "along the motion: " + defect);
    const ModifiedEnergyForm form = modified_energy_form(context.scheme.future.rule);
    std::vector<T> modified_error, energy_error;
    std::vector<EnergyDrift<T>> drifts;
    nlohmann::json against_t = nlohmann::json::array();  // |H̃_k − H̃_0| against t, per h
    visit_trajectories(context, "modified-energy: H and H̃", [&](const T& h, const auto& q) {
      const int steps = static_cast<int>(q.size()) - 1;
      T H0 = 0, modified0 = 0, largest_H = 0, largest_modified = 0, size = 0;
      std::vector<T> modified;
      std::vector<Vector<T, N>> velocities;  // w = p for L = ½|w|² − U(q)
      const auto momenta = trajectory_momenta(context, q, h);
      for (int k = 0; k < steps; ++k) {
        const Vector<T, N>& p = (*momenta)[k];
        const ModifiedEnergy<T> E = modified_energy(context.system, form, q[k], p, h);
        if (k == 0) H0 = E.H, modified0 = E.modified;
        largest_H = nan_max(largest_H, T(abs(T(E.H - H0))));
        largest_modified = nan_max(largest_modified, T(abs(T(E.modified - modified0))));
        modified.push_back(E.modified);
        velocities.push_back(p);
        size = nan_max(size, T(p.dot(p)));
      }
      energy_error.push_back(largest_H);
      modified_error.push_back(largest_modified);
      drifts.push_back(measure_energy_drift<T, N>(h, modified, velocities, size));
      against_t.push_back(energy_error_against_t(h, modified));
    });
    claim.evidence["rule"] = rule_name(context.scheme.future.rule);
    claim.evidence["energy_error_against_t"] = against_t;
    claim.evidence["H2_in_24ths"] = {{"pT_U''_p", form.pUp}, {"|U'|^2", form.UU}};
    claim.evidence["momenta"] = "p_k = p_begin[L_d](q_k, q_k+1), k = 0 … N−1";
    claim.evidence["mismatched_del"] = context.scheme.mismatched;
    claim.series.push_back(sweep_series(context, "max_k |H̃_k − H̃_0| (modified energy)", modified_error, predicted(context)));
    nlohmann::json drift_rows;
    claim.series.push_back(
        energy_drift_series(context, drifts, "the modified energy's error H̃ − H̃_0", drift_rows));
    claim.evidence["modified_energy_drift"] = drift_rows["per_step"];
    claim.series.push_back(sweep_series(context, "max_k |H_k − H_0| (energy, O(h²): fitted, not judged)", energy_error,
                                        std::nullopt));
    conclude(claim);
  }
};

}  // namespace vivv
