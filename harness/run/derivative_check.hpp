// A cross-check of vivv's own derivatives from values of L and L_d alone (issue 25). The
// reference flow and the DEL both take L's derivatives from the same jets and tapes, so a fault
// in a derivative rule moves both together and no claim sees it (a wrong Schur-complement sign in
// the Galerkin derivatives was once caught only as a solver failure). Here, by central
// differences, with no jet and no tape:
//   Euler–Lagrange  from t = 0 and t = T over τ = the sweep's finest h, in integral form
//                   p(t + τ) − p(t) = ∫ ∂L/∂q dt along the reference flow: ∂L/∂w and ∂L/∂q by
//                   differences of L values, the integral by Gauss–Legendre (8 and 16 nodes) on
//                   the flow's states;
//                   (for an L that depends on time, from t0 alone, L at each state's own time);
//   DEL             at q_1 of one DEL step from the case's start, at the coarsest and the finest
//                   h: ∂/∂q_1 [L_d^past(q_0, q_1) + L_d^future(q_1, q_2)] by differences of L_d.
// Each residual is judged against its own terms' size: it may reach √u of it (u the larger of
// the unit roundoff and the reference's tolerance: far above what differences leave, far below
// the O(1) a wrong derivative rule makes) plus 100 × what halving the increment changes, plus
// what the rounding of the values differenced leaves: a central difference of f over ±δ carries
// up to ε·max|f|/δ of f's rounding, and L's values are allowed rounding_ulps ulps of their size.
// L = v²/2 − x⁵⁰ at x = 0.5 in double has ∂L/∂x ≈ 9e-14 beside values of 0.1: the rounding of
// those values alone (4e-12 a difference) once made this check blame vivv's derivatives.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <tuple>

#include "core/numerics/quadrature.hpp"
#include "harness/claims/global_order.hpp"

