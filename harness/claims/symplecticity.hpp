// symplecticity (Marsden–West §1.3.2): the DEL of a discrete Lagrangian is, on
// (q, p), a symplectic map: its Jacobian J satisfies JᵀΩJ = Ω at every step,
// to working precision — not as h → 0, at every h. J comes from the implicit
// function theorem with the Hessian blocks of L_d (core/structure/symplectic.hpp). Two
// different rules on the DEL's two sides (a past_discretization) make a map
// that is not symplectic: the defect is the difference of their mixed blocks
// through B_e⁻¹, O(h²) and far above rounding (the claim's negative control).
#pragma once

#include "core/structure/energy.hpp"
#include "core/structure/symplectic.hpp"
#include "core/structure/symplectic_probes.hpp"
#include "harness/claims/claim.hpp"
#include "harness/claims/global_order.hpp"
#include "harness/claims/map_symplecticity_probes.hpp"

namespace vivv {

struct SymplecticityClaim : Claim<SymplecticityClaim> {
  static constexpr const char* id = "symplecticity";
  // A DEL's step k is read on the system at t0 + k·h (a non-autonomous DEL map is symplectic step
  // by step); a case with a map or a TQ evolution and such an L is refused when it is read.
  static constexpr bool takes_time_dependent_lagrangians = true;
  static constexpr const char* series_rules[] = {"per-step-tolerance"};
  static constexpr const char* source = "Marsden–West §1.3.2";
  static constexpr const char* prediction =
      "the one-step map (q_k, p_k) ↦ (q_{k+1}, p_{k+1}) — a variational integrator's DEL map, or the "
      "case's map — is symplectic, JᵀΩJ = Ω, at every step and every h to working precision; so is "
      "its N-step composition";
  // The rounding unit of a step: the map's blocks come out of Hessian entries of size s ~ 1/h
  // that cancel to O(1) and O(h) (B_e⁻¹·B_b, E_b + E_e·∂q'/∂q), each with an error of a few ulps
  // of s, and JᵀΩJ multiplies two such: u = ε·s·max(1, |J|)² (s = 1 for a one-step map).
  // Calibrated: correct integrators measure at most 1 u (midpoint, trapezoid and Galerkin DELs on
  // the pendulum, the double pendulum, Kepler, Toda and Hénon–Heiles, in double, long double,
  // float128 and MPFR) and 2 u (odeint's symplectic maps): a step fails above `ulps` units, eight
  // times the worst measured; the N-step composition Φ above N·ulps·u_max·max(1, |Φ|)².
  static constexpr int ulps = 16;
  // Scaling: defects above `resolved` units at two or more h that fall like a power of h are
  // truncation (harness/claims/claim.hpp, truncation_scaling), however small: RK4's h^5 per-step defect
  // in double, a DEL whose two sides differ at O(h³).
  static constexpr int resolved = 4;
  // A DEL map of more than `dense_limit` coordinates sized at run time is judged without forming
  // J, in O(the DEL step's nonzeros) a step where the dense check costs 16 n³ and keeps every
  // step's 4n² numbers. Each step by the map's generating form: with p = p_begin(q, q'),
  // p' = p_end(q, q') and ∂p_begin/∂q' invertible, JᵀΩJ = Ω exactly when the one-form
  // p'dq' − p dq is closed, that is when
  //   B_b = ∂p_begin/∂q and E_e = ∂p_end/∂q' are symmetric and E_b = ∂p_end/∂q = −B_eᵀ,
  // entry by entry against ulps·ε·s (balanced as the dense check; for two different rules E_b +
  // B_eᵀ is the difference of their mixed blocks, which the dense check sees through B_e⁻¹); the
  // N-step composition by `probe_pairs` pairs of Gaussian vectors carried through the run
  // (core/structure/symplectic_probes.hpp), |ξᵀ(ΦᵀΩΦ − Ω)η| per unit |ξ||η| against N·ulps·
  // max_k(ε·s_k·r_k²)·max(1, r_Φ)², r the stretch |Jx|/|x| of the carried vectors. At or below
  // the limit the dense check is cheap and sees J itself.
  static constexpr int dense_limit = symplecticity_dense_limit;
  static constexpr int probe_pairs = symplecticity_probe_pairs;
  // A composition whose defect D = ΦᵀΩΦ − Ω has ‖D‖₂ ≥ 10 × its allowance × |ξ||η| passes all
  // probe_pairs pairs with probability at most 10^−probe_pairs (the file's bound, evidence.probes).
  // The seed of the probes' draws (evidence.probes.seed): a run is reproduced from its report.
  static constexpr std::uint64_t probe_seed = 0x5eed5eedULL;

