// discrete-noether (Marsden–West §1.3.3, discrete Noether theorem): if the
// system has a symmetry with generator ξ and L_d is invariant under it, the DEL
// conserves the discrete momentum map J_k = p_k · ξ(q_k), p_k = −D1 L_d(q_k, q_{k+1})
// — exactly, at every h, so to working precision over the whole run (angular
// momentum for kepler and charged_particle). A discrete Lagrangian that breaks
// the symmetry (an expression adding h·Δq_1·Δq_2, still consistent of order 2)
// drifts at O(h²) per unit time: the claim's negative control.
#pragma once

#include <tuple>

#include "core/structure/noether.hpp"
#include "harness/claims/claim.hpp"
#include "harness/claims/global_order.hpp"

namespace vivv {

struct DiscreteNoetherClaim : Claim<DiscreteNoetherClaim> {
  static constexpr const char* id = "discrete-noether";
  // A symmetry of L at every t: J_k from p_k at t_k (trajectory_momenta), L's invariance checked at
  // each state's own time.
  static constexpr bool takes_time_dependent_lagrangians = true;
  static constexpr const char* series_rules[] = {"per-step-tolerance"};
  static constexpr const char* source = "Marsden–West §1.3.3 (discrete Noether theorem)";
  static constexpr const char* prediction =
      "J_k = p_k · ξ(q_k) is the same at every step k, at every h, to working precision (rounding "
      "accumulated over the N steps)";
  // The rounding unit of a run: J_k = p_k·ξ(q_k) is computed from p's terms and ξ, each carrying
  // a few ulps of its own size, and the Newton solve leaves a residual at rounding level of
  // those terms; N steps add up to u = N·ε·max_k |terms of p_k|·|ξ(q_k)|. The terms, not p: in
  // a magnetic field p = w + A may be 70 times smaller than w and A, and its rounding is theirs.
  // They are |p|, |M·w| and |∂L/∂w − M·w| (M = ∂²L/∂w², w the step's velocity): the kinetic and
  // the vector-potential parts of p on a charged particle. Relative to the momentum map's own
  // scale, never max(1, ·), so that small units are judged as strictly as unit ones. The drift
  // fails above `ulps` units (calibrated in docs/claims.md); drifts above `resolved` units at two
  // or more h that fall like a power of h fail as truncation (an L_d that breaks the symmetry at
  // O(h⁴) once passed in double). A drift above `ulps` but within `rounding_band` units that
  // does not fall with h (it grows with N, as rounding does) is inconclusive, naming the digits
  // at which rounding would sit 1000 times below it: rerun there, a drift that does not shrink
  // with the precision is then more than `rounding_band` units and fails.
  static constexpr int ulps = 16;
  static constexpr int resolved = 2;
  static constexpr int rounding_band = 1024;

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    using std::abs;
    using std::max;
    if constexpr (!DeclaresSymmetry<System>) {
      throw std::invalid_argument("discrete-noether: the system declares no symmetry");
    } else {
      if (!has_symmetry(context.system)) throw std::invalid_argument("discrete-noether: the system declares no symmetry");
      check_generator(context);
      PerStepCheck<T> check;
      std::vector<T> units;
      // J_k and the size of its terms at each step, judged against ulps × N × ε × the largest;
      // w[k] the velocity at step k (for a DEL its difference quotient).
      auto judge = [&](const T& h, const std::vector<Vector<T, N>>& q,
                       const std::vector<Vector<T, N>>& p, const std::vector<Vector<T, N>>& w) {
        using std::isfinite;
        const int steps = static_cast<int>(p.size());
        // The terms of p at 64 steps spread over the run (and every step of a short one).
        const int stride = std::max(1, steps / 64);
        T first = 0, drift = 0, size = 0;
        int worst_step = 0;
        for (int k = 0; k < steps; ++k) {
          const Vector<T, N> xi = symmetry_generator(context.system, q[k]);
          require_finite(context, xi, q[k],
                         "at step " + std::to_string(k) + " (t = " + format_scalar(T(k * h), 8) +
                             ") of the run with h = " + format_scalar(h, 6));
          const T J = p[k].dot(xi);
          if (!isfinite(J))
            throw CaseError(
                context.spec.file, "system.lagrangian",
                "the momentum p_k is not finite at step " + std::to_string(k) + " (t = " +
                    format_scalar(T(k * h), 8) + ", q = " + to_decimal_tuple<T, N>(q[k]) +
                    ") of the run with h = " + format_scalar(h, 6) +
                    ": the discrete trajectory left the Lagrangian's domain (a formula's "
                    "sqrt or log of a negative number, a division by zero)");
          if (k == 0) first = J;
          T terms = max_norm<T, N>(p[k]);
          if (k % stride == 0 || k == steps - 1)
            terms = nan_max(terms, momentum_terms(context.at_step(h, k), q[k], w[k]));
          size = nan_max(size, T(terms * max_norm<T, N>(xi)));
          if (abs(T(J - first)) > drift) drift = abs(T(J - first)), worst_step = k;
        }
        if (!(size > 0))
          throw CaseError(
              context.spec.file, "initial",
              "|p_k|·|xi(q_k)| is 0 at every step of the run with h = " + format_scalar(h, 6) +
                  ": the momentum map has no scale to judge a drift against");
        const T unit = T(steps) * context.working_epsilon() * size;
        units.push_back(unit);
        check.add(h, drift, T(ulps * unit),
                  {{"N", steps},
                   {"J_0", to_decimal<T>(first)},
                   {"worst_step", worst_step},
                   {"rounding_units", format_scalar(T(unit > 0 ? T(drift / unit) : T(0)), 3)}});
      };
      if (context.map) {
        visit_map_trajectories(context, "discrete-noether: momentum map", [&](const T& h, const auto& x) {
          std::vector<Vector<T, N>> q, p, w;
          for (std::size_t k = 0; k + 1 < x.size(); ++k)
            q.push_back(x[k].q), p.push_back(momentum(context.at_step(h, static_cast<long>(k)), x[k].q, x[k].w)),
                w.push_back(x[k].w);
          judge(h, q, p, w);
        });
        claim.evidence["momentum_map"] = "J_k = FL(q_k, w_k) · xi(q_k) along the states of " + context.map->name() +
                                         ", k = 0 … N−1";
      } else {
        visit_trajectories(
            context, "discrete-noether: momentum map",
            [&](const T& h, const auto& q) {
              std::vector<Vector<T, N>> w;
              for (std::size_t k = 0; k + 1 < q.size(); ++k) w.push_back(Vector<T, N>((q[k + 1] - q[k]) / h));
              judge(h, q, *trajectory_momenta(context, q, h), w);
            });
        claim.evidence["momentum_map"] = "J_k = p_begin[L_d](q_k, q_k+1) · xi(q_k), k = 0 … N−1";
      }
      claim.evidence["tolerance_rule"] =
          std::to_string(ulps) +
          " units u = N·ε·max_k |terms of p_k|·|xi(q_k)|, the terms |p|, |M·w| and |dL/dw − M·w| "
          "(M = d2L/dw2); drifts above " + std::to_string(resolved) +
          " u at two or more h falling like a power of h fail as truncation; a drift within " +
          std::to_string(rounding_band) + " u that does not fall with h is rounding's signature: "
          "inconclusive, naming the digits that decide";
      check.scaling_failure = truncation_scaling(context.steps(), check.values, units, resolved);
      check.scaling_limit = "a drift above " + std::to_string(resolved) +
                            " rounding unit at two h that falls like a power of h";
      if (!check.holds && check.scaling_failure.empty())
        check.undecided = rounding_growth(check.values, units, context.floors().precision_fixed);
      const std::string breaks = context.map ? (context.spec.discretization.kind == "process"
                                                    ? "the program's map (" + context.map->name() + ")"
                                                    : "the map " + context.map->name()) +
                                                   " does not conserve the momentum map of the symmetry"
                                             : "L_d is not invariant under the symmetry";
      check.conclude_claim(claim, context, "max_k |J_k − J_0|",
                           "the discrete momentum map is conserved to working precision at every h",
                           "the discrete momentum map drifts beyond rounding: " + breaks +
                               " (the drift and its rounding units at each h are in the per-step evidence)");
    }
  }

