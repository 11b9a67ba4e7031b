// Claims measured along one exact solution segment [0, h] from the case's
// initial state, for every h of the sweep:
//   lagrangian-order: |L_d(q(0), q(h); h) − L_d^E| = O(h^{r+1})  (Marsden–West Def. 2.3.1)
//   legendre-order:   |p_end(q(0), q(h)) − p(h)| and |p_begin(q(0), q(h)) − p(0)|
//                     are O(h^r) — not the O(h^{r+1}) of Marsden–West Thm 2.3.1 (2) —
//                     with equal leading coefficients: their difference is O(h^{r+1})
//                     (paper §2.3).
#pragma once

#include "harness/case_context.hpp"
#include "harness/series.hpp"
#include "references/gauss_legendre.hpp"

namespace vivv {

struct LagrangianOrderClaim {
  static constexpr const char* id = "lagrangian-order";
  static constexpr const char* source = "Marsden–West Def. 2.3.1; paper §2.2";
  static constexpr const char* prediction =
      "|L_d(q(0), q(h); h) − ∫₀ʰ L(q, q') dt| = O(h^{r+1}) along solutions";

  template <LagrangianSystem System>
  static ClaimResult evaluate(const CaseContext<System>& context) {
    using T = typename System::Scalar;
    constexpr int n = System::dimension;
    ClaimResult claim = claim_result_for(id, source, prediction);
    auto expected = context.expected(id);
    double predicted = expected ? *expected : context.order() + 1;
    // L_d^E(q(0), q(h); h) is the action along the solution itself (DESIGN §1.2),
    // by Gauss–Legendre with enough nodes that its error is below the floor.
    int nodes = context.spec.digits / 2 + 4;
    auto rule = gauss_legendre<T>(nodes);
    std::vector<T> error;
    for (const T& h : context.steps()) {
      context.report("lagrangian-order h = " + to_decimal<T>(h));
      T exact_action = integrate(rule, T(0), h, [&](const T& t) {
        State<T, n> v = context.exact(t);
        Point<T, n> q, w;
        for (int i = 0; i < n; ++i) q[i] = v.q[i], w[i] = v.w[i];
        return context.system.lagrangian(q, w);
      });
      Vector<T, n> q_end = context.exact(h).q;
      Point<T, n> q_b, q_e;
      for (int i = 0; i < n; ++i) q_b[i] = context.initial.q[i], q_e[i] = q_end[i];
      T discrete = discrete_lagrangian(context.system, context.scheme.future, q_b, q_e, h);
      using std::abs;
      error.push_back(abs(discrete - exact_action));
    }
    claim.evidence["quadrature_nodes"] = nodes;
    claim.series.push_back(make_series("|L_d − L_d^E|", context.steps(), error, context.floor(),
                                       predicted, expected.has_value(), context.order_tolerance));
    conclude(claim);
    return claim;
  }
};

struct LegendreOrderClaim {
  static constexpr const char* id = "legendre-order";
  static constexpr const char* source = "Marsden–West Thm 2.3.1 (2) vs paper §2.3";
  static constexpr const char* prediction =
      "p_end(q(0), q(h)) − p(h) and p_begin(q(0), q(h)) − p(0) are O(h^r), not O(h^{r+1}); "
      "their leading coefficients are equal, so their difference is O(h^{r+1})";

  template <LagrangianSystem System>
  static ClaimResult evaluate(const CaseContext<System>& context) {
    using T = typename System::Scalar;
    constexpr int n = System::dimension;
    ClaimResult claim = claim_result_for(id, source, prediction);
    auto expected = context.expected(id);
    double predicted = expected ? *expected : context.order();
    Vector<T, n> p_start = momentum(context.system, context.initial.q, context.initial.w);
    std::vector<T> end_error, begin_error, difference;
    for (const T& h : context.steps()) {
      State<T, n> v = context.exact(h);
      auto legendre =
          discrete_legendre(context.system, context.scheme.future, context.initial.q, v.q, h);
      Vector<T, n> end_residual = legendre.p_end - momentum(context.system, v.q, v.w);
      Vector<T, n> begin_residual = legendre.p_begin - p_start;
      end_error.push_back(max_norm<T, n>(end_residual));
      begin_error.push_back(max_norm<T, n>(begin_residual));
      difference.push_back(max_norm<T, n>(end_residual - begin_residual));
    }
    // The order is exact: observing r + 1 would confirm Marsden–West and refute the paper.
    claim.series.push_back(make_series("|p_end(q(0), q(h)) − p(h)|", context.steps(), end_error,
                                       context.floor(), predicted, true, context.order_tolerance));
    claim.series.push_back(make_series("|p_begin(q(0), q(h)) − p(0)|", context.steps(),
                                       begin_error, context.floor(), predicted, true,
                                       context.order_tolerance));
    claim.series.push_back(make_series("|(p_end − p(h)) − (p_begin − p(0))|", context.steps(),
                                       difference, context.floor(), predicted + 1, false,
                                       context.order_tolerance));
    conclude(claim);
    return claim;
  }
};

}  // namespace vivv
