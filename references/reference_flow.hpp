// The near-exact flow F_t the harness measures every discretization against
// (docs/theory.md): the closed form where one exists (harmonic oscillator,
// pendulum, Kepler), otherwise Gragg–Bulirsch–Stoer extrapolation to a requested
// tolerance. It says which method it used, what accuracy it claims and how
// that claim is backed up.
//
// Accuracy means, for every component y_i of (q, w):
//   |y_i − F_t(start)_i| ≤ tolerance() (1 + |F_t(start)_i|)       (within_tolerance).
#pragma once

#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "cases/systems.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "core/numerics/scalar.hpp"
#include "core/lagrangian/state.hpp"
#include "references/closed_forms.hpp"
#include "references/extrapolation_flow.hpp"
#include "references/taylor_flow.hpp"

namespace vivv {

// The closed-form flow of System, where one is known: a specialization with
//   static State<T, N> advance(const System&, const State<T, N>& start, const T& t);
//   static std::string method();   // what the closed form is, for the report
// makes ReferenceFlow<System> use it, cross-checked against the Taylor flow (estimate_error).
// Without one (the primary template stays undefined) the reference is extrapolation.
template <class System>
struct ClosedFormFlow;

template <class T>
struct ClosedFormFlow<HarmonicOscillator<T>> {
  static State<T, 1> advance(const HarmonicOscillator<T>& system, const State<T, 1>& start,
                             const T& t) {
    return harmonic_oscillator_flow(system, start, t);
  }
  static std::string method() { return "closed form: q0 cos(omega t) + (w0/omega) sin(omega t)"; }
};
template <class T>
struct ClosedFormFlow<Pendulum<T>> {
  static State<T, 1> advance(const Pendulum<T>& system, const State<T, 1>& start, const T& t) {
    return pendulum_flow(system, start, t);
  }
  static std::string method() {
    return "closed form: Jacobi elliptic functions (Boost.Math sn, cn, F)";
  }
};
template <class T>
struct ClosedFormFlow<Kepler<T>> {
  static State<T, 2> advance(const Kepler<T>& system, const State<T, 2>& start, const T& t) {
    return kepler_flow(system, start, t);
  }
  static std::string method() {
    return "closed form: Kepler's equation in difference form (Boost.Math Newton), Lagrange f and "
           "g";
  }
};

// Whether the reference flow of System is a closed form.
template <class System>
inline constexpr bool has_closed_form_v = requires {
  ClosedFormFlow<System>::method();
};

// Accuracy a closed form claims: 256 ε, before amplification by the flow's conditioning ‖DF_t‖.
template <class T>
T closed_form_tolerance() {
  return 256 * epsilon<T>();
}

// The local tolerance of the Taylor flow that checks a closed form: 1000 ε (100 ε is reachable,
// but slowly).
template <class T>
T closed_form_check_floor() {
  return 1000 * epsilon<T>();
}

// How a closed form's claimed accuracy is backed up, for the report.
template <class T>
std::string closed_form_cross_check() {
  return "closed form in " + scalar_name<T>() + " (" + std::to_string(precision_bits<T>()) +
         " bits), accurate to a few ulps times the conditioning of the flow; unit tests "
         "compare it with the same formula at 100 digits and with Gragg–Bulirsch–Stoer "
         "extrapolation; estimate_error(v, t) is its max-norm distance to the Taylor-series flow "
         "(Jorba–Zou steps) at local tolerance " + three_digits(closed_form_check_floor<T>()) + " (1000 ulps)";
}

// Whether |a_i − b_i| ≤ tol (1 + |b_i|) for every component of q and w.
template <class T, int N>
bool within_tolerance(const State<T, N>& a, const State<T, N>& b, const T& tol) {
  using std::abs;
  for (int i = 0; i < static_cast<int>(a.q.size()); ++i) {
    if (!(abs(a.q[i] - b.q[i]) <= tol * (1 + abs(b.q[i])))) return false;
    if (!(abs(a.w[i] - b.w[i]) <= tol * (1 + abs(b.w[i])))) return false;
  }
  return true;
}

template <LagrangianSystem System>
class ReferenceFlow {
 public:
  using T = typename System::Scalar;
  static constexpr int N = System::dimension;
  static constexpr bool closed_form = has_closed_form_v<System>;

  // `tolerance`: the global tolerance of the extrapolation flow, raised to
  // minimum_flow_tolerance if below it (tolerance() and method() say so); a
  // closed form ignores it.
  ReferenceFlow(System system, T tolerance)
      : system_(std::move(system)), requested_tolerance_(std::move(tolerance)) {
    using std::max;
    if (!(requested_tolerance_ > 0)) {
      throw std::invalid_argument("ReferenceFlow: tolerance must be positive, got " +
                                  to_decimal<T>(requested_tolerance_));
    }
    effective_tolerance_ = closed_form ? closed_form_tolerance<T>()
                                       : max(requested_tolerance_, minimum_flow_tolerance<T>());
  }