 private:
  // The size of the terms that p = ∂L/∂w is a sum of, at (q, w): |p|, |M·w| and |∂L/∂w − M·w|.
  template <LagrangianSystem System>
  static typename System::Scalar momentum_terms(const System& system, const VectorOf<System>& q,
                                                const VectorOf<System>& w) {
    using T = typename System::Scalar;
    return max_norm<T, System::dimension>(momentum_term_sizes(system, q, w));
  }

  // A drift beyond `ulps` units that does not fall with h (the finest step's is at least the
  // largest's: it grows with N, as rounding does) and stays within `rounding_band` units cannot
  // be told from rounding the unit underestimates: what would decide, or empty when it is not so.
  template <class T>
  static PerStepCheck<T>::Undecided rounding_growth(const std::vector<T>& drift, const std::vector<T>& unit,
                                                    bool precision_fixed = false) {
    using std::log10;
    T worst = 0;
    for (std::size_t i = 0; i < drift.size(); ++i)
      if (unit[i] > 0 && drift[i] / unit[i] > worst) worst = drift[i] / unit[i];
    if (drift.size() < 2 || !(drift.back() >= drift.front()) || !(worst <= T(rounding_band))) return {};
    const T digits_now = -log10(epsilon<T>());
    const int digits = static_cast<int>(std::ceil(static_cast<double>(digits_now + log10(T(worst / ulps))) + 3));
    // A double program's precision is its own: what the case accepts is larger steps, where a broken
    // symmetry's drift (a power of h) grows and rounding (which grows with N) shrinks.
    const std::string advice = precision_fixed ? std::string("larger steps (smaller step counts), where a broken "
                                                             "symmetry's drift grows with h and rounding falls with N")
                                               : digits_advice(std::max(20, digits));
    return {"the drift is at most " + format_scalar(worst, 3) + " rounding units (allowed " + std::to_string(ulps) +
                ") and does not fall with h (" + format_scalar(drift.front(), 3) + " at the largest h, " +
                format_scalar(drift.back(), 3) +
                " at the smallest): rounding grows with N like this, a broken symmetry falls like a power of h; "
                "the unit may underestimate rounding where the terms cancel",
            precision_fixed ? advice
                            : advice + ", where rounding sits 1000 times below this drift; a drift that does not "
                                       "shrink there fails"};
  }