namespace vivv {

// The ulps of rounding a value of L or L_d may carry, each a few operations' worth.
inline constexpr int rounding_ulps = 64;

// A residual and what it may reach.
template <class T>
struct DifferenceResidual {
  T residual = 0, allowed = 0, scale = 0;
  T rounding = 0;  // what the rounding of the values differenced may leave in the residual
  bool holds() const { return residual <= allowed; }
};

template <class T>
bool finite(const DifferenceResidual<T>& r) {
  using std::isfinite;
  return isfinite(r.residual) && isfinite(r.allowed) && isfinite(r.scale);
}

// ∇f at x by central differences with increments δ_i.
template <class T, int N>
Vector<T, N> central_gradient(const std::function<T(const Vector<T, N>&)>& f, const Vector<T, N>& x,
                              const Vector<T, N>& delta) {
  const int n = static_cast<int>(x.size());
  Vector<T, N> gradient(n);
  for (int i = 0; i < n; ++i) {
    Vector<T, N> up = x, down = x;
    up[i] += delta[i];
    down[i] -= delta[i];
    gradient[i] = (f(up) - f(down)) / (2 * delta[i]);
  }
  return gradient;
}

// Increments for differences of a function of x at the scale `size` of its variation:
// ε^(1/3)·size, the balance of truncation (δ²) and rounding (ε/δ).
template <class T, int N>
Vector<T, N> difference_steps(const T& size, int n) {
  using std::cbrt;
  Vector<T, N> delta(n);
  for (int i = 0; i < n; ++i) delta[i] = cbrt(epsilon<T>()) * size;
  return delta;
}

// The Euler–Lagrange equation in integral form along a flow, L by values only:
//   p(t + τ) − p(t) − ∫_t^{t+τ} ∂L/∂q dt,   p = ∂L/∂w,
// ∂L/∂w and ∂L/∂q by central differences, the integral by Gauss–Legendre on the flow's states
// at the nodes t + c_j τ (`nodes`, with `weights` summing to 1). An integral, not a difference
// quotient in time: the differences' error is not divided by τ.
template <LagrangianSystem System>
DifferenceResidual<typename System::Scalar> euler_lagrange_residual(
    const System& system, const State<typename System::Scalar, System::dimension>& begin,
    const State<typename System::Scalar, System::dimension>& end,
    const std::vector<State<typename System::Scalar, System::dimension>>& nodes,
    const std::vector<typename System::Scalar>& weights, const std::vector<typename System::Scalar>& fractions,
    const typename System::Scalar& tau, const typename System::Scalar& u) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  using std::abs;
  using std::max;
  using std::sqrt;
  // L at the state s after `begin` (begin is at the system's time; node j at fractions[j]·τ).
  const T t = system_time(system);
  const auto value = [&](const T& s, const Vector<T, N>& q, const Vector<T, N>& w) {
    return T(lagrangian_at(system, T(t + s), as_point<T, N>(q), as_point<T, N>(w)));
  };
  const int n = static_cast<int>(begin.q.size());
  T value_size = 0;  // max |L| over the states differenced about
  value_size = max(T(abs(value(T(0), begin.q, begin.w))), T(abs(value(tau, end.q, end.w))));
  for (std::size_t j = 0; j < nodes.size(); ++j)
    value_size = max(value_size, T(abs(value(T(fractions[j] * tau), nodes[j].q, nodes[j].w))));
  T q_size = 0, w_size = 0;
  for (int i = 0; i < n; ++i)
    q_size = max(q_size, T(abs(begin.q[i]))), w_size = max(w_size, T(abs(begin.w[i])));
  if (!(q_size > 0)) q_size = 1;
  if (!(w_size > 0)) w_size = 1;
  const auto residual_with = [&](const T& shrink) {
    // The increments only set the differences' accuracy, which halving them measures.
    const Vector<T, N> dq = difference_steps<T, N>(T(q_size / shrink), n);
    const Vector<T, N> dw = difference_steps<T, N>(T(w_size / shrink), n);
    const auto momentum = [&](const T& s, const State<T, N>& x) {
      return central_gradient<T, N>([&](const Vector<T, N>& w) { return value(s, x.q, w); }, x.w, dw);
    };
    const Vector<T, N> change = momentum(tau, end) - momentum(T(0), begin);
    Vector<T, N> impulse = zero_vector<T, N>(n);
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const T s = fractions[j] * tau;
      impulse += (weights[j] * tau) *
                 central_gradient<T, N>([&](const Vector<T, N>& q) { return value(s, q, nodes[j].w); },
                                        nodes[j].q, dq);
    }
    DifferenceResidual<T> r;
    for (int i = 0; i < n; ++i) {
      r.residual = max(r.residual, T(abs(T(change[i] - impulse[i]))));
      r.scale = max({r.scale, T(abs(change[i])), T(abs(impulse[i]))});
    }
    // Two differences in w, and Σ weights·τ = τ of differences in q.
    r.rounding = rounding_ulps * epsilon<T>() * value_size * (2 / dw[0] + tau / dq[0]);
    return r;
  };
  DifferenceResidual<T> coarse = residual_with(T(1)), fine = residual_with(T(2));
  fine.allowed = sqrt(u) * fine.scale + 100 * abs(T(fine.residual - coarse.residual)) + fine.rounding;
  return fine;
}

// The Euler–Lagrange residual over [t, t + τ] of the flow `advance` (advance(s) is the state at
// t + s, t the system's time), with the integral by 8 and by 16 Gauss–Legendre nodes: the residual is the 16-node one,
// and what the two differ by (the quadrature's own error, not L's) is allowed ten times over.
template <LagrangianSystem System, class Advance>
DifferenceResidual<typename System::Scalar> euler_lagrange_check(const System& system,
                                                                 Advance&& advance,
                                                                 const typename System::Scalar& tau,
                                                                 const typename System::Scalar& u) {
  using T = typename System::Scalar;
  using std::abs;
  const State<T, System::dimension> begin = advance(T(0)), end = advance(tau);
  const auto with_nodes = [&](int m) {
    const GaussLegendreRule<T> rule = gauss_legendre<T>(m);
    std::vector<State<T, System::dimension>> nodes;
    for (const T& c : rule.nodes) nodes.push_back(advance(T(c * tau)));
    return euler_lagrange_residual(system, begin, end, nodes, rule.weights, rule.nodes, tau, u);
  };
  const DifferenceResidual<T> coarse = with_nodes(8);
  DifferenceResidual<T> fine = with_nodes(16);
  fine.allowed += 10 * abs(T(coarse.residual - fine.residual));
  return fine;
}

