// The local error of a Q×Q discrete Lagrangian along a solution, as a power
// series in h computed from the solution's Taylor expansion:
//
//   E(h) = L_d(q(0), q(h); h) − ∫₀ʰ L(q(t), q'(t)) dt = Σ_k E_k h^k,
//
// q(t) = Σ q_k t^k the Taylor series of the Euler–Lagrange solution through
// (q0, w0) (Taylor-mode AD of the system's L, core/lagrangian/taylor_curve.hpp). Each rule
// is written here again from its formula (docs/case-files.md), in truncated
// power series, independently of core/qxq/discrete_lagrangian.hpp: the leading
// coefficient E_{r+1} is a *signed* prediction that lagrangian-order compares
// with the measured L_d − L_d^E, so a swapped weight (β ↔ 1 − β) or a swapped
// interval, which keep every order, is seen.
//
// For an L that depends on t the segment starts at the system's time t_b: the solution is that of
// (q, t) with t'' = 0 (time_extended_euler_lagrange_tape), the action integrates L at t_b + τ, and
// each rule's point f is at t_b + f·h — the time itself a power series t_b + h·f.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/qxq/discrete_lagrangian.hpp"
#include "core/lagrangian/euler_lagrange_tape.hpp"
#include "core/autodiff/power_series.hpp"
#include "core/lagrangian/taylor_curve.hpp"
#include "references/taylor_flow.hpp"

namespace vivv {

// The first `terms` coefficients of discrete − action, and with `sizes` max(|discrete_k|,
// |action_k|) for each.
template <class T>
std::vector<T> difference_coefficients(const PowerSeries<T>& discrete, const PowerSeries<T>& action,
                                       int terms, std::vector<T>* sizes) {
  using std::abs, std::max;
  std::vector<T> out(terms);
  if (sizes) sizes->assign(terms, T(0));
  for (int k = 0; k < terms; ++k) {
    out[k] = discrete.coefficient(k) - action.coefficient(k);
    if (sizes) (*sizes)[k] = max(abs(discrete.coefficient(k)), abs(action.coefficient(k)));
  }
  return out;
}

// L(q, w) in power series at the time t (a power series too): an autonomous system's L at any t.
template <LagrangianSystem System, class P>
P lagrangian_series_at(const System& system, const P& t, const Coordinates<P, System::dimension>& q,
                       const Coordinates<P, System::dimension>& w) {
  if constexpr (CarriesTime<System>) {
    if (system.timed) return P(system.lagrangian_at(t, q, w));
  }
  return P(system.lagrangian(q, w));
}

// t_b + f·h as a power series in h, of `length` coefficients (t_b the system's time).
template <LagrangianSystem System>
PowerSeries<typename System::Scalar> time_series(const System& system, const typename System::Scalar& fraction,
                                                 int length) {
  PowerSeries<typename System::Scalar> t(system_time(system), length);
  if (length > 1) t[1] = fraction;
  return t;
}

// q(h) = Σ_k q_k h^k, its first `length` coefficients, of the Euler–Lagrange solution through
// (q0, w0) (Taylor-mode AD of the system's L, core/lagrangian/taylor_curve.hpp); for an L that
// depends on t, of (q, t) through (q0, t_b) with t' = 1, the time dropped.
template <LagrangianSystem System>
Coordinates<PowerSeries<typename System::Scalar>, System::dimension> solution_series(
    const System& system, const VectorOf<System>& q0, const VectorOf<System>& w0, int length) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q0.size());
  const bool timed = depends_on_time(system);
  const Tape<T> tape = flow_tape(system);  // of (q, t) for an L that depends on t
  std::vector<T> x0(n + (timed ? 1 : 0)), v0(n + (timed ? 1 : 0));
  for (int i = 0; i < n; ++i) x0[i] = q0[i], v0[i] = w0[i];
  if (timed) x0[n] = system_time(system), v0[n] = 1;
  const auto solution = solution_taylor_coefficients<T, T>(tape, x0, v0, length);
  Coordinates<PowerSeries<T>, N> q = make_point<PowerSeries<T>, N>(n);
  for (int i = 0; i < n; ++i)
    q[i] = PowerSeries<T>::from(std::vector<T>(solution[i].begin(), solution[i].begin() + length));
  return q;
}

