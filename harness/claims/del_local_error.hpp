// One DEL step from exact data, the Q×Q counterpart of local-order that global-order includes
// (docs/claims.md, global-order). From q(t), q(t + h) of the reference orbit the DEL
//   p_begin[L_d](q(t + h), q_2) = p_end[L~_d](q(t), q(t + h))
// gives q_2, compared with q(t + 2h). For an order-r discrete Lagrangian the DEL's residual at
// exact data is O(h^(r+1)) — the errors of its two discrete Legendre transforms, each O(h^r),
// share their leading coefficient, which cancels (paper §2.3) — and ∂p_begin/∂q_e ~ M/h turns it
// into |q_2 − q(t + 2h)| = O(h^(r+2)): the two-step recurrence's local error, which the N ~ 1/h
// steps of a run turn into the global O(h^r). Unlike the DEL's map on (q, p), it does not see a
// term the DEL cancels (weights 0.45/0.55 on L = ½w² − V add a difference f(q_b) − f(q_e) that
// telescopes: the momenta are off at O(h), the trajectory is not).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/claims/claim.hpp"
#include "harness/claims/map_local_order.hpp"

namespace vivv {

// The local error of one DEL step at states x(j·T/states) of the reference orbit, j = 0 …
// states − 1, as one series per state over the case's steps and halvings below its finest until
// the error reaches the floor (at most `extra_halvings`), judged against order >= `order`. For an L
// that depends on time each step is at its state's own time: the DEL at q(t + h) joins the segments
// from t and t + h, and q(t + h), q(t + 2h) are the orbit's (CaseContext::exact_after).
template <LagrangianSystem System>
std::vector<Series> del_local_error_series(const CaseContext<System>& context, int order, int states = 4,
                                           int extra_halvings = 80) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  using std::isfinite;
  std::vector<T> steps = context.steps();
  for (int k = 0; k < extra_halvings; ++k) steps.push_back(steps.back() / 2);
  std::vector<Series> all;
  for (int j = 0; j < states; ++j) {
    const T t = context.final_time * T(j) / T(states);
    const State<T, N> x = j == 0 ? context.initial : context.reference.advance(context.initial, t);
    T scale = max_norm<T, N>(x.q);
    std::vector<T> error, used_h;
    // local-order's floor: the rounding of a step that divides by h, and the reference's.
    const auto floor_at = [&](const T& h) { return MapLocalOrderClaim::floor_at(context, scale, h); };
    for (const T& h : steps) {
      context.report("global-order: one DEL step from x(" + format_scalar(t, 4) + ") at h = " + to_decimal<T>(h, 6));
      const Vector<T, N> q1 = context.exact_after(x, t, h).q, q2 = context.exact_after(x, t, T(2 * h)).q;
      // del_step takes the system at q1's time: its future segment starts there, its past one h before.
      const auto [q_next, report] = depends_on_time(context.system)
                                        ? del_step(context.at(T(t + h)), context.scheme, x.q, q1, h)
                                        : del_step(context.system, context.scheme, x.q, q1, h);
      // A step too large for Newton from this state (h = 2 on an elastic pendulum) starts the
      // series at a smaller h; one that fails below a converged one ends it.
      if (!report.converged) {
        if (error.empty()) continue;
        break;
      }
      const T e = max_norm<T, N>(Vector<T, N>(q_next - q2));
      if (!isfinite(e)) throw std::domain_error("one DEL step at h = " + format_scalar(h, 6) + " is not finite");
      scale = nan_max(scale, max_norm<T, N>(Vector<T, N>(q2 - x.q)));
      error.push_back(e);
      used_h.push_back(h);
      if (used_h.size() > context.steps().size() && e <= floor_at(h).value()) break;
    }
    if (error.empty())
      throw std::domain_error("no DEL step from x(" + format_scalar(t, 4) + ") converged at any h of the grid");
    all.push_back(make_series("|q_2 − q(t + 2h)| of one DEL step from x(" + format_scalar(t, 4) + ")", used_h, error,
                              floor_at(used_h.back()), std::optional<double>(order), false, context.order_tolerance,
                              context.fit_options));
  }
  return all;
}

}  // namespace vivv