  // evidence.tolerance_rule: `ulps` ulps times what `scaled` says, and the scaling test.
  static std::string tolerance_rule(const std::string& scaled) {
    return std::to_string(ulps) + " ulps" + scaled + "; a defect falling like a power of h fails as truncation";
  }

  // evidence.probes: the probes' rule, the chance that they miss a defect (and how much coarser
  // than the dense check they are), where the dense check stops and the draws' seed.
  static nlohmann::json probes_evidence(const std::string& rule, const std::string& miss_probability) {
    return {{"rule", rule},
            {"miss_probability", miss_probability +
                                     ": coarser than the dense check by up to 2n for a defect in one entry, about "
                                     "sqrt(2n) for one spread over the coordinates"},
            {"dense_limit", "the dense check (every entry of J^T Omega J - Omega) up to " +
                                std::to_string(dense_limit) + " coordinates"},
            {"seed", probe_seed}};
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    const int n = dimension_of(context.system);
    const std::vector<int> exponents = balancing(context);
    PerStepCheck<T> check;
    std::vector<T> units;  // the rounding unit of the judged (worst) step at each h
    std::vector<JacobianCheck> jacobian_checks;  // the judged step's Jacobian against its map
    bool noise_raised_tolerance = false;  // a program's measured answer noise raised some step's tolerance
    if (context.map && judged_by_probes(context)) {
      if constexpr (N == any_size)
        measure_map_by_probes<SymplecticityClaim>(context, exponents, check, units, jacobian_checks,
                                                  noise_raised_tolerance);
      claim.evidence["jacobian"] = "not formed: J applied to vectors, " + context.map->jacobian_method() +
                                   " taken along each vector instead of each coordinate";
      claim.evidence["jacobian_unit"] = to_decimal<T>(context.map->jacobian_unit(), 6);
      claim.evidence["probes"] = probes_evidence(
          "at each step " + std::to_string(map_probe_fresh_pairs) +
               " new pairs of standard Gaussian vectors (xi, eta) on (q, p): |xi^T (J^T Omega J - Omega) eta| per "
               "unit |xi||eta| against " + std::to_string(ulps) +
               " ulps x u x max(1, g)^2, u the products' relative rounding (evidence.jacobian_unit, or the noise "
               "measured in the map's answers) and g the largest |J v|/|v| of the step's vectors; " +
               std::to_string(map_probe_carried_pairs) +
               " pairs carried through the whole run for the composition, against N x that x max(1, |Phi xi|/|xi|, "
               "|Phi eta|/|eta|)^2",
          "a step whose ||J^T Omega J - Omega||_2 is at least 10 x its tolerance x |xi||eta| passes its " +
               std::to_string(map_probe_fresh_pairs) + " pairs with probability at most 10^-" +
               std::to_string(map_probe_fresh_pairs) + ", a defect present at m steps at most 10^-(" +
               std::to_string(map_probe_fresh_pairs) + " m), the composition 10^-" +
               std::to_string(map_probe_carried_pairs));
      claim.evidence["tolerance_rule"] = tolerance_rule(
          " × u × max(1, g)² per step by probes (evidence.probes; measured: the step with the largest "
          "defect/tolerance); the composition by carried probes");
    } else if (context.map) {
      // A one-step map: its Jacobian by jets through its own code; no Hessian blocks to size.
      visit_map_trajectories(context, "symplecticity: Jacobians", [&](const T& h, const auto& x) {
        std::vector<Matrix<T, twice(N), twice(N)>> jacobians;
        std::vector<T> noise;  // each Jacobian's rounding in units of jacobian_unit(): 1, or measured
        Vector<T, twice(N)> scale = zero_vector<T, twice(N)>(2 * n);  // each coordinate's size along the run
        for (std::size_t k = 0; k + 1 < x.size(); ++k) {
          jacobians.push_back(context.map_at(T(k * h)).jacobian(x[k], h));
          noise.push_back(context.map->last_jacobian_unit() / context.map->jacobian_unit());
          noise_raised_tolerance = noise_raised_tolerance || noise.back() > 1;
          scale = scale.cwiseMax(phase_size<T, N>(context, context.at_step(h, static_cast<long>(k)), x[k].q, x[k].w, k,
                                                  x.size() - 1));
        }
        // The noise is measured at the first step and every eighth, the largest so far standing
        // for the steps between; the largest of the whole run stands for every step of it (a step
        // before the measurement that found it is no less noisy), scaled by each step's |J| as
        // the map scales it (ProcessMap: 1.5·r·10^e / max(1, |J|)).
        if (!jacobians.empty() && noise.back() > 1) {
          const T last_size = nan_max(T(1), max_entry<T, twice(N), twice(N)>(jacobians.back()));
          for (std::size_t k = 0; k < jacobians.size(); ++k)
            noise[k] = nan_max(noise[k], T(noise.back() * last_size /
                                            nan_max(T(1), max_entry<T, twice(N), twice(N)>(jacobians[k]))));
        }
        std::size_t worst = 0;
        units.push_back(judge<T, N>(check, h, jacobians, noise, context.map->jacobian_unit(), exponents, worst));
        // The map on (q, p) itself: w from p by the inverse Legendre transform, one step, p' =
        // FL(q', w').
        // (For an L that depends on time, p at the step's start is FL at t0 + worst·h, p' at h later.)
        const State<T, N>& at = x[worst];
        const System before = context.at_step(h, static_cast<long>(worst)),
                     after = context.at_step(h, static_cast<long>(worst) + 1);
        auto step = [&](const Vector<T, twice(N)>& y) {
          State<T, N> from;
          from.q = y.head(n);
          from.w = velocity_for_momentum(before, from.q, Vector<T, N>(y.tail(n)), at.w);
          const State<T, N> to = context.map_at(T(worst * h)).step(from, h);
          Vector<T, twice(N)> out(2 * n);
          out << to.q, momentum(after, to.q, to.w);
          return out;
        };
        Vector<T, twice(N)> y(2 * n);
        y << at.q, momentum(before, at.q, at.w);
        // A double program's answers carry the noise it measured (answer_noise, a spread r): its
        // differences may differ from its Jacobian by 2·3r/δ more (3r bounds a rounding of spread r;
        // a Verlet whose force kept 32 bits missed by 1.1e-7 against the 1.5e-8 its widths' changes
        // allowed, by chance of its quantized rounding).
        std::optional<Vector<T, twice(N)>> rounding;
        if (const std::optional<T> noise_r = context.map_at(T(worst * h)).answer_noise(at, h)) {
          rounding = Vector<T, twice(N)>(2 * n);
          rounding->setConstant(T(3 * *noise_r));
        }
        jacobian_checks.push_back(check_jacobian(h, worst, step, y, jacobians[worst], scale, context.working_epsilon(),
                                                 rounding ? &*rounding : nullptr));
      });
      claim.evidence["jacobian"] = context.map->jacobian_method();
      claim.evidence["jacobian_unit"] = to_decimal<T>(context.map->jacobian_unit(), 6);
      claim.evidence["tolerance_rule"] = tolerance_rule(
          " × max(1, |J|)² per step (measured: the step with the largest defect/tolerance); N × that × "
          "max(1, |J_N…J_1|)² for the composition");
    } else if (judged_by_probes(context)) {
      if constexpr (N == any_size) measure_by_probes(context, exponents, check, units, jacobian_checks);
      claim.evidence["jacobian"] =
          "not formed: each step judged by its generating form (B_b, E_e symmetric and E_b = -B_e^T, with "
          "B = d p_begin[L_d], E = d p_end[past L_d] at (q_k, q_k+1)); J applied to vectors for the composition "
          "and the check against differences: dq' = B_e^-1 (dp - B_b dq), dp' = E_b dq + E_e dq', B_e factored by "
          "a sparse LU";
      claim.evidence["probes"] = probes_evidence(
          std::to_string(probe_pairs) +
               " pairs of standard Gaussian vectors (xi, eta) on (q, p) carried through the whole run: "
               "|omega(Phi xi, Phi eta) - omega(xi, eta)| = |xi^T (Phi^T Omega Phi - Omega) eta| per unit "
               "|xi||eta| (composite_defect) against N x " +
               std::to_string(ulps) +
               " ulps x max_k(s_k r_k^2) x max(1, |Phi xi|/|xi|, |Phi eta|/|eta|)^2, r_k the carried vectors' "
               "stretch at step k (composite_tolerance)",
          "a composition whose ||Phi^T Omega Phi - Omega||_2 is at least 10 x its tolerance x |xi||eta| "
           "(|xi||eta| about 2n) passes all " +
               std::to_string(probe_pairs) + " pairs with probability at most 10^-" + std::to_string(probe_pairs) +
               " (P(|xi^T D eta| < t ||D||_2) <= t for antisymmetric D)");
      claim.evidence["tolerance_rule"] = tolerance_rule(
          " × max(1, |Hessian blocks|) per step for max(|E_b + B_eᵀ|, |B_b − B_bᵀ|, |E_e − E_eᵀ|) "
          "(measured: the step with the largest defect/tolerance), balanced; the composition by probes "
          "(evidence.probes)");
      claim.evidence["mismatched_del"] = context.scheme.mismatched;
    } else {
      visit_trajectories(context, "symplecticity: Jacobians", [&](const T& h, const auto& q) {
        using std::max;
        std::vector<Matrix<T, twice(N), twice(N)>> jacobians;
        std::vector<T> sizes;
        Vector<T, twice(N)> scale = zero_vector<T, twice(N)>(2 * n);  // each coordinate's size along the run
        for (std::size_t k = 0; k + 1 < q.size(); ++k) {
          const System at_k = context.at_step(h, static_cast<long>(k));  // step k's segment starts at t0 + k·h
          const auto future = discrete_legendre(at_k, context.scheme.future, q[k], q[k + 1], h);
          scale = scale.cwiseMax(phase_size<T, N>(context, at_k, q[k], Vector<T, N>((q[k + 1] - q[k]) / h), k,
                                                  q.size() - 1, &future.p_begin));
          // A matched scheme's past side is the same discretization at the same points: the same
          // numbers, not computed twice.
          const auto past =
              context.scheme.mismatched
                  ? discrete_legendre(at_k, context.scheme.past, q[k], q[k + 1], h)
                  : future;
          jacobians.push_back(del_map_jacobian<T, N>(future, past));
          sizes.push_back(nan_max({T(1), max_entry<T, N, N>(future.dp_begin_dq_b), max_entry<T, N, N>(future.dp_begin_dq_e),
                               max_entry<T, N, N>(past.dp_end_dq_b), max_entry<T, N, N>(past.dp_end_dq_e)}));
        }
        std::size_t worst = 0;
        units.push_back(judge<T, N>(check, h, jacobians, sizes, epsilon<T>(), exponents, worst));
        // The DEL's map on (q, p) itself: q' by Newton on p_begin[future](q, q') = p from the
        // trajectory's q_{k+1}, p' = p_end[past](q, q').
        const Vector<T, N>& q_next = q[worst + 1];
        const System at_worst = context.at_step(h, static_cast<long>(worst));
        auto step = [&](const Vector<T, twice(N)>& y) {
          const Vector<T, N> from = y.head(n), p = y.tail(n);
          Vector<T, N> to = q_next;
          auto report = newton_solve<T, N>(to, [&](const Vector<T, N>& x, Vector<T, N>& residual,
                                                   Matrix<T, N, N>& jacobian) {
            auto legendre = discrete_legendre(at_worst, context.scheme.future, from, x, h);
            residual = legendre.p_begin - p;
            jacobian = legendre.dp_begin_dq_e;
          });
          require_converged(
              report, "symplecticity's check of its Jacobian: a DEL step from a perturbed (q, p)");
          Vector<T, twice(N)> out(2 * n);
          out << to, p_end(at_worst, context.scheme.past, from, to, h);
          return out;
        };
        Vector<T, twice(N)> y(2 * n);
        y << q[worst], p_begin(at_worst, context.scheme.future, q[worst], q_next, h);
        // The rounding of the step's outputs, which central differences cannot see when it drifts
        // with their width (core/structure/symplectic.hpp, compare_with_differences).
        const auto end = discrete_legendre(
            at_worst, context.scheme.mismatched ? context.scheme.past : context.scheme.future, q[worst], q_next, h);
        const T unit = context.working_epsilon();
        const Vector<T, twice(N)> rounding = del_step_rounding<T, N, twice(N)>(end, q[worst], q_next, scale, unit);
        jacobian_checks.push_back(
            check_jacobian(h, worst, step, y, jacobians[worst], scale, unit, &rounding));
      });
      claim.evidence["jacobian"] =
          "implicit function theorem: dq'/d(q, p) = B_e^-1 (-B_b, I), dp'/d(q, p) = (E_b, 0) + E_e dq'/d(q, p) "
          "with B = d p_begin[L_d], E = d p_end[past L_d] at (q_k, q_k+1)";
      claim.evidence["tolerance_rule"] = tolerance_rule(
          " × max(1, |Hessian blocks|) × max(1, |J|)² per step (measured: the step with the largest "
          "defect/tolerance); N × that × max(1, |J_N…J_1|)² for the composition");
      claim.evidence["mismatched_del"] = context.scheme.mismatched;
    }
    if (!exponents.empty())
      claim.evidence["balancing"] = {
          {"rule",
           "J judged in the coordinates q~_i = 2^e_i q_i, p~_i = 2^-e_i p_i, e_i the nearest integer to "
           "log2 sqrt(M_ii) at the initial state (M = d2L/dw2): a symplectic change of coordinates, exact "
           "in binary arithmetic, that keeps the entries of a Jacobian of bodies of very different masses "
           "(dq/dp = h/m) within the precision"},
          {"exponents", exponents}};
    check.scaling_failure = truncation_scaling(context.steps(), check.values, units, resolved);
    check.scaling_limit = "a defect above " + std::to_string(resolved) +
                          " rounding units at two h that falls like a power of h";
    claim.evidence["rounding_unit_rule"] =
        "u = ε·s·max(1, |J|)² per step (s the largest Hessian block; for a one-step map 1, or the noise "
        "its answers show in units of evidence.jacobian_unit, which replaces ε for a map whose Jacobian comes "
        "from differences at a double's widths: rows[].step_size_factor); a step "
        "fails above " +
        std::to_string(ulps) + " u, and defects above " + std::to_string(resolved) +
        " u at two or more h falling like a power of h fail as truncation";
    const bool generating_form = !context.map && judged_by_probes(context);
    if (generating_form)
      claim.evidence["rounding_unit_rule"] =
          "u = ε·s per step (s the largest balanced Hessian block, rows[].step_size_factor); a step fails "
          "above " + std::to_string(ulps) + " u, and defects above " + std::to_string(resolved) +
          " u at two or more h falling like a power of h fail as truncation";
    const bool map_probes = context.map && judged_by_probes(context);
    if (map_probes)
      claim.evidence["rounding_unit_rule"] =
          "u = the relative rounding of the map's products J v (evidence.jacobian_unit, or the noise its answers "
          "show: rows[].step_size_factor in units of it) times max(1, g)², g the probes' largest |J v|/|v|; a step "
          "fails above " + std::to_string(ulps) + " u, and defects above " + std::to_string(resolved) +
          " u at two or more h falling like a power of h fail as truncation";
    check.conclude_claim(claim, context,
                         generating_form ? "max_k of |E_b + B_eᵀ|, |B_b − B_bᵀ|, |E_e − E_eᵀ| (the DEL map's generating "
                                           "form of JᵀΩJ = Ω; worst step against its tolerance)"
                         : map_probes    ? "max_k of |ξᵀ(J_kᵀΩJ_k − Ω)η| / (|ξ||η|) over each step's fresh Gaussian "
                                           "pairs (worst step against its tolerance)"
                                         : "max_k |J_kᵀΩJ_k − Ω| (worst step against its tolerance)",
                         "symplectic to working precision at every step and every h, and so is the N-step map",
                         "the (q, p) map is not symplectic");
    conclude_jacobian_checks(claim, jacobian_checks);
    if (noise_raised_tolerance)
      record_answer_noise(context, claim, "the per-step tolerance (its Jacobian by differences of those answers)");
  }