// E_0 … E_{terms−1} of E(h) for a discretization written as a formula (or registered C++),
// whose only statement is its tape: the tape run in h-series, q_b = q(0), q_e = q(h) and h = h.
// Its divisions by h leave the top coefficients unknown (KnownSeries), so the series is
// computed longer than asked and lengthened until `terms` are known. This does not state the
// rule a second time: it checks the measured coefficient (shooting, quadrature, the tape run in
// T) against the same formula expanded exactly, so one rule gets one verdict whichever way it
// is written. Throws std::domain_error where the formula has no expansion at this state.
// With `sizes`, also the size of the two sides of each coefficient, max(|L_d's|, |the action's|):
// the terms that cancel in E_k, from which its rounding unit comes (add_exact_coefficients,
// harness/claims/local_consistency.hpp).
template <LagrangianSystem System>
std::vector<typename System::Scalar> expression_error_expansion(
    const System& system, const QxQDiscretization<typename System::Scalar>& d,
    const VectorOf<System>& q0, const VectorOf<System>& w0, int terms,
    std::vector<typename System::Scalar>* sizes = nullptr) {
  using T = typename System::Scalar;
  using P = PowerSeries<T>;
  using K = KnownSeries<T>;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q0.size());
  for (int length = terms + 4; length <= 4 * terms + 16; length *= 2) {
    const Coordinates<P, N> q = solution_series(system, q0, w0, length);
    // Its inputs (q_b, q_e, h) and, for an L that depends on time, t_b (a constant).
    Coordinates<K, plus(twice(N), 2)> x = make_point<K, plus(twice(N), 2)>(d.expression->inputs);
    Coordinates<P, N> w = make_point<P, N>(n);
    for (int i = 0; i < n; ++i) {
      w[i] = q[i].derivative();
      x[i] = K(P(q0[i], length), length);
      x[n + i] = K(q[i], length);
    }
    P step(T(0), length);
    step[1] = 1;
    x[2 * n] = K(step, length);
    if (d.expression->inputs == 2 * n + 2) x[2 * n + 1] = K(P(system_time(system), length), length);
    const K discrete = d.expression->evaluate_first(x.data());
    if (discrete.known < terms) continue;
    const P along = lagrangian_series_at(system, time_series(system, T(1), length), q, w);
    P action(T(0), length);
    for (int k = 1; k < length; ++k) action[k] = along[k - 1] / k;
    P sum = discrete.series;
    if (d.twin)  // + a·h^s·(q(h) − q(0))
      for (int i = 0; i < n; ++i)
        sum = sum + (d.twin->a[i] * (q[i] - P(q0[i], length))).shifted(d.twin->power);
    return difference_coefficients(sum, action, terms, sizes);
  }
  throw std::domain_error("the formula's divisions by h leave fewer than " + std::to_string(terms) +
                          " coefficients of its expansion known");
}

// E_0 … E_{terms−1} of E(h) for the discretization `d` along the solution through (q0, w0);
// with `sizes`, the size of each coefficient's two sides as in expression_error_expansion.
template <LagrangianSystem System>
std::vector<typename System::Scalar> lagrangian_error_expansion(
    const System& system, const QxQDiscretization<typename System::Scalar>& d,
    const VectorOf<System>& q0, const VectorOf<System>& w0, int terms,
    std::vector<typename System::Scalar>* sizes = nullptr) {
  using T = typename System::Scalar;
  using P = PowerSeries<T>;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q0.size());
  // q(h), q'(h), the constant q(0), and the difference quotient (q(h) − q(0))/h.
  const Coordinates<P, N> q = solution_series(system, q0, w0, terms);
  Coordinates<P, N> w = make_point<P, N>(n), q_begin = w, quotient = w;
  for (int i = 0; i < n; ++i) {
    w[i] = q[i].derivative();
    q_begin[i] = P(q0[i], terms);
    quotient[i] = (q[i] - q_begin[i]).shifted(-1);
  }
  // ∫₀ʰ L dt: the series of L along the solution, integrated term by term.
  const P along = lagrangian_series_at(system, time_series(system, T(1), terms), q, w);
  P action(T(0), terms);
  for (int k = 1; k < terms; ++k) action[k] = along[k - 1] / k;
  // L_d, rule by rule from its formula; L at the segment's point f is at t_b + f·h.
  const auto at = [&](const T& fraction, const Coordinates<P, N>& point) {
    return lagrangian_series_at(system, time_series(system, fraction, terms), point, quotient);
  };
  auto on_segment = [&](const T& fraction) {
    Coordinates<P, N> point = make_point<P, N>(n);
    for (int i = 0; i < n; ++i) point[i] = (1 - fraction) * q_begin[i] + fraction * q[i];
    return at(fraction, point);
  };
  const T& c = d.parameter;
  P per_step;  // L_d / h
  switch (d.rule) {
    case QxQRule::left_rectangle: per_step = at(T(0), q_begin); break;
    case QxQRule::right_rectangle: per_step = at(T(1), q); break;
    case QxQRule::midpoint: per_step = on_segment(T(1) / 2); break;
    case QxQRule::alpha: per_step = on_segment(c); break;
    case QxQRule::trapezoid:
      per_step = (at(T(0), q_begin) + at(T(1), q)) / 2;
      break;
    case QxQRule::weighted:
      per_step = (1 - c) * at(T(0), q_begin) + c * at(T(1), q);
      break;
    case QxQRule::expression:
      return expression_error_expansion(system, d, q0, w0, terms, sizes);
    case QxQRule::galerkin:  // extremized by Newton: no closed expression to expand
      throw std::invalid_argument("lagrangian_error_expansion: no independent expansion of a Galerkin L_d");
  }
  P discrete = per_step.shifted(1);
  if (d.twin)  // + a·h^s·(q(h) − q(0))
    for (int i = 0; i < n; ++i) discrete = discrete + (d.twin->a[i] * (q[i] - q_begin[i])).shifted(d.twin->power);
  return difference_coefficients(discrete, action, terms, sizes);
}

}  // namespace vivv
