// past-future-symmetry (proof of paper Theorem 5.4, §2.6): at fixed end points
// q_minus = d−(v), q_plus = d+(ṽ), the blown-up critical points (v, ṽ) of two
// discretizations in order-r contact differ by O(h^r) — the order of their
// graphs — and the residual is symmetric: the leading coefficients of the
// velocity differences Δw = w² − w¹ (at v) and Δw̃ = w̃² − w̃¹ (at ṽ) are equal,
// because at h = 0 the principle L(v) + L(ṽ) is invariant under v ↔ ṽ. So
// Δw − Δw̃ = O(h^{r+1}), and that is what lifts the evolution maps' agreement
// to O(h^{r+1}) (Theorem 5.4).
//
// The end points come from the reference solution: q_minus = q(0) = the case's
// q, q_plus = q(2h). A case may give a past_discretization: then the first pair
// is mismatched (its past segment v uses it, its future segment ṽ the
// discretization), the symmetry is broken, and the claim must fail.
#pragma once

#include "harness/claims/tq_claims.hpp"

namespace vivv {

struct PastFutureSymmetryClaim : Claim<PastFutureSymmetryClaim> {
  static constexpr const char* id = "past-future-symmetry";
  static constexpr const char* series_rules[] = {"order", "floor", "none"};
  static constexpr const char* source = "paper Thm 5.4 (proof), §2.6";
  static constexpr const char* prediction =
      "at fixed end points the blown-up critical points (v, ṽ) of two discretizations in order-r "
      "contact differ by O(h^r), with equal leading coefficients at v and ṽ: Δw − Δw̃ = O(h^{r+1})";

  // r, the mutual order of contact of the second discretization with both
  // segments of the first: the order of Δw; the symmetric residual's is r + 1.
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    return ContactOrderClaim::mutual_order(context);
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    using std::max;
    const auto& first_future = *context.tq;
    const auto& first_past = context.tq_past ? *context.tq_past : first_future;
    const auto& second = *context.tq_compare;
    const int r = *theorem_order(context);
    const OrderPrediction order = predicted(context);
    std::vector<T> difference, asymmetry;
    nlohmann::json rows = nlohmann::json::array();
    for (const T& h : context.steps()) {
      context.report("past-future-symmetry at h = " + to_decimal<T>(h, 6));
      const Vector<T, N> q_minus = context.initial.q;
      const Vector<T, N> q_plus = context.exact(T(2 * h)).q;
      auto one = tq_critical_pair(context.system, first_past, first_future, q_minus, q_plus, h);
      require_converged(one.report, "first critical pair at h = " + to_decimal<T>(h, 17));
      auto two = tq_critical_pair(context.system, second, second, q_minus, q_plus, h);
      require_converged(two.report, "second critical pair at h = " + to_decimal<T>(h, 17));
      Vector<T, N> dw = two.v.w - one.v.w, dw_next = two.v_next.w - one.v_next.w;
      difference.push_back(nan_max(max_norm<T, N>(dw), max_norm<T, N>(dw_next)));
      asymmetry.push_back(max_norm<T, N>(Vector<T, N>(dw - dw_next)));
      rows.push_back({{"h", to_decimal<T>(h)},
                      {"delta_w", to_decimal<T>(max_norm<T, N>(dw))},
                      {"delta_w_next", to_decimal<T>(max_norm<T, N>(dw_next))},
                      {"delta_q", to_decimal<T>(max_norm<T, N>(Vector<T, N>(two.v.q - one.v.q)))},
                      {"delta_q_next", to_decimal<T>(max_norm<T, N>(Vector<T, N>(two.v_next.q - one.v_next.q)))}});
    }
    claim.evidence["contact_order_r"] = r;
    claim.evidence["mismatched_first_pair"] = context.tq_past.has_value();
    claim.evidence["per_step"] = rows;
    // The symmetric residual is the claim's main measurement; the graph difference beside it.
    claim.series.push_back(sweep_series(context, "|Δw − Δw̃| (symmetric residual)", asymmetry,
                                        OrderPrediction{order.order + 1, order.exact},
                                        context.floors_without_reference()));
    claim.series.push_back(sweep_series(context, "max(|Δw|, |Δw̃|)", difference, order,
                                        context.floors_without_reference()));
    conclude(claim);
  }
};

}  // namespace vivv
