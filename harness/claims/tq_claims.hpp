// Claims stated on discretizations of TQ (paper §4–6, docs/claims.md):
//   order:                |F_h(v) − F^exact_h(v)| = O(h^{r+1})       (Theorem 5.5)
//   contact-order:        |F²_h(v) − F¹_h(v)| = O(h^{r+1}) for two
//                         discretizations in order-r contact         (Theorem 5.4)
//   qxq-tq-equivalence:   Psi(F_h(v)) = DEL(Psi(v)), Psi = (d−, d+)  (Lemma 6.1)
//   existence-uniqueness: Newton from the h = 0 solution converges for
//                         h <= h_max(v), h_max(v) > 0 however fast v is;
//                         the critical point is unique near the diagonal;
//                         F_h(v) − v = O(h)                           (Theorem 4.2)
#pragma once

#include <cmath>

#include "harness/claims/claim.hpp"

namespace vivv {

// F_h(v) from the case's initial state, or an error naming h; mismatched (d+
// and P+ at v from `past`) when `past` is given.
template <LagrangianSystem System>
State<typename System::Scalar, System::dimension> tq_map(const CaseContext<System>& context,
                                                         const TQDiscretization<typename System::Scalar>& d,
                                                         const typename System::Scalar& h,
                                                         const TQDiscretization<typename System::Scalar>* past = nullptr) {
  using T = typename System::Scalar;
  auto step = tq_step(context.system, past ? *past : d, d, context.initial, h);
  require_converged(step.report, "TQ step with h = " + to_decimal<T>(h, 17));
  return step.next;
}

struct LocalOrderClaim : Claim<LocalOrderClaim> {
  static constexpr const char* id = "order";
  static constexpr const char* series_rules[] = {"order", "floor", "none"};
  static constexpr const char* source = "paper Thm 5.5";
  static constexpr const char* prediction =
      "local error |F_h(v) − F^exact_h(v)| = O(h^{r+1}) for an order-r discretization of TQ";

  // r + 1, r the order of the evolution.
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    return context.map_order() + 1;
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    std::vector<T> error = measure_each_step(context, "order: local error", [&](const T& h) {
      return state_distance(tq_map(context, *context.tq, h), context.exact(h));
    });
    claim.evidence["evolution_order_r"] = context.map_order();
    claim.series.push_back(sweep_series(context, "|F_h(v) − F^exact_h(v)|", error, predicted(context)));
    conclude(claim);
  }
};

struct ContactOrderClaim : Claim<ContactOrderClaim> {
  static constexpr const char* id = "contact-order";
  static constexpr const char* series_rules[] = {"order", "floor", "none"};
  static constexpr const char* source = "paper Thm 5.4";
  static constexpr const char* prediction =
      "two discretizations in order-r contact have evolutions agreeing to O(h^{r+1}); r is their "
      "mutual order of contact, not the lower of their orders against the exact discretization";

  // r, the two discretizations' mutual order of contact. A past_discretization makes the first
  // evolution mismatched (its negative control): r is then the lower contact of its two sides.
  template <LagrangianSystem System>
  static int mutual_order(const CaseContext<System>& context) {
    int r = contact_order(*context.tq, *context.tq_compare);
    if (context.tq_past) r = std::min(r, contact_order(*context.tq_past, *context.tq_compare));
    return r;
  }

  // r + 1.
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    return mutual_order(context) + 1;
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    const int r = mutual_order(context);
    std::vector<T> difference = measure_each_step(context, "contact-order", [&](const T& h) {
      return state_distance(tq_map(context, *context.tq, h, context.tq_past ? &*context.tq_past : nullptr),
                            tq_map(context, *context.tq_compare, h));
    });
    claim.evidence["contact_order_r"] = r;
    claim.evidence["mismatched_first_evolution"] = context.tq_past.has_value();
    claim.evidence["orders_against_exact"] = {nominal_order(*context.tq), nominal_order(*context.tq_compare)};
    claim.series.push_back(sweep_series(context, "|F²_h(v) − F¹_h(v)|", difference,
                                        predicted(context), context.floors_without_reference()));
    conclude(claim);
  }
};

