// Claims measured along one exact solution segment [0, h] from the case's
// initial state, for every h of the sweep:
//   lagrangian-order: |L_d(q(0), q(h); h) − L_d^E| = O(h^{r+1})  (Marsden–West Def. 2.3.1)
//   legendre-order:   |p_end(q(0), q(h)) − p(h)| and |p_begin(q(0), q(h)) − p(0)|
//                     are O(h^r) — not the O(h^{r+1}) of Marsden–West Thm 2.3.1 (2) —
//                     with equal leading coefficients: their difference is O(h^{r+1})
//                     (paper §2.3).
//
// For an L that depends on time the segment is [t0, t0 + h], on the case's system at t0 (its L_d and
// L_d^E start there), p(h) is read at t0 + h, and the exact coefficients from each state of the orbit
// are those of the segment starting at that state's time.
#pragma once

#include "harness/claims/claim.hpp"
#include "references/exact_discrete_lagrangian.hpp"
#include "references/lagrangian_error_expansion.hpp"

namespace vivv {

// Whether the measured leading coefficients c_i = (L_d − L_d^E)/h_i^{r+1} (in the sweep's order,
// decreasing h) settle on the predicted E_{r+1}: the distance at the smallest h against the
// coefficient's own error bar there — at order-1 convergence the last change |c_N − c_{N−1}|,
// or half the change before it (either can dip through zero) — plus `floor`. A correct rule
// passes through a cancellation dip of c − E_{r+1}, where a fitted order would not (the midpoint
// on Duffing once failed at pairwise orders 0.26 and 0.74 while c agreed with E_3 to 6·10⁻⁶);
// a swapped weight settles on another value and fails.
template <class T>
void judge_signed_coefficient(Series& series, const std::vector<T>& coefficient, const T& leading,
                              const T& floor) {
  using std::abs;
  using std::max;
  const std::size_t N = coefficient.size();
  // Below the floor the fit already said what the evidence can decide (inconclusive, naming the
  // digits), and the coefficient's error bar would be rounding. Above it the fitted order of
  // |c − E_(r+1)| is shown, not judged (docs/claims.md): whatever the order rule made of it — a
  // trapezoid rule on a magnetic ring in float128 showed 1.58, 1.49, 1.35, "receding", while c
  // was −1.7420 against E_3 = −1.7554 and converging — this rule alone decides.
  if (N < 2 || (series.inconclusive && series.rule == "floor")) return;
  series.inconclusive = false;
  series.to_decide.clear();
  T bar = abs(T(coefficient[N - 1] - coefficient[N - 2]));
  if (N >= 3) bar = nan_max(bar, T(abs(T(coefficient[N - 2] - coefficient[N - 3])) / 2));
  const T distance = abs(T(coefficient[N - 1] - leading));
  const T allowed = 3 * bar + floor;
  series.rule = "signed-coefficient";
  series.holds = distance <= allowed;
  series.explanation =
      "at the smallest h the measured coefficient " + format_scalar(coefficient[N - 1], 8) +
      " is " + format_scalar(distance, 3) + " from E_(r+1) = " + format_scalar(leading, 8) +
      (*series.holds ? ", within" : ", more than") + " 3 × its own error bar " +
      format_scalar(bar, 3) + " (its last change with h) + the floor " + format_scalar(floor, 3) +
      (*series.holds ? ": holds" : ": it settles on another value, fails");
  series.detection_limit =
      "a leading coefficient more than " + format_scalar(allowed, 3) + " from E_(r+1) fails";
}

// The sign, not only the size: (L_d − L_d^E)/h^{r+1} → E_{r+1}, the leading coefficient of
// E(h) = L_d(q(0), q(h); h) − ∫₀ʰ L dt from the solution's Taylor expansion
// (references/lagrangian_error_expansion.hpp). A swapped weight or interval keeps every order
// but changes E_{r+1}: this series sees it (judge_signed_coefficient). A rule written as a
// formula is expanded from its tape, so it gets the verdict its built-in twin gets.
template <LagrangianSystem System>
void add_signed_coefficient(ClaimResult& claim, const CaseContext<System>& context,
                            const std::vector<typename System::Scalar>& signed_error) {
  using T = typename System::Scalar;
  using std::abs, std::pow;
  const int r = context.lagrangian_order();
  std::vector<T> expansion;
  try {
    expansion = lagrangian_error_expansion(context.system, context.scheme.future, context.initial.q,
                                           context.initial.w, r + 3);
  } catch (const std::domain_error& e) {
    // A formula with no expansion in h at this state (a pole, a square root of zero): the
    // order series above still judges; the coefficient is not compared, and the report says why.
    claim.evidence["leading_coefficient_rule"] = std::string("not compared: ") + e.what();
    return;
  }
  const T leading = expansion[r + 1];
  const std::vector<T> steps = context.steps();
  std::vector<T> distance, coefficient;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    coefficient.push_back(signed_error[i] / pow(steps[i], r + 1));
    distance.push_back(abs(T(coefficient.back() - leading)));
  }
  claim.evidence["leading_coefficient_taylor"] = to_decimal<T>(leading);
  claim.evidence["leading_coefficient_measured_at_smallest_h"] = to_decimal<T>(coefficient.back());
  claim.evidence["leading_coefficient_rule"] =
      "E(h) = L_d(q(0), q(h); h) − ∫₀ʰ L dt = Σ E_k h^k from the Taylor coefficients of the "
      "solution; "
      "(L_d − L_d^E)/h^(r+1) at the smallest h must lie within 3 × its last change with h of "
      "E_(r+1)";
  const Floor<T> floor = context.floors().scaled_down(pow(steps.back(), r + 1));
  Series series =
      make_series("|(L_d − L_d^E)/h^(r+1) − E_(r+1)| (signed leading coefficient)", steps, distance,
                  floor, 1.0, false, context.order_tolerance, context.fit_options);
  judge_signed_coefficient(series, coefficient, leading, floor.value());
  claim.series.push_back(series);
}

