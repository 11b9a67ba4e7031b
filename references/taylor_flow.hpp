// The Taylor-series integrator: near-exact flows of any catalogue Lagrangian (issue 3).
//
// The Euler–Lagrange equations q'' = a(q, q') (core/lagrangian/euler_lagrange_tape.hpp)
// are advanced by Taylor polynomials of order p whose coefficients come from
// Taylor-mode automatic differentiation (core/autodiff/taylor_expansion.hpp). Order and
// step follow Jorba & Zou (2005, §3.2–3.3), as heyoka does: for a tolerance tol,
//   p = ⌈−ln(tol)/2 + 1⌉,
//   ρ = min( (s/‖y_{p−1}‖)^{1/(p−1)}, (s/‖y_p‖)^{1/p} ),   h = ρ e^{−2} e^{−0.7/(p−1)},
// with ‖·‖ the max norm over the components of y = (q, w) and s = max(1, ‖y_0‖)
// (absolute error control for states of norm at most 1, relative above). The
// local error of a step is then about tol·s. The last step is shortened to end
// exactly at the requested time; negative times run backward (h < 0).
//
// TaylorIntegrator works on any tape x'' = a(x, x') (the variational flow uses
// it too); TaylorFlow is the facade for a LagrangianSystem. Dense output: a
// TaylorTrajectory keeps the polynomial of every step, and advance_many
// evaluates one trajectory at many times in one pass. Reports count steps,
// order and multiply-adds. Errors (non-finite coefficients, too many steps) throw.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/lagrangian/euler_lagrange_tape.hpp"
#include "core/numerics/scalar.hpp"
#include "core/lagrangian/state.hpp"
#include "core/autodiff/taylor_expansion.hpp"
#include "references/taylor_trajectory.hpp"

namespace vivv {

// What a Taylor integrator did (cumulative).
struct TaylorReport {
  long steps = 0;                // steps taken (each one expansion of order `order`)
  int order = 0;                 // p
  long long multiply_adds = 0;   // in the Taylor recurrences
  int tape_operations = 0;       // nodes of the acceleration's tape, inputs and constants excluded
};

template <class T>
class TaylorIntegrator {
 public:
  // The integrator of x'' = a(x, x') recorded on `tape`, at step tolerance `tolerance`, of order
  // `order` (0: Jorba–Zou's for the tolerance, taylor_order_for).
  TaylorIntegrator(Tape<T> tape, T tolerance, int order = 0)
      : expansion_(std::move(tape)),
        tolerance_(std::move(tolerance)),
        order_(order > 0 ? order : taylor_order_for(tolerance_)) {
    report_.order = order_;
    report_.tape_operations = expansion_.tape().operations();
  }

  int order() const { return order_; }
  const T& tolerance() const { return tolerance_; }
  // m, the dimension of x; y = (x, v) has 2m components.
  int dimension() const { return expansion_.dimension(); }
  TaylorReport report() const {
    TaylorReport r = report_;
    r.multiply_adds = expansion_.multiply_adds();
    return r;
  }
  // Test-only access to the recurrences (TaylorExpansion::fault_order).
  TaylorExpansion<T>& expansion() { return expansion_; }

  // One step from y at time t, direction ±1, of length min(Jorba–Zou, |limit|); with clip false,
  // |limit| only replaces an unbounded Jorba–Zou step (all of the last coefficients zero).
  TaylorStep<T> step(const std::vector<T>& y, const T& t, int direction, const T& limit,
                     bool clip = true);

  // F_t(y) with an exact end time t (of either sign).
  std::vector<T> advance(std::vector<T> y, const T& t);

  // Appends steps (full Jorba–Zou steps, never shortened) until the trajectory covers t_end.
  void extend(TaylorTrajectory<T>& trajectory, const T& t_end);

  // A coordinate that is the time itself (t'' = 0, t' = 1: an L that depends on t), or −1: left out
  // of the norms that choose the step, where its size would loosen the other coordinates' control.
  int clock = -1;
  // Steps one advance or extend may take; a pace that would need more ends the run after a
  // thousand steps (the message says how many it would take). A dense trajectory keeps every
  // step's polynomial: a million steps of order 60 in 2 coordinates are gigabytes in MPFR.
  long max_steps = 1000000;
  // Called after every step of advance and extend with the time reached and the target (the
  // harness throttles it into progress lines); empty: nothing is called.
  std::function<void(const T& reached, const T& target)> on_progress;