  const System& system() const { return system_; }

  // F_t(start), the exact flow (t may be negative).
  State<T, N> advance(const State<T, N>& start, const T& t) const {
    if constexpr (closed_form) {
      return ClosedFormFlow<System>::advance(system_, start, t);
    } else {
      return extrapolation_flow(system_, start, t, effective_tolerance_).state;
    }
  }

  // The accuracy claimed: closed_form_tolerance for a closed form, else the (floored) requested
  // one.
  T tolerance() const { return effective_tolerance_; }

  // ‖advance(start, t) − F̃_t(start)‖_max for the independent, tighter F̃ of cross_check().
  T estimate_error(const State<T, N>& start, const T& t) const {
    if constexpr (closed_form) {
      TaylorFlow<System> check(system_, check_local_tolerance());
      check.integrator().on_progress = progress_;
      return state_distance<T, N>(advance(start, t), check.advance(start, t));
    } else {
      ExtrapolationOptions<T> options;
      options.local_tolerance = check_local_tolerance();
      State<T, N> check =
          extrapolation_flow(system_, start, t, effective_tolerance_, options).state;
      return state_distance<T, N>(advance(start, t), check);
    }
  }

  // e.g. "closed form: Jacobi elliptic functions" or "Gragg–Bulirsch–Stoer extrapolation, tol
  // 1e-50".
  std::string method() const {
    if constexpr (closed_form) {
      return ClosedFormFlow<System>::method();
    } else {
      std::string text =
          "Gragg–Bulirsch–Stoer extrapolation, tol " + three_digits(effective_tolerance_);
      if (effective_tolerance_ > requested_tolerance_) {
        text += " (requested " + three_digits(requested_tolerance_) +
                ", below the floor of 10⁸ ulps of " + scalar_name<T>() + ")";
      }
      return text;
    }
  }

  // How tolerance() is backed up.
  std::string cross_check() const {
    if constexpr (closed_form) {
      return closed_form_cross_check<T>();
    } else {
      const std::string check = three_digits(check_local_tolerance());
      const bool floored =
          check_local_tolerance() > tighter(local_tolerance_for(effective_tolerance_));
      return "local error control at tol/1e6 per step; estimate_error(v, t) reruns the "
             "extrapolation at local tolerance " +
             check +
             (floored ? " (1000 ulps, the working-precision floor, rather than tol·1e-10/1e6)"
                      : " (tol·1e-10/1e6)") +
             " and reports the max-norm difference, an estimate of the global error";
    }
  }

  // The global accuracy the check itself promises, by extrapolation_flow's own
  // rule (local tolerance = global / 10⁶). estimate_error() measures the
  // distance of two approximations, so it confirms tolerance() only up to this:
  // a closed form's few ulps rest on the unit tests at higher precision.
  T check_tolerance() const { return check_local_tolerance() * 1000000; }

  // `check_report(reached, target)` after every step of a Taylor cross-check (a closed form
  // itself has no steps to report: `report` is not called).
  void set_progress(std::function<void(const T&, const T&)> /*report*/,
                    std::function<void(const T&, const T&)> check_report = {}) {
    progress_ = std::move(check_report);
  }

  // Smallest local tolerance of the check: 1000 ε (100 ε is reachable, but slowly).
  static T check_floor() { return closed_form_check_floor<T>(); }

  // A closed form is checked against the Taylor flow at every precision. Extrapolation at 1000
  // ulps needs ever more columns, whose rounding it must stay above: at 300 digits its steps
  // shrank until it would have needed 5·10⁷ of them (pendulum, T = 2), and even at 40 digits it
  // took 1.85 s where the Taylor flow took 0.08 s (Kepler, e = 0.5, T = 50), landing 1000 times
  // further from the closed form. The Taylor flow's order grows with the digits instead.

 private:
  static T tighter(const T& tol) {
    using std::pow;
    return tol / pow(T(10), 10);
  }

  // Local tolerance of the independent check: 10⁻¹⁰ times the flow's, at least 1000 ε.
  T check_local_tolerance() const {
    using std::max;
    if constexpr (closed_form) {
      return check_floor();
    } else {
      return max(tighter(local_tolerance_for(effective_tolerance_)), check_floor());
    }
  }

  System system_;
  T requested_tolerance_;
  T effective_tolerance_;
  std::function<void(const T&, const T&)> progress_;
};

}  // namespace vivv