// Exact coefficients: an L_d of order r has E(h) = L_d(q(0), q(h); h) − ∫₀ʰ L dt = O(h^{r+1}) along
// every solution, so each coefficient E_k, k ≤ r, of its expansion in h is zero at every state —
// identically, not only in the limit. For a rule given as a formula (built in or written as an
// expression) vivv expands E(h) exactly (references/lagrangian_error_expansion.hpp), so a
// non-zero E_k decides fail without a sweep: a weight off by 10⁻³ whose h term hides in a
// cancellation dip of the sweep, or a spurious term that vanishes at the initial state (∝ w·h
// with w₀ = 0), shows at the states along the reference orbit. Each E_k is a difference of L_d's
// coefficient and the action's; its rounding unit is ε times the size of those terms (below), and
// `rounding_units` of them are allowed (correct rules measure at most 0.99: docs/claims.md).
// Below that the coefficient vanishes to working precision and the sweep decides alone.
template <LagrangianSystem System>
void add_exact_coefficients(ClaimResult& claim, const CaseContext<System>& context, int r) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  using std::abs, std::max, std::pow;
  constexpr int states = 4;
  const T rounding_units = 1024;
  // E_k at each state, and the size of the terms it is computed from: the larger of L_d's and the
  // action's coefficient, largest over the states (L itself may cancel at one of them: T ≈ V),
  // and for E_1 = L_d's h term − L(q, w) the sizes of p·w and p·w − L, L's kinetic and
  // potential parts on a natural system.
  std::vector<std::vector<T>> expansions;
  std::vector<T> times, size(static_cast<std::size_t>(r + 1), T(0));
  for (int j = 0; j < states; ++j) {
    const T t = context.final_time * T(j) / T(states);
    const State<T, N> x = j == 0 ? context.initial : context.reference.advance(context.initial, t);
    const System system = context.at(t);  // the segment from x starts at x's time
    std::vector<T> sizes;
    try {
      expansions.push_back(lagrangian_error_expansion(system, context.scheme.future, x.q, x.w, r + 1, &sizes));
    } catch (const std::domain_error& e) {
      claim.evidence["exact_coefficients"] = "not compared: at t = " + format_scalar(t, 4) + ", " + e.what();
      return;
    }
    times.push_back(t);
    for (int k = 0; k <= r; ++k) size[k] = nan_max(size[k], sizes[k]);
    if (r >= 1) {
      const Vector<T, N> p = momentum(system, x.q, x.w);
      T pw = 0;
      for (int i = 0; i < static_cast<int>(p.size()); ++i) pw += p[i] * x.w[i];
      size[1] = nan_max(size[1], nan_max(abs(pw), abs(T(pw - system.lagrangian(as_point<T, N>(x.q), as_point<T, N>(x.w))))));
    }
  }
  const std::vector<T> steps = context.steps();
  std::vector<T> part(steps.size(), T(0)), allowed(steps.size(), T(0));
  nlohmann::json rows = nlohmann::json::array();
  std::string failure;
  T worst = 0;  // the largest |E_k| in rounding units ε·size_k
  for (int j = 0; j < states; ++j) {
    const std::vector<T>& expansion = expansions[j];
    nlohmann::json coefficients = nlohmann::json::array();
    for (int k = 0; k <= r; ++k) {
      const T unit = epsilon<T>() * size[k];
      const T magnitude = abs(expansion[k]);
      if (magnitude > 0) worst = nan_max(worst, unit > 0 ? T(magnitude / unit) : T(INFINITY));
      coefficients.push_back({{"k", k}, {"E_k", to_decimal<T>(expansion[k], 8)}});
      if (magnitude > rounding_units * unit && failure.empty())
        failure = "the coefficient of h^" + std::to_string(k) + " of L_d − L_d^E is " + format_scalar(expansion[k], 4) +
                  " at the state x(" + format_scalar(times[j], 4) + ") of the reference orbit, where rounding allows " +
                  format_scalar(T(rounding_units * unit), 3) + ": L_d is not of order " + std::to_string(r) +
                  " (every coefficient of h^k, k ≤ " + std::to_string(r) + ", vanishes for an order-" +
                  std::to_string(r) + " L_d)";
    }
    for (std::size_t i = 0; i < steps.size(); ++i) {
      T sum = 0, bound = 0;
      for (int k = 0; k <= r; ++k) {
        sum += expansion[k] * pow(steps[i], k);
        bound += rounding_units * epsilon<T>() * size[k] * pow(steps[i], k);
      }
      part[i] = nan_max(part[i], abs(sum));
      allowed[i] = nan_max(allowed[i], bound);
    }
    rows.push_back({{"t", to_decimal<T>(times[j], 8)}, {"coefficients", coefficients}});
  }
  nlohmann::json units = nlohmann::json::array();
  for (int k = 0; k <= r; ++k) units.push_back(to_decimal<T>(T(epsilon<T>() * size[k]), 3));
  claim.evidence["exact_coefficients"] = rows;
  claim.evidence["exact_coefficients_rounding_unit"] = units;
  claim.evidence["exact_coefficients_largest_in_rounding_units"] = format_scalar(worst, 3);
  Floor<T> floor;
  floor.rounding = allowed.front();
  Series series = make_series("|Σ_{k≤r} E_k h^k| (the terms of L_d − L_d^E that must vanish, from its exact expansion)",
                              steps, part, floor, std::nullopt, false, context.order_tolerance, context.fit_options);
  series.rule = "exact-coefficients";
  series.holds = failure.empty();
  series.explanation =
      failure.empty() ? "every coefficient of h^k, k ≤ " + std::to_string(r) + ", vanishes to rounding at " +
                            std::to_string(states) + " states x(j·T/" + std::to_string(states) +
                            ") of the reference orbit (the largest is " + format_scalar(worst, 3) + " of the " +
                            format_scalar(rounding_units, 4) + " rounding units allowed)"
                      : failure;
  series.detection_limit = "a coefficient E_k, k ≤ " + std::to_string(r) + ", larger than " +
                           format_scalar(rounding_units, 4) + " rounding units ε·(the size of its terms) at one of " +
                           std::to_string(states) + " states fails";
  claim.series.push_back(series);
}