 private:
  // ρ e^{−2} e^{−0.7/(p−1)} from the current expansion; +∞ when the last two orders vanish.
  // `at`: the time of the expansion, for the message when the step underflows.
  T jorba_zou_step(const T& at) const;

  // Throws when the `steps` steps taken from `from` reached `now` on the way to `target` at a
  // pace that would need more than max_steps (checked from the thousandth step on).
  void check_pace(long steps, const T& from, const T& now, const T& target) const;

  // result = Σ_{k=0..p} coefficient(k) τ^k by Horner, in place.
  template <class Coefficient>
  void horner(T& result, Coefficient coefficient, const T& tau) const {
    result = coefficient(order_);
    for (int k = order_ - 1; k >= 0; --k) {
      taylor_detail::set_mul(result, result, tau);
      taylor_detail::set_add(result, result, coefficient(k));
    }
  }

  TaylorExpansion<T> expansion_;
  T tolerance_;
  int order_;
  TaylorReport report_;
};

namespace taylor_flow_detail {

// Whether |a| < |b|, without temporaries for MPFR.
template <class T>
bool abs_less(const T& a, const T& b) {
  using std::abs;
  if constexpr (is_mpfr_v<T>) {
    return mpfr_cmpabs(a.backend().data(), b.backend().data()) < 0;
  } else {
    return abs(a) < abs(b);
  }
}

}  // namespace taylor_flow_detail

// ρ is a step-size heuristic, so it is computed from ln-norms in double: its
// few digits cost nothing next to the recurrences (an MPFR pow per step
// would cost as much as the whole expansion at tolerance 1e-40). The step h
// is then a double rounded into T — any step is valid, and end times are
// hit exactly by shortening the last step.
template <class T>
T TaylorIntegrator<T>::jorba_zou_step(const T& at) const {
  using boost::multiprecision::isfinite;
  using std::isfinite;
  using taylor_flow_detail::abs_less;
  const int m = dimension();
  const int p = order_;
  const T zero = 0;
  const T* state_norm = &zero;
  const T* norm_last = &zero;
  const T* norm_previous = &zero;
  for (int i = 0; i < m; ++i) {
    if (i == clock) continue;
    for (int part = 0; part < 2; ++part) {
      const T& y0 = part == 0 ? expansion_.position(i, 0) : expansion_.velocity(i, 0);
      const T& yp = part == 0 ? expansion_.position(i, p) : expansion_.velocity(i, p);
      const T& yq = part == 0 ? expansion_.position(i, p - 1) : expansion_.velocity(i, p - 1);
      if (!isfinite(yp) || !isfinite(yq) || !isfinite(y0)) {
        std::string q, w;
        for (int k = 0; k < m; ++k) {
          q += (k ? ", " : "") + to_decimal<T>(expansion_.position(k, 0), 8);
          w += (k ? ", " : "") + to_decimal<T>(expansion_.velocity(k, 0), 8);
        }
        throw std::runtime_error(
            "the Taylor-series flow's coefficients are not finite at t = " + to_decimal<T>(at, 8) +
            " from q = (" + q + "), w = (" + w +
            "): the state left the Lagrangian's domain (a formula's √ or log of a negative number, "
            "a division by zero) or its mass matrix became singular there");
      }
      if (abs_less(*state_norm, y0)) state_norm = &y0;
      if (abs_less(*norm_last, yp)) norm_last = &yp;
      if (abs_less(*norm_previous, yq)) norm_previous = &yq;
    }
  }
  // ln s with s = max(1, ‖y_0‖): absolute control below norm 1, relative above.
  using taylor_detail::log_abs;
  const double log_scale = abs_less(*state_norm, T(1)) ? 0.0 : log_abs(*state_norm);
  const double step = vivv::jorba_zou_step(log_scale, log_abs(*norm_previous), log_abs(*norm_last), p);
  if (!(step > 0))
    throw std::runtime_error("the Taylor-series flow's step fell to zero at t = " + to_decimal<T>(at, 17) +
                             " (its Taylor coefficients overflow): the solution is probably singular there "
                             "(a collision, a blow-up, or a Lagrangian that stops being regular along it)");
  return T(step);
}

template <class T>
TaylorStep<T> TaylorIntegrator<T>::step(const std::vector<T>& y, const T& t, int direction,
                                        const T& limit, bool clip) {
  using boost::multiprecision::isfinite;
  using std::abs;
  using std::isfinite;
  const int m = dimension();
  if (static_cast<int>(y.size()) != 2 * m)
    throw std::invalid_argument("TaylorIntegrator::step: state of the wrong size");
  ++report_.steps;
  expansion_.expand(y.data(), y.data() + m, order_);
  T length = jorba_zou_step(t);
  if (clip ? !(length < abs(limit)) : !isfinite(length)) length = abs(limit);
  if (!isfinite(length))
    throw std::runtime_error("TaylorIntegrator: unbounded step with no end time to stop at");
  TaylorStep<T> step;
  step.start = t;
  step.length = direction > 0 ? length : T(-length);
  step.order = order_;
  const int stride = order_ + 1;
  step.coefficients.resize(2 * m * stride);
  for (int i = 0; i < m; ++i) {
    for (int k = 0; k <= order_; ++k) {
      step.coefficients[i * stride + k] = expansion_.position(i, k);
      step.coefficients[(m + i) * stride + k] = expansion_.velocity(i, k);
    }
  }
  return step;
}

template <class T>
void TaylorIntegrator<T>::check_pace(long steps, const T& from, const T& now, const T& target) const {
  using std::abs;
  const T covered = abs(T(now - from));
  const bool over_pace = steps >= 1000 && covered != 0 &&
                         static_cast<double>(abs(T(target - from)) / covered) * static_cast<double>(steps) > max_steps;
  if (steps < max_steps && !over_pace) return;
  const std::string projected =
      covered != 0 ? "about " + to_decimal(static_cast<double>(abs(T(target - from)) / covered) * steps, 2)
                   : "more than " + std::to_string(steps);
  throw std::runtime_error("the Taylor-series flow would need " + projected + " steps to reach t = " +
                           to_decimal<T>(target, 6) + " (" + std::to_string(steps) + " steps reached t = " +
                           to_decimal<T>(now, 6) + ", step tolerance " + to_decimal<T>(tolerance_, 3) +
                           "); its limit is " + std::to_string(max_steps) +
                           ": the motion is too fast, or too long, for this T at this precision (take a smaller T)");
}

template <class T>
std::vector<T> TaylorIntegrator<T>::advance(std::vector<T> y, const T& t) {
  using boost::multiprecision::isfinite;
  using std::abs;
  using std::isfinite;
  const int m = dimension();
  if (static_cast<int>(y.size()) != 2 * m)
    throw std::invalid_argument("TaylorIntegrator::advance: state of the wrong size");
  T now = 0, length = 0;
  long taken = 0;
  while (now != t) {
    ++report_.steps;
    check_pace(taken++, T(0), now, t);
    const T remaining = t - now;
    expansion_.expand(y.data(), y.data() + m, order_);
    length = jorba_zou_step(now);
    const bool last = !(length < abs(remaining));
    if (last) length = remaining;
    if (t < 0 && !last) length = -length;
    // y ← Σ_k y_k h^k, in place (Horner).
    for (int i = 0; i < m; ++i) {
      horner(y[i], [&](int k) -> const T& { return expansion_.position(i, k); }, length);
      horner(y[m + i], [&](int k) -> const T& { return expansion_.velocity(i, k); }, length);
    }
    now = last ? t : T(now + length);
    if (on_progress) on_progress(now, t);
  }
  return y;
}

template <class T>
void TaylorIntegrator<T>::extend(TaylorTrajectory<T>& trajectory, const T& t_end) {
  const T from = trajectory.end_time();
  long taken = 0;
  while (!trajectory.covers(t_end)) {
    check_pace(taken++, from, trajectory.end_time(), t_end);
    // Steps are never shortened, so the trajectory from a state does not depend on how far it
    // was asked to go; the remaining span only bounds a step with vanishing coefficients.
    T remaining = t_end - trajectory.end_time();
    TaylorStep<T> taken = step(trajectory.end_state(), trajectory.end_time(),
                               trajectory.direction(), remaining, false);
    std::vector<T> end = TaylorTrajectory<T>::evaluate(taken, taken.length);
    trajectory.append(std::move(taken), std::move(end));
    if (on_progress) on_progress(trajectory.end_time(), t_end);
  }
}

// The tape a Taylor flow integrates: the Euler–Lagrange acceleration a(q, w), or, for an L that
// depends on t, a(t, q, w) over the coordinates (q, t) with t'' = 0
// (core/lagrangian/euler_lagrange_tape.hpp: time_extended_euler_lagrange_tape).
template <TapeRecordable System>
Tape<typename System::Scalar> flow_tape(const System& system) {
  if constexpr (SparselyDifferentiated<System>) {
    if (depends_on_time(system)) return time_extended_euler_lagrange_tape(system);
  }
  return euler_lagrange_tape(system);
}

// The Taylor flow F_t of a Lagrangian system. For an L that depends on t, every trajectory starts
// at the system's time t_0 (core/lagrangian/lagrangian.hpp: at_time) and F_t(start) is the state
// at t_0 + t.
template <TapeRecordable System>
class TaylorFlow {
 public:
  using T = typename System::Scalar;
  static constexpr int N = System::dimension;