struct QxQTQEquivalenceClaim : Claim<QxQTQEquivalenceClaim> {
  static constexpr const char* id = "qxq-tq-equivalence";
  static constexpr const char* series_rules[] = {"per-step-tolerance"};
  static constexpr const char* source = "paper §6, Lemma 6.1";
  static constexpr const char* prediction =
      "the TQ evolution of L_h = L_d(d−, d+; h) equals the Q×Q DEL of L_d conjugated by "
      "Psi(v) = (d−(v), d+(v)), to working precision";
  static constexpr int compared_steps = 8;

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    using std::max;
    const auto& d = *context.tq;
    PerStepCheck<T> check;
    for (const T& h : context.steps()) {
      context.report("qxq-tq-equivalence at h = " + to_decimal<T>(h, 6));
      // A past_discretization makes the TQ steps mismatched: the negative control.
      auto states = tq_trajectory(context.system, context.tq_past ? *context.tq_past : d, d, context.initial, h,
                                  compared_steps);
      // The DEL from Psi(v_0) = (d−(v_0), d+(v_0)).
      auto v0 = tangent_point(states[0]);
      auto del = del_trajectory(context.system, matched_scheme(d.qxq),
                                as_vector<T, N>(d_minus<T, N>(d, v0, h)), as_vector<T, N>(d_plus<T, N>(d, v0, h)),
                                h, compared_steps + 1);
      T gap = 0, scale = 1;
      for (int k = 0; k <= compared_steps; ++k) {
        auto v = tangent_point(states[k]);
        gap = nan_max(gap, max_norm<T, N>(as_vector<T, N>(d_minus<T, N>(d, v, h)) - del.q[k]));
        gap = nan_max(gap, max_norm<T, N>(as_vector<T, N>(d_plus<T, N>(d, v, h)) - del.q[k + 1]));
        scale = nan_max(scale, max_norm<T, N>(del.q[k]));
      }
      // Both evolutions round at each of their Newton solves (64 ulps each).
      check.add(h, gap, T(1024 * T(compared_steps) * epsilon<T>() * scale), {{"steps_compared", compared_steps}});
    }
    claim.evidence["mismatched_tq_steps"] = context.tq_past.has_value();
    check.conclude_claim(claim, context, "max_k |Psi(v_k) − (q_k, q_{k+1})|", "equal to working precision at every h",
                         "the TQ and Q×Q evolutions differ");
  }
};

struct ExistenceUniquenessClaim : Claim<ExistenceUniquenessClaim> {
  static constexpr const char* id = "existence-uniqueness";
  static constexpr const char* series_rules[] = {"order", "floor", "none", "step-size-search"};
  static constexpr const char* source = "paper Thm 4.2";
  static constexpr const char* prediction =
      "Newton from the h = 0 solution converges to a near-diagonal critical point for all "
      "h <= h_max(v), with h_max(v) > 0 however fast v is; F_h(v) − v = O(h)";
  static constexpr int speed_levels = 6;   // |w| scaled by 1, 2, 4, ..., 32
  static constexpr int halvings = 40;      // h_max searched from T·2^−40 …
  static constexpr int doublings = 8;      // … up to T·2^8

  // The largest h = T·2^−j (−doublings <= j <= halvings) such that, at that h
  // and every smaller h of the grid, Newton from the h = 0 solution ṽ = v
  // converges and contracts from its first step (each correction at most half
  // the one before, until rounding): the h = 0 solution lies in the region
  // where the blown-up equations have one solution that Newton reaches
  // monotonically — the computable form of Theorem 4.2's neighbourhood of the
  // diagonal. 0 when no h of the grid qualifies.
  template <LagrangianSystem System>
  static typename System::Scalar h_max(const CaseContext<System>& context,
                                       const State<typename System::Scalar, System::dimension>& v) {
    using T = typename System::Scalar;
    using std::ldexp;
    NewtonOptions options;
    options.max_iterations = 30;
    T largest = 0;
    for (int j = halvings; j >= -doublings; --j) {
      T h = ldexp(context.final_time, -j);
      bool contracts = false;
      try {
        auto step = tq_step(context.system, *context.tq, v, h, options);
        contracts = step.report.converged && step.report.contracting;
      } catch (const std::domain_error&) {
      } catch (const SingularLagrangianError&) {
      }
      if (!contracts) break;
      largest = h;
    }
    return largest;
  }