struct LagrangianOrderClaim : Claim<LagrangianOrderClaim> {
  static constexpr const char* id = "lagrangian-order";
  // L_d^E and the expansions on the segment [t0, t0 + h] (and from each state at its own time).
  static constexpr bool takes_time_dependent_lagrangians = true;
  static constexpr const char* series_rules[] = {
      "order", "floor", "none", "signed-coefficient", "exact-coefficients"};
  static constexpr const char* source = "Marsden–West Def. 2.3.1; paper §2.2";
  static constexpr const char* prediction =
      "|L_d(q(0), q(h); h) − ∫₀ʰ L(q, q') dt| = O(h^{r+1}) along solutions";

  // r + 1, r the order of L_d with its twin term.
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    return context.lagrangian_order() + 1;
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    // L_d^E(q(0), q(h); h) by Newton shooting on the Taylor flow and the action
    // by composite Gauss–Legendre (references/exact_discrete_lagrangian.hpp).
    // Shooting must recover the solution's own initial velocity: that mismatch
    // is reported as the cross-check.
    ExactDiscreteLagrangian<System> exact_lagrangian(context.system,
                                                     reference_tolerance_for<T>(context.spec.digits));
    std::vector<T> signed_error;
    T velocity_mismatch = 0;
    int nodes = 0;
    for (const T& h : context.steps()) {
      context.report("lagrangian-order: L_d^E at h = " + to_decimal<T>(h, 6));
      Vector<T, N> q_end = context.exact(h).q;
      auto exact = exact_lagrangian(context.initial.q, q_end, h, &context.initial.w);
      if (!exact.converged)
        throw SolverError("exact discrete Lagrangian at h = " + to_decimal<T>(h, 17) +
                          ": shooting did not converge (residual " + to_decimal<T>(exact.residual) + ")");
      using std::max;
      velocity_mismatch = nan_max(velocity_mismatch, max_norm<T, N>(exact.w_begin - context.initial.w));
      nodes = exact.quadrature_nodes;
      T discrete = discrete_lagrangian(context.system, context.scheme.future, as_point<T, N>(context.initial.q),
                                       as_point<T, N>(q_end), h);
      signed_error.push_back(discrete - exact.value);
    }
    claim.evidence["exact_discrete_lagrangian"] =
        "Newton shooting on the Taylor flow with its variational equations; action by composite "
        "Gauss-Legendre, " + std::to_string(nodes) + " nodes per Taylor step";
    claim.evidence["shooting_velocity_mismatch"] = to_decimal<T>(velocity_mismatch);
    using std::abs;
    std::vector<T> error;
    for (const T& e : signed_error) error.push_back(abs(e));
    claim.series.push_back(sweep_series(context, "|L_d − L_d^E|", error, predicted(context)));
    if (context.scheme.future.rule == QxQRule::galerkin) {
      claim.evidence["leading_coefficient_rule"] =
          "not compared: a Galerkin L_d is extremized by Newton, with no closed expression to expand";
      claim.evidence["exact_coefficients"] =
          "not checked: a Galerkin L_d has no closed expression to expand; the sweep alone judges it";
    } else if constexpr (TapeRecordable<System>) {
      add_signed_coefficient(claim, context, signed_error);
      add_exact_coefficients(claim, context, predicted(context).order - 1);
    }
    conclude(claim);
  }
};