// ∂/∂q_1 [L_d^past(q_0, q_1) + L_d^future(q_1, q_2)] by differences of L_d values; `past_system`
// is at q_0's time (for an L that depends on time, the future segment starts h later).
template <LagrangianSystem System>
DifferenceResidual<typename System::Scalar> del_residual(
    const System& past_system, const DelScheme<typename System::Scalar>& scheme,
    const VectorOf<System>& q0, const VectorOf<System>& q1, const VectorOf<System>& q2,
    const typename System::Scalar& h) {
  const System& system = past_system;
  const System future_system = at_time(past_system, typename System::Scalar(system_time(past_system) + h));
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  using std::abs;
  using std::max;
  using std::sqrt;
  const int n = static_cast<int>(q1.size());
  T motion = 0, size = 0;
  for (int i = 0; i < n; ++i)
    motion = max({motion, T(abs(T(q1[i] - q0[i]))), T(abs(T(q2[i] - q1[i])))}), size = max(size, T(abs(q1[i])));
  if (!(motion > 0)) motion = size;
  if (!(motion > 0)) motion = 1;
  if (!(size > motion)) size = motion;
  // max |L_d| of the two steps differenced about q_1.
  const T value_size =
      max(T(abs(T(discrete_lagrangian(system, scheme.past, as_point<T, N>(q0), as_point<T, N>(q1), h)))),
          T(abs(T(discrete_lagrangian(future_system, scheme.future, as_point<T, N>(q1), as_point<T, N>(q2), h)))));
  const auto residual_with = [&](const T& scale, const T& shrink) {
    const Vector<T, N> delta = difference_steps<T, N>(T(scale / shrink), n);
    const Vector<T, N> past = central_gradient<T, N>(
        [&](const Vector<T, N>& q) {
          return T(
              discrete_lagrangian(system, scheme.past, as_point<T, N>(q0), as_point<T, N>(q), h));
        },
        q1, delta);
    const Vector<T, N> future = central_gradient<T, N>(
        [&](const Vector<T, N>& q) {
          return T(
              discrete_lagrangian(future_system, scheme.future, as_point<T, N>(q), as_point<T, N>(q2), h));
        },
        q1, delta);
    DifferenceResidual<T> r;
    for (int i = 0; i < n; ++i) {
      r.residual = max(r.residual, T(abs(T(past[i] + future[i]))));
      r.scale = max({r.scale, T(abs(past[i])), T(abs(future[i]))});
    }
    r.rounding = rounding_ulps * epsilon<T>() * value_size * 2 / delta[0];  // two differences
    return r;
  };
  const auto judged_at = [&](const T& scale) {
    DifferenceResidual<T> coarse = residual_with(scale, T(1)), fine = residual_with(scale, T(2));
    fine.allowed =
        sqrt(epsilon<T>()) * fine.scale + 100 * abs(T(fine.residual - coarse.residual)) + fine.rounding;
    return fine;
  };
  // Increments sized by the step's motion, and — where the coordinates are larger — by the
  // coordinates: a step from rest moves q by O(h²), and increments that small divide L_d's
  // rounding by them (the midpoint rule on a double pendulum from rest, in double: 1.9e-9 against
  // an allowed 6.7e-10). A wrong derivative misses at every increment; the residual is blamed on
  // vivv only when both measurements miss, and the one nearer its allowance is reported.
  const DifferenceResidual<T> by_motion = judged_at(motion);
  if (by_motion.holds() || !(size > motion)) return by_motion;
  const DifferenceResidual<T> by_size = judged_at(size);
  if (by_size.holds()) return by_size;
  return by_size.residual / by_size.allowed < by_motion.residual / by_motion.allowed ? by_size : by_motion;
}