  // The Jacobian of the judged step at one h against central differences of the step's map.
  struct JacobianCheck {
    nlohmann::json row;
    bool holds = true;
    std::string where;
  };
  template <class T, int m, class Map>
  static JacobianCheck check_jacobian(const T& h, std::size_t step, const Map& map,
                                      const Vector<T, m>& y, const Matrix<T, m, m>& jacobian,
                                      const Vector<T, m>& scale, const T& unit,
                                      const Vector<T, m>* output_rounding = nullptr) {
    return jacobian_check_row(h, step, compare_with_differences<T, m>(map, y, jacobian, scale, unit, output_rounding));
  }
  template <class T>
  static JacobianCheck jacobian_check_row(const T& h, std::size_t step, const JacobianAgreement<T>& agreement) {
    const std::string at = "at h = " + format_scalar(h, 6) + ", step " + std::to_string(step) + " ";
    require_finite(agreement.mismatch, at + "the Jacobian's distance from central differences of its map");
    require_finite(agreement.allowed, at + "the allowance of the Jacobian's check against differences");
    JacobianCheck out;
    out.holds = agreement.holds;
    out.row = {{"h", to_decimal<T>(h)},
               {"step", step},
               {"mismatch", to_decimal<T>(agreement.mismatch)},
               {"allowed", to_decimal<T>(agreement.allowed)},
               {"holds", agreement.holds}};
    out.where = "at h = " + to_decimal<T>(h, 6) + ", step " + std::to_string(step) +
                " the Jacobian judged is " + format_scalar(agreement.mismatch, 3) +
                " from central differences of that step's map (allowed " +
                format_scalar(agreement.allowed, 3) + ")";
    return out;
  }
  // (|q_i|, the size of the terms of p_i) at one state: p = ∂L/∂w is a sum of terms — M w and
  // the rest, ∂L/∂w − M w (a vector potential) — whose rounding it carries, however small it is
  // (p_x = v_x − B·y ≈ 3·10⁻⁶ of terms near 0.8 for a charge in the Landau gauge). A width sized
  // by |p_i| alone drowned the differences in that rounding, and the check called an exactly
  // symplectic midpoint's Jacobian wrong (6.8e-8 against 7.3e-10 in long double).
  // The terms (a Hessian) at 64 steps spread over the run of `steps` steps, |p_i| at every step
  // (`p` the DEL's momentum at step k when given, else FL(q, w)).
  // `system`: the case's, at the state's time.
  template <class T, int N, LagrangianSystem System>
  static Vector<T, twice(N)> phase_size(const CaseContext<System>& context, const System& system,
                                     const Vector<T, N>& q, const Vector<T, N>& w, std::size_t k, std::size_t steps,
                                     const Vector<T, N>* p = nullptr) {
    (void)context;
    Vector<T, twice(N)> size(2 * q.size());
    const std::size_t stride = std::max<std::size_t>(1, steps / 64);
    if (k % stride != 0 && k + 1 != steps) {
      size << q.cwiseAbs(), (p ? *p : momentum(system, q, w)).cwiseAbs();
      return size;
    }
    size << q.cwiseAbs(), momentum_term_sizes(system, q, w);
    return size;
  }
  // The exponents e_i of the balancing (core/structure/symplectic.hpp, balanced): the nearest
  // integer to log2 √M_ii, M = ∂²L/∂w² at the initial state, 0 where M_ii is not a positive
  // normal number (an indefinite L's negative entry; a zero, whose log2 is −∞, though a formula
  // system with M_ii ≡ 0 is refused before this by its Euler–Lagrange tape); empty when every
  // e_i is 0 (unit masses: the Jacobians are judged as they are). mutate-rules' `mass >= 0`
  // fault is thereby the same rule.
  template <LagrangianSystem System>
  static std::vector<int> balancing(const CaseContext<System>& context) {
    using std::isnormal, std::log2, std::lround;
    const auto d = lagrangian_derivatives(context.system, context.initial.q, context.initial.w);
    std::vector<int> exponents(static_cast<std::size_t>(context.n), 0);
    bool any = false;
    for (int i = 0; i < context.n; ++i) {
      const double mass = static_cast<double>(d.d2L_dw2(i, i));
      if (!(isnormal(mass) && mass > 0)) continue;
      exponents[static_cast<std::size_t>(i)] = static_cast<int>(lround(log2(mass) / 2));
      any = any || exponents[static_cast<std::size_t>(i)] != 0;
    }
    if (!any) exponents.clear();
    return exponents;
  }
  // A Jacobian that is not the derivative of the step it is judged for makes the verdict
  // meaningless either way: the claim is an error, whatever the identity measured.
  static void conclude_jacobian_checks(ClaimResult& claim,
                                       const std::vector<JacobianCheck>& checks) {
    nlohmann::json rows = nlohmann::json::array();
    for (const JacobianCheck& c : checks) rows.push_back(c.row);
    claim.evidence["jacobian_check"] = {
        {"rule",
         "at each h, the judged (worst) step's Jacobian against central differences of the step's "
         "own "
         "map on (q, p) at widths δ = ε^(1/3)·max(|x_j|, the coordinate's largest size along the "
         "run), δ/2 "
         "and δ/4: it may differ from the widest by 4 × the larger change between them + √ε·|J|"},
        {"rows", rows}};
    for (const JacobianCheck& c : checks)
      if (!c.holds) {
        claim.verdict = "error";
        claim.explanation =
            c.where + ": the identity was measured on a matrix that is not this map's derivative";
        claim.detection_limit = "none: the identity was measured on a matrix that is not the map's derivative";
        return;
      }
  }