struct LegendreOrderClaim : Claim<LegendreOrderClaim> {
  static constexpr const char* id = "legendre-order";
  static constexpr bool takes_time_dependent_lagrangians = true;  // p(h) read at t0 + h
  static constexpr const char* series_rules[] = {"order", "floor", "none"};
  static constexpr const char* source = "Marsden–West Thm 2.3.1 (2) vs paper §2.3";
  static constexpr const char* prediction =
      "p_end(q(0), q(h)) − p(h) and p_begin(q(0), q(h)) − p(0) are at least O(h^r) — not "
      "necessarily O(h^{r+1}) as Marsden–West state; their leading coefficients are equal, so "
      "their "
      "difference is O(h^{r+1})";

  // r, the order of L_d with its twin term: a lower bound for each transform. Some rules keep
  // r + 1 (Simpson's or two-point Gauss on the straight line, for a separable L: the h^{r+1}
  // coefficient of L_d − L_d^E depends on q only): information, never a failure. A case's
  // "expect" declares the exact order it sees for the transforms.
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    return context.lagrangian_order();
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    Vector<T, N> p_start = momentum(context.system, context.initial.q, context.initial.w);
    std::vector<T> end_error, begin_error, difference;
    for (const T& h : context.steps()) {
      State<T, N> v = context.exact(h);
      auto legendre =
          discrete_legendre(context.system, context.scheme.future, context.initial.q, v.q, h);
      Vector<T, N> end_residual = legendre.p_end - momentum(context.at(h), v.q, v.w);
      Vector<T, N> begin_residual = legendre.p_begin - p_start;
      end_error.push_back(max_norm<T, N>(end_residual));
      begin_error.push_back(max_norm<T, N>(begin_residual));
      difference.push_back(max_norm<T, N>(end_residual - begin_residual));
    }
    const OrderPrediction transforms = predicted(context);
    const int theorem = context.lagrangian_order();
    claim.series.push_back(
        sweep_series(context, "|p_end(q(0), q(h)) − p(h)|", end_error, transforms));
    claim.series.push_back(
        sweep_series(context, "|p_begin(q(0), q(h)) − p(0)|", begin_error, transforms));
    claim.series.push_back(sweep_series(context, "|(p_end − p(h)) − (p_begin − p(0))|", difference,
                                        OrderPrediction{theorem + 1, false}));
    // Which transforms keep r + 1 (Marsden–West's statement, true for some rules): shown, not
    // judged.
    nlohmann::json kept = nlohmann::json::array();
    for (int i = 0; i < 2; ++i) {
      const Series& series = claim.series[static_cast<std::size_t>(i)];
      if (series.fit && series.fit->ok &&
          series.fit->order >= theorem + 1 - context.order_tolerance)
        kept.push_back(series.label);
    }
    claim.evidence["transforms_of_order_r_plus_1"] = kept;
    if (!kept.empty())
      claim.evidence["note"] = "observed order r + 1 = " + std::to_string(theorem + 1) + " for " +
                               std::to_string(kept.size()) +
                               " of the two transforms: this rule keeps the order "
                               "Marsden–West state (information; the paper's bound is r)";
    conclude(claim);
  }
};

}  // namespace vivv