  // A generator that is not finite or vanishes at the initial state makes J meaningless (a NaN
  // generator compares false with every tolerance; a zero one conserves J = 0 trivially): bad
  // input naming the generator, before any step is judged.
  template <LagrangianSystem System>
  static void check_generator(const CaseContext<System>& context) {
    using T = typename System::Scalar;
    constexpr int N = System::dimension;
    using std::isfinite;
    const Vector<T, N> xi = symmetry_generator(context.system, context.initial.q);
    for (int i = 0; i < static_cast<int>(xi.size()); ++i)
      if (!isfinite(xi[i]))
        throw CaseError(context.spec.file, "system.symmetry",
                        "the symmetry generator is " + to_decimal<T>(xi[i]) + " in component " +
                            std::to_string(i + 1) +
                            " at the initial state: it must be finite along the motion");
    if (!(max_norm<T, N>(xi) > 0))
      throw CaseError(
          context.spec.file, "system.symmetry",
          "the symmetry generator vanishes at the initial state: its momentum map J = p·xi is 0 "
          "whatever the integrator does, so conserving it proves nothing");
    check_invariance(context);
  }

  // A generator that is not finite where vivv evaluates it (a formula's √ or log of a negative
  // number along the run) would compare false with every tolerance and so pass: bad input, naming
  // where.
  template <LagrangianSystem System>
  static void require_finite(const CaseContext<System>& context,
                             const VectorOf<System>& xi, const VectorOf<System>& q,
                             const std::string& where) {
    using std::isfinite;
    for (int i = 0; i < static_cast<int>(xi.size()); ++i)
      if (!isfinite(xi[i]))
        throw CaseError(
            context.spec.file, "system.symmetry",
            "the symmetry generator is " + to_decimal(xi[i]) + " in component " +
                std::to_string(i + 1) + " " + where +
                ", q = " + to_decimal_tuple<typename System::Scalar, System::dimension>(q) +
                ": it must be finite wherever the motion goes (a formula's sqrt or log of "
                "a negative number, a division by zero)");
  }