  // F_h(v) − v = O(h).
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>&) {
    return 1;
  }

  // Uniqueness near the diagonal at one h: Newton from 4n starts around the h = 0 solution,
  // (w, w) ± ρ e_j in the blown-up unknowns with ρ = (1 + |w|)/4, each of which that converges
  // must land on F_h(v) to rounding (1024 ε·max(1, |v|)/min(1, h): z = (q̃ − q)/h and, for a
  // pullback, w̃ round at ε|q|/h).
  template <class T>
  struct UniquenessProbe {
    int starts = 0, converged = 0;
    T largest_distance = 0, tolerance = 0;
  };

  template <LagrangianSystem System>
  static UniquenessProbe<typename System::Scalar> probe_uniqueness(
      const CaseContext<System>& context, const State<typename System::Scalar, System::dimension>& next,
      const typename System::Scalar& h) {
    using T = typename System::Scalar;
    constexpr int N = System::dimension;
    using std::max, std::min;
    const State<T, N>& v = context.initial;
    UniquenessProbe<T> probe;
    const T size = nan_max(T(1), nan_max(max_norm<T, N>(v.q), max_norm<T, N>(v.w)));
    probe.tolerance = 1024 * epsilon<T>() * size / nan_min(T(1), h);
    const T radius = (1 + max_norm<T, N>(v.w)) / 4;
    NewtonOptions options;
    options.max_iterations = 30;
    for (int j = 0; j < 2 * static_cast<int>(v.q.size()); ++j)
      for (int sign : {-1, 1}) {
        Vector<T, twice(N)> start = blown_up_identity(v);
        start[j] += sign * radius;
        ++probe.starts;
        try {
          auto step = tq_step_from(context.system, *context.tq, *context.tq, v, h, start, options);
          if (!step.report.converged) continue;
          ++probe.converged;
          probe.largest_distance = nan_max(probe.largest_distance, state_distance(step.next, next));
        } catch (const std::domain_error&) {  // a start outside the Lagrangian's domain
        } catch (const SingularLagrangianError&) {
        }
      }
    return probe;
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    // F_h(v) − v over the sweep: order at least 1; at each h the critical point is unique near
    // the diagonal. Here a failed solve is the measured outcome, not bad input.
    std::vector<T> displacement;
    std::string failure, second_point;
    nlohmann::json uniqueness = nlohmann::json::array();
    for (const T& h : context.steps()) {
      context.report("existence-uniqueness: F_h(v) and its uniqueness at h = " + to_decimal<T>(h, 6));
      auto step = tq_step(context.system, *context.tq, context.initial, h);
      if (!step.report.converged && failure.empty())
        failure = "no critical point found from the h = 0 solution at h = " + to_decimal<T>(h, 17) +
                  ": " + step.report.failure;
      displacement.push_back(state_distance(step.next, context.initial));
      if (!step.report.converged) continue;
      auto probe = probe_uniqueness(context, step.next, h);
      const bool unique = probe.largest_distance <= probe.tolerance;
      if (!unique && second_point.empty())
        second_point = "a second critical point near the diagonal at h = " + to_decimal<T>(h, 17) + ": " +
                       format_scalar(probe.largest_distance) + " from F_h(v) (rounding " +
                       format_scalar(probe.tolerance) + ")";
      uniqueness.push_back({{"h", to_decimal<T>(h)},
                            {"starts", probe.starts},
                            {"converged", probe.converged},
                            {"largest_distance_to_F_h", to_decimal<T>(probe.largest_distance)},
                            {"rounding", to_decimal<T>(probe.tolerance)},
                            {"unique", unique}});
    }
    claim.evidence["uniqueness_by_h"] = uniqueness;
    claim.evidence["uniqueness_search"] =
        "Newton (<= 30 iterations) from (w, w) ± (1 + |w|)/4 along each blown-up unknown (z, w~); "
        "every start that converges must land on F_h(v)";
    claim.series.push_back(sweep_series(context, "|F_h(v) − v|", displacement, predicted(context),
                                        context.floors_without_reference()));
    // h_max against the speed |w|: Theorem 4.2 is semi-global, h_max(v) > 0 however fast v is;
    // h_max·|w| says how it falls.
    using std::ldexp;
    nlohmann::json map = nlohmann::json::array();
    std::optional<T> zero_at;
    State<T, N> v = context.initial;
    if (max_norm<T, N>(v.w) == 0) v.w.setConstant(T(1));
    for (int level = 0; level < speed_levels; ++level) {
      const T speed = max_norm<T, N>(v.w);
      context.report("existence-uniqueness: h_max at |w| = " + to_decimal<T>(speed));
      T largest = h_max(context, v);
      if (!(largest > 0) && !zero_at) zero_at = speed;
      map.push_back({{"speed", to_decimal<T>(speed)},
                     {"h_max", to_decimal<T>(largest)},
                     {"h_max_times_speed", to_decimal<T>(T(largest * speed))},
                     {"at_search_ceiling", largest == ldexp(context.final_time, doublings)}});
      v.w *= 2;
    }
    claim.evidence["h_max_by_speed"] = map;
    claim.evidence["h_max_search"] = "largest h = T·2^-j such that at it and every smaller h of the grid T·2^-" +
                                     std::to_string(halvings) + " … T·2^" + std::to_string(doublings) +
                                     " Newton from the h = 0 solution converges (<= 30 iterations) with every "
                                     "correction at most half the previous one until rounding; T·2^" +
                                     std::to_string(doublings) + " means the search ceiling was reached";
    Series& series = claim.series.front();
    if (!failure.empty() || !second_point.empty() || zero_at) series.rule = "step-size-search";
    if (!failure.empty()) {
      series.holds = false;
      series.explanation = failure;
    } else if (!second_point.empty()) {
      series.holds = false;
      series.explanation = second_point;
    } else if (zero_at) {
      series.holds = false;
      series.explanation = "no step h > 0 works at speed |w| = " + format_scalar(*zero_at, 4) +
                           " (h_max = 0): the semi-global statement needs L regular on all of TQ; "
                           "see h_max_by_speed";
    } else if (series.holds && *series.holds) {
      series.explanation += "; the critical point is unique near the diagonal at every h, and h_max > 0 "
                            "at every speed";
    }
    conclude(claim);
  }
};

}  // namespace vivv