 private:
  template <LagrangianSystem System>
  static bool judged_by_probes(const CaseContext<System>& context) {
    return System::dimension == any_size && context.n > dense_limit;
  }

  // The DEL map judged by its generating form and probes (see dense_limit): per h, the step with
  // the largest defect/tolerance is the one judged and its J is checked against differences of
  // its map along two random directions; the composition through the pairs carried along the run.
  template <LagrangianSystem System, class T = typename System::Scalar>
  static void measure_by_probes(const CaseContext<System>& context, const std::vector<int>& exponents,
                                PerStepCheck<T>& check, std::vector<T>& units,
                                std::vector<JacobianCheck>& jacobian_checks) {
    using V = Vector<T, any_size>;
    using Blocks = SparseLegendreBlocks<T>;
    const int n = context.n;
    // J̃ = S J S⁻¹ with S = diag(2^e, 2^−e) (balanced, core/structure/symplectic.hpp).
    auto rescale = [&](const V& v, int sign) { return balanced_vector<T, any_size>(v, exponents, sign); };
    std::size_t index = 0;
    visit_trajectories(context, "symplecticity: generating form and probes", [&](const T& h, const auto& q) {
      using std::max;
      GaussianProbes draw(probe_seed + index++);
      const int steps = static_cast<int>(q.size()) - 1;
      std::vector<V> start_xi, start_eta, xi, eta;  // the composition's pairs: at step 0, carried
      for (int i = 0; i < probe_pairs; ++i) {
        start_xi.push_back(draw.next<T>(2 * n));
        start_eta.push_back(draw.next<T>(2 * n));
      }
      xi = start_xi, eta = start_eta;
      V scale = V::Zero(2 * n);
      T worst_ratio = -1, worst_defect = 0, worst_tolerance = 0, largest_defect = 0, step_unit = 0;
      std::size_t worst = 0;
      for (int k = 0; k < steps; ++k) {
        const System at_k = context.at_step(h, k);  // step k's segment starts at t0 + k·h
        const Blocks future = legendre_blocks(at_k, context.scheme.future, q[k], q[k + 1], h);
        std::optional<Blocks> mismatched;  // a matched scheme's past side is the future's numbers
        if (context.scheme.mismatched)
          mismatched = legendre_blocks(at_k, context.scheme.past, q[k], q[k + 1], h);
        const Blocks& past = mismatched ? *mismatched : future;
        scale = scale.cwiseMax(V(phase_size<T, any_size>(context, at_k, q[k], Vector<T, any_size>((q[k + 1] - q[k]) / h),
                                                         static_cast<std::size_t>(k), q.size() - 1, &future.p_begin)));
        const std::string where = "at h = " + format_scalar(h, 6) + ", step " + std::to_string(k) + " of " +
                                  std::to_string(steps);
        // The generating form, entry by entry (balanced), and the carried pairs through J̃ = S J S⁻¹.
        const GeneratingDefect<T> generating = generating_defect(future, past, exponents);
        const T defect = generating.defect, tolerance = ulps * epsilon<T>() * generating.size;
        require_finite(defect, where + " |E_b + B_eᵀ|, |B_b − B_bᵀ|, |E_e − E_eᵀ|");
        require_finite(tolerance, where + " its tolerance");
        largest_defect = nan_max(largest_defect, defect);
        if (defect / tolerance > worst_ratio)
          worst_ratio = defect / tolerance, worst_defect = defect, worst_tolerance = tolerance,
          worst = static_cast<std::size_t>(k);
        const DelMapJacobian<T> jacobian(future, past);
        if (!jacobian.invertible())
          throw SolverError(where + ": the DEL's dp_begin/dq_end is singular, so its map has no Jacobian there");
        auto apply = [&](const V& balanced_v) { return rescale(jacobian.apply(rescale(balanced_v, -1)), 1); };
        T stretch = 1;
        for (int i = 0; i < probe_pairs; ++i) {
          const V next_xi = apply(xi[i]), next_eta = apply(eta[i]);
          stretch = nan_max({stretch, T(next_xi.norm() / xi[i].norm()), T(next_eta.norm() / eta[i].norm())});
          xi[i] = next_xi, eta[i] = next_eta;
        }
        step_unit = nan_max(step_unit, T(epsilon<T>() * generating.size * stretch * stretch));
      }
      const auto [composite_defect, composite_tolerance] =
          composite_probes<T>(probe_pairs, steps, ulps, step_unit, h,
                              [&](int i) { return probe_defect<T>(start_xi[i], start_eta[i], xi[i], eta[i]); });
      add_symplecticity_row<T>(check, h, steps, ulps, worst_defect, worst_tolerance, largest_defect,
                               composite_defect, composite_tolerance, T(worst_tolerance / (ulps * epsilon<T>())));
      units.push_back(worst_tolerance / ulps);
      // The judged step's J against differences of its map on (q, p) along two directions.
      const V& q_next = q[worst + 1];
      const System at_worst = context.at_step(h, static_cast<long>(worst));
      const Blocks future = legendre_blocks(at_worst, context.scheme.future, q[worst], q_next, h);
      std::optional<Blocks> mismatched;
      if (context.scheme.mismatched)
        mismatched = legendre_blocks(at_worst, context.scheme.past, q[worst], q_next, h);
      const Blocks& past = mismatched ? *mismatched : future;
      const DelMapJacobian<T> jacobian(future, past);
      if (!jacobian.invertible())
        throw SolverError("at h = " + format_scalar(h, 6) + " the judged step's dp_begin/dq_end is singular");
      auto apply = [&](const V& v) { return jacobian.apply(v); };
      auto step = [&](const V& y) {
        const V to = next_configuration(at_worst, context.scheme.future, V(y.head(n)), V(y.tail(n)), q_next, h,
                                        "symplecticity's check of its Jacobian: a DEL step from a perturbed (q, p)");
        V out(2 * n);
        out << to, p_end(at_worst, context.scheme.past, V(y.head(n)), to, h);
        return out;
      };
      V y(2 * n);
      y << q[worst], future.p_begin;
      const T unit = context.working_epsilon();
      V rounding(2 * n);  // del_step_rounding's, from the sparse blocks of the side giving p_end
      const Blocks& end = past;
      V sizes_q(n), sizes_next(n);
      for (int i = 0; i < n; ++i) {
        using std::abs;
        sizes_q[i] = max(T(abs(q[worst][i])), T(abs(scale[i])));
        sizes_next[i] = max(T(abs(q_next[i])), T(abs(scale[i])));
        rounding[i] = unit * sizes_next[i];
      }
      const V terms = absolute(end.dp_end_dq_b) * sizes_q + absolute(end.dp_end_dq_e) * sizes_next;
      for (int i = 0; i < n; ++i) {
        using std::abs;
        rounding[n + i] = unit * (max(T(abs(end.p_end[i])), T(abs(scale[n + i]))) + terms[i]);
      }
      const JacobianAgreement<T> agreement =
          compare_directions_with_differences<T>(step, apply, y, scale, draw, 2, unit, &rounding);
      jacobian_checks.push_back(jacobian_check_row(h, worst, agreement));
    });
  }
  template <class T>
  static Eigen::SparseMatrix<T> absolute(const Eigen::SparseMatrix<T>& a) {
    return a.unaryExpr([](const T& x) { using std::abs; return T(abs(x)); });
  }