  // `tolerance`: the Jorba–Zou step tolerance (local error per step about tolerance·max(1, |y|));
  // `order`: 0 for Jorba–Zou's, or another (the reference's check at the floor of a precision).
  TaylorFlow(const System& system, const T& tolerance, int order = 0)
      : system_(system), integrator_(flow_tape(system), tolerance, order) {
    if (timed()) integrator_.clock = dimension_of(system);
  }

  const System& system() const { return system_; }
  int order() const { return integrator_.order(); }
  const T& tolerance() const { return integrator_.tolerance(); }
  TaylorReport report() const { return integrator_.report(); }
  TaylorIntegrator<T>& integrator() { return integrator_; }

  // F_t(start), ending exactly at t (t may be negative).
  State<T, N> advance(const State<T, N>& start, const T& t) {
    return state_of(integrator_.advance(components(start), t));
  }

  // The dense trajectory from `start` covering [0, t_end] (or [t_end, 0]).
  TaylorTrajectory<T> trajectory(const State<T, N>& start, const T& t_end) {
    TaylorTrajectory<T> result(components(start), t_end >= 0 ? 1 : -1);
    integrator_.extend(result, t_end);
    return result;
  }

  // F_t(start) for every t of `times` (any order, either sign) from one trajectory per direction.
  std::vector<State<T, N>> advance_many(const State<T, N>& start, const std::vector<T>& times) {
    T latest = 0, earliest = 0;
    for (const T& t : times) {
      if (t > latest) latest = t;
      if (t < earliest) earliest = t;
    }
    TaylorTrajectory<T> forward = trajectory(start, latest);
    TaylorTrajectory<T> backward(components(start), -1);
    if (earliest < 0) integrator_.extend(backward, earliest);
    std::vector<State<T, N>> states;
    states.reserve(times.size());
    for (const T& t : times)
      states.push_back(state_of(t >= 0 ? forward.state_at(t) : backward.state_at(t)));
    return states;
  }

  // y = (q, w) as the integrator's components; for an L that depends on t, (q, t_0, w, 1).
  std::vector<T> components(const State<T, N>& v) const {
    const int size = static_cast<int>(v.q.size()), m = size + (timed() ? 1 : 0);
    std::vector<T> y(2 * m);
    for (int i = 0; i < size; ++i) y[i] = v.q[i], y[m + i] = v.w[i];
    if (timed()) y[size] = system_time(system_), y[2 * m - 1] = 1;
    return y;
  }
  // The state of components y (the time dropped).
  State<T, N> state_of(const std::vector<T>& y) const {
    const int m = static_cast<int>(y.size()) / 2, size = m - (timed() ? 1 : 0);
    State<T, N> v{Vector<T, N>(size), Vector<T, N>(size)};
    for (int i = 0; i < size; ++i) v.q[i] = y[i], v.w[i] = y[m + i];
    return v;
  }
  bool timed() const { return depends_on_time(system_); }

 private:
  System system_;
  TaylorIntegrator<T> integrator_;
};

}  // namespace vivv