// The case's cross-check: the Euler–Lagrange residual of the reference flow at 0 and T and, for a
// Q×Q case, the DEL residual of one step at the coarsest and at the finest h.
template <LagrangianSystem System>
DerivativeCheck derivative_free_check(const CaseContext<System>& context) {
  using T = typename System::Scalar;
  using std::max;
  DerivativeCheck check;
  const T u = max(epsilon<T>(), T(context.reference.tolerance()));
  const std::vector<T> steps = context.steps();
  // Over the sweep's finest step: short enough that Gauss–Legendre resolves the motion, long
  // enough that the change of p stands far above the differences' error.
  const T tau = steps.back();
  DifferenceResidual<T> worst_el;
  bool measured_el = false;
  for (const State<T, System::dimension>* at : {&context.initial, &context.final_state}) {
    // The reference flow of an L that depends on time starts at t0 only.
    if (at == &context.final_state && depends_on_time(context.system)) continue;
    const auto residual = euler_lagrange_check(
        context.system,
        [&](const T& s) { return s == 0 ? *at : context.reference.advance(*at, s); }, tau, u);
    // Values of L outside its domain near the state (a speed next to the relativistic limit)
    // leave a difference undefined: no evidence about the derivatives, so no sample.
    if (!finite(residual)) continue;
    if (!measured_el || residual.residual - residual.allowed > worst_el.residual - worst_el.allowed)
      worst_el = residual;
    measured_el = true;
  }
  std::string found;
  if (measured_el) {
    check.euler_lagrange_residual = to_decimal<T>(worst_el.residual, 6);
    check.euler_lagrange_allowed = to_decimal<T>(worst_el.allowed, 6);
    check.holds = worst_el.holds();
    if (!worst_el.holds())
      found =
          "the reference flow's Euler–Lagrange residual p(t + τ) − p(t) − ∫ ∂L/∂q dt, from values "
          "of L, is " +
          format_scalar(worst_el.residual) + " against terms of size " +
          format_scalar(worst_el.scale) + " (allowed " + format_scalar(worst_el.allowed) + ")";
  }
  if (context.spec.discretization.formalism == "qxq") {
    DifferenceResidual<T> worst_del;
    bool measured = false;  // a step that does not converge is left to the claims' own runs
    for (const T& h : {steps.front(), steps.back()}) {
      Vector<T, System::dimension> q0, q1;
      try {
        std::tie(q0, q1) = context.start(context.scheme, h);
      } catch (const SolverError&) {
        continue;
      }
      auto [q2, report] = del_step(context.at_step(h, 1), context.scheme, q0, q1, h);  // q_1 at t0 + h
      if (!report.converged) continue;
      const auto residual = del_residual(context.system, context.scheme, q0, q1, q2, h);
      if (!finite(residual)) continue;
      if (!measured ||
          residual.residual - residual.allowed > worst_del.residual - worst_del.allowed)
        worst_del = residual;
      measured = true;
    }
    if (measured) {
      check.del_residual = to_decimal<T>(worst_del.residual, 6);
      check.del_allowed = to_decimal<T>(worst_del.allowed, 6);
      check.holds = check.holds && worst_del.holds();
    }
    if (measured && !worst_del.holds())
      found += (found.empty() ? "" : "; ") +
               std::string(
                   "the DEL residual D2 L_d(q_0, q_1) + D1 L_d(q_1, q_2) of one step, from values "
                   "of L_d, "
                   "is ") +
               format_scalar(worst_del.residual) + " against terms of size " +
               format_scalar(worst_del.scale) + " (allowed " + format_scalar(worst_del.allowed) +
               ")";
  }
  check.explanation = found;
  return check;
}

}  // namespace vivv