  // The verdict at one h from the step Jacobians J_k and the sizes s_k of what they were
  // computed from: each step against ulps·u_k, u_k = unit·s_k·max(1, |J_k|)² (unit the relative
  // rounding of the Jacobian's entries: ε, or a double program's differences'), the composition
  // against N times the largest of those times max(1, |J_N…J_1|)². Returns the rounding unit of
  // the step judged (the largest defect/tolerance) and sets `worst_step` to its index. Each J_k
  // is judged balanced by `exponents` (see balancing).
  template <class T, int N>
  static T judge(PerStepCheck<T>& check, const T& h,
                 const std::vector<Matrix<T, twice(N), twice(N)>>& jacobians, const std::vector<T>& sizes,
                 const T& unit, const std::vector<int>& exponents, std::size_t& worst_step) {
    using std::max;
    const int steps = static_cast<int>(jacobians.size());
    const int size = jacobians.empty() ? std::max(0, twice(N)) : static_cast<int>(jacobians.front().rows());
    Matrix<T, twice(N), twice(N)> composition = Matrix<T, twice(N), twice(N)>::Identity(size, size);
    T worst_ratio = -1, worst_defect = 0, worst_tolerance = 0, largest_defect = 0, step_tolerance = 0;
    for (int k = 0; k < steps; ++k) {
      const Matrix<T, twice(N), twice(N)> jacobian = balanced<T, twice(N)>(jacobians[k], exponents);
      composition = jacobian * composition;
      const T largest = max_entry<T, twice(N), twice(N)>(jacobian);
      const T entry = nan_max(T(1), largest);
      const T tolerance = ulps * unit * sizes[k] * entry * entry;
      const T defect = symplecticity_defect<T, twice(N)>(jacobian);
      const std::string where = "at h = " + format_scalar(h, 6) + ", step " + std::to_string(k) + " of " +
                                std::to_string(steps) + " (the Jacobian's largest entry " +
                                format_scalar(largest, 3) + (exponents.empty() ? "" : ", balanced") + ")";
      require_finite(defect, where + " |JᵀΩJ − Ω|");
      require_finite(tolerance, where + " its tolerance");
      // An allowance of |Ω| = 1 or more would pass JᵀΩJ = 0: the identity cannot be measured at
      // that step in this precision (a program's Jacobian with entries 1e160, which in double
      // overflowed to NaN, is finite in float128 and would have passed against 1.6e310).
      if (!(tolerance < 1))
        throw UnmeasurableJacobian(where + ": its rounding allowance " + format_scalar(tolerance, 3) +
                                   " reaches |Ω| = 1, so even JᵀΩJ = 0 would pass: a Jacobian this large "
                                   "leaves the identity unmeasurable in this precision");
      step_tolerance = nan_max(step_tolerance, tolerance);
      largest_defect = nan_max(largest_defect, defect);
      if (defect / tolerance > worst_ratio)
        worst_ratio = defect / tolerance, worst_defect = defect, worst_tolerance = tolerance,
        worst_step = static_cast<std::size_t>(k);
    }
    const T composed = nan_max(T(1), max_entry<T, twice(N), twice(N)>(composition));
    const T composite_defect = symplecticity_defect<T, twice(N)>(composition);
    const T composite_tolerance = T(steps) * step_tolerance * composed * composed;
    const std::string composite = "at h = " + format_scalar(h, 6) + " the " + std::to_string(steps) +
                                  "-step composition's ";
    require_finite(composite_defect, composite + "|JᵀΩJ − Ω|");
    require_finite(composite_tolerance, composite + "tolerance");
    add_symplecticity_row<T>(check, h, steps, ulps, worst_defect, worst_tolerance, largest_defect, composite_defect,
                             composite_tolerance, T(sizes[worst_step]));
    return worst_tolerance / ulps;
  }
};

}  // namespace vivv