  // L itself must be invariant under the lifted flow of ξ: δL = ∂L/∂q·ξ + ∂L/∂w·(Dξ·w) = 0 on
  // all of TQ, checked at the initial state, the reference state at T/2 and at T (one state can
  // fool it: (−y, 2x) is not a symmetry of Kepler, yet δL = 0 at a periapsis on the x axis),
  // each relative to the size of its terms (so a non-symmetry scaled by 10⁻⁴⁰ is as wrong as
  // one of unit size). Otherwise p·ξ is not conserved by the flow, and a drift would be blamed
  // on L_d. ∂L/∂q, ∂L/∂w by automatic differentiation; Dξ·w by central differences of ξ along w
  // (relative error about ε^(2/3)), so the allowance is 10⁴·ε^(2/3).
  template <LagrangianSystem System>
  static void check_invariance(const CaseContext<System>& context) {
    using T = typename System::Scalar;
    const T half = context.final_time / 2;
    // Each state with the system at its own time (for an L that depends on time, invariance at every t).
    const std::vector<std::tuple<std::string, State<T, System::dimension>, T>> states = {
        {"the initial state", context.initial, T(0)},
        {"t = T/2 (" + format_scalar(half, 6) + ")", context.exact(half), half},
        {"t = T", context.final_state, context.final_time}};
    for (const auto& [where, state, t] : states) check_invariance_at(context, context.at(t), state, where);
  }

  template <LagrangianSystem System>
  static void check_invariance_at(const CaseContext<System>& context, const System& system,
                                  const State<typename System::Scalar, System::dimension>& state,
                                  const std::string& where) {
    using T = typename System::Scalar;
    constexpr int N = System::dimension;
    using std::abs, std::max, std::pow;
    const Vector<T, N>& q = state.q;
    const Vector<T, N>& w = state.w;
    const Vector<T, N> xi = symmetry_generator(context.system, q);
    require_finite(context, xi, q, "at " + where + " of the reference flow");
    const auto d = lagrangian_derivatives(system, q, w);
    const int n = static_cast<int>(q.size());
    Vector<T, N> along = zero_vector<T, N>(n);  // Dξ(q)·w
    const T speed = max_norm<T, N>(w);
    if (speed > 0) {
      const T length = max_norm<T, N>(q) > 0 ? T(max_norm<T, N>(q)) : T(1);
      const T s = pow(epsilon<T>(), T(1) / 3) * length / speed;
      const Vector<T, N> up = q + s * w, down = q - s * w;
      const Vector<T, N> xi_up = symmetry_generator(context.system, up);
      const Vector<T, N> xi_down = symmetry_generator(context.system, down);
      require_finite(context, xi_up, up, "beside " + where + " (a difference quotient's sample)");
      require_finite(context, xi_down, down,
                     "beside " + where + " (a difference quotient's sample)");
      along = (xi_up - xi_down) / (up - down).dot(w) * w.dot(w);
    }
    T variation = 0, size = 0;
    for (int i = 0; i < n; ++i) {
      variation += d.dL_dq[i] * xi[i] + d.dL_dw[i] * along[i];
      size += abs(T(d.dL_dq[i] * xi[i])) + abs(T(d.dL_dw[i] * along[i]));
    }
    if (!(size > 0)) return;  // every term vanishes here: nothing to compare
    const T allowed = 10000 * pow(epsilon<T>(), T(2) / 3);
    if (!(abs(variation) <= allowed * size))
      throw CaseError(
          context.spec.file, "system.symmetry",
          "L itself is not invariant under the declared generator: dL/dq·xi + dL/dw·(Dxi·w) = " +
              format_scalar(variation, 3) + " at " + where + ", " +
              format_scalar(T(abs(variation) / size), 3) +
              " of the size of its terms (a symmetry gives 0; allowed " +
              format_scalar(allowed, 2) +
              " of that size): the flow itself does not conserve p·xi, so its drift would be "
              "blamed on "
              "L_d");
  }
};

}  // namespace vivv
