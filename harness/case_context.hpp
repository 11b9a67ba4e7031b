// A case made concrete in scalar T for one system: the parsed numbers, the
// schemes, the reference flow and the step sweep every claim measures over.
#pragma once

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/case_file.hpp"
#include "core/del_evolution.hpp"
#include "core/euler_lagrange_tape.hpp"
#include "core/state.hpp"
#include "core/tq_evolution.hpp"
#include "references/gauss_legendre.hpp"
#include "harness/claim_result.hpp"
#include "references/reference_flow.hpp"
#include "references/taylor_reference.hpp"

namespace vivv {

// The Q×Q discretization a case file describes, in scalar T.
template <class T>
QxQDiscretization<T> make_discretization(const DiscretizationSpec& spec) {
  QxQDiscretization<T> d;
  if (spec.formalism != "qxq") {
    if (spec.twin) {  // only the twin term is shared with TQ discretizations
      TwinTerm<T> twin;
      for (const auto& a : spec.twin->a) twin.a.push_back(from_decimal<T>(a));
      twin.power = spec.twin->power;
      d.twin = twin;
    }
    return d;
  }
  d.rule = *rule_from_name(spec.kind);
  if (spec.parameter) d.parameter = from_decimal<T>(*spec.parameter);
  if (spec.twin) {
    TwinTerm<T> twin;
    for (const auto& a : spec.twin->a) twin.a.push_back(from_decimal<T>(a));
    twin.power = spec.twin->power;
    d.twin = twin;
  }
  return d;
}

// A decimal "0.5" or a fraction "1/2", parsed in T.
template <class T>
T from_fraction(const std::string& text) {
  auto slash = text.find('/');
  if (slash == std::string::npos) return from_decimal<T>(text);
  return from_decimal<T>(text.substr(0, slash)) / from_decimal<T>(text.substr(slash + 1));
}

// The TQ discretization a case file describes, in scalar T; an exact psi is
// computed to step tolerance `curve_tolerance`, and the exact action by
// p/2 + 4 Gauss–Legendre nodes on each of its Taylor pieces (p its order, as
// for the exact discrete Lagrangian of references/exact_discrete_lagrangian.hpp).
template <class T>
TQDiscretization<T> make_tq_discretization(const DiscretizationSpec& spec, const T& curve_tolerance) {
  const TQSpec& tq = *spec.tq;
  TQDiscretization<T> d;
  d.psi = tq.psi == "taylor" ? CurveFamily::taylor
          : tq.psi == "exact" ? CurveFamily::exact
                              : CurveFamily::linear;
  d.r = tq.psi == "taylor" ? tq.r : 1;
  d.curve_tolerance = curve_tolerance;
  d.theta = from_fraction<T>(tq.theta);
  if (tq.lagrangian == "quadrature" || tq.lagrangian == "exact") {
    d.lagrangian = tq.lagrangian == "exact" ? TQLagrangianKind::exact : TQLagrangianKind::quadrature;
    auto rule = gauss_legendre<T>(tq.lagrangian == "exact" ? taylor_order_for(curve_tolerance) / 2 + 4
                                                           : tq.nodes);
    d.nodes = rule.nodes;
    d.weights = rule.weights;
  } else {
    d.lagrangian = TQLagrangianKind::pullback;
    d.qxq = make_discretization<T>(*tq.qxq);
  }
  if (spec.twin) d.twin = make_discretization<T>(spec).twin;
  return d;
}

// The TQ discretization a case file describes for `system`: as above, with the
// Euler–Lagrange tape a(q, w) of its L recorded for a taylor psi.
template <LagrangianSystem System>
TQDiscretization<typename System::Scalar> make_tq_discretization(
    const DiscretizationSpec& spec, const System& system, const typename System::Scalar& curve_tolerance) {
  auto d = make_tq_discretization<typename System::Scalar>(spec, curve_tolerance);
  if (d.psi != CurveFamily::linear) {
    if constexpr (TapeRecordable<System>) {
      d.acceleration =
          std::make_shared<const Tape<typename System::Scalar>>(euler_lagrange_tape(system));
    } else {
      throw std::invalid_argument(
          "psi \"" + spec.tq->psi + "\" needs a Lagrangian that can be recorded on a tape; " +
          System::name + "'s cannot");
    }
  }
  return d;
}

// The order of an exact part of a discretization: more than any sweep can measure.
constexpr int unbounded_order = 1000;

// Order r of a TQ discretization: its order of contact with the exact one
// (Definition 5.4), the lower of the curve's and the Lagrangian's. A linear
// psi agrees with the solution to O(t²): r = 1; a taylor-r psi to O(t^{r+1}): r;
// the exact psi and the exact action are unbounded.
template <class T>
int nominal_order(const TQDiscretization<T>& d) {
  int psi_order = d.psi == CurveFamily::taylor ? d.r
                  : d.psi == CurveFamily::exact ? unbounded_order
                                                : 1;
  int lagrangian_order = d.lagrangian == TQLagrangianKind::quadrature ? 2 * static_cast<int>(d.nodes.size())
                         : d.lagrangian == TQLagrangianKind::exact    ? unbounded_order
                                                                      : d.qxq.nominal_order();
  if (d.twin) lagrangian_order = std::min(lagrangian_order, d.twin->power);
  return std::min(psi_order, lagrangian_order);
}

// Reference tolerance for a case computed with `digits` decimal digits: ten
// digits of the working precision are kept as guard.
template <class T>
T reference_tolerance_for(int digits) {
  using std::pow;
  return pow(T(10), -(digits - 10));
}

template <LagrangianSystem System>
struct CaseContext {
  using T = typename System::Scalar;
  static constexpr int n = System::dimension;

  const CaseSpec& spec;
  System system;
  // Closed forms where they exist, the Taylor-series flow otherwise.
  std::conditional_t<has_closed_form_v<System>, ReferenceFlow<System>, TaylorReference<System>> reference;
  State<T, n> initial;
  T final_time;
  DelScheme<T> scheme;                    // formalism "qxq"
  std::optional<TQDiscretization<T>> tq;  // formalism "tq"
  std::optional<TQDiscretization<T>> tq_compare;  // contact-order's second discretization
  std::optional<TQDiscretization<T>> tq_past;     // past-future-symmetry: a mismatched past segment
  double order_tolerance;
  std::function<void(const std::string&)> progress;

  CaseContext(const CaseSpec& spec_, System system_, std::function<void(const std::string&)> progress_)
      : spec(spec_),
        system(system_),
        reference(system_, reference_tolerance_for<T>(spec_.digits)),
        final_time(from_decimal<T>(spec_.final_time)),
        order_tolerance(std::stod(spec_.order_tolerance)),
        progress(std::move(progress_)) {
    for (int i = 0; i < n; ++i) {
      initial.q[i] = from_decimal<T>(spec.q[i]);
      initial.w[i] = from_decimal<T>(spec.w[i]);
    }
    if (spec.discretization.formalism == "tq") {
      // An exact psi runs at the reference's step tolerance.
      T curve_tolerance = reference.tolerance() / 1000;
      tq = make_tq_discretization(spec.discretization, system, curve_tolerance);
      if (spec.compare_discretization)
        tq_compare = make_tq_discretization(*spec.compare_discretization, system, curve_tolerance);
      if (spec.past_discretization)
        tq_past = make_tq_discretization(*spec.past_discretization, system, curve_tolerance);
    }
    scheme.future = make_discretization<T>(spec.discretization);
    scheme.past = spec.past_discretization && !tq_past ? make_discretization<T>(*spec.past_discretization)
                                                       : scheme.future;
    scheme.mismatched = spec.past_discretization.has_value() && !tq_past;
    // The initial state must be inside the Lagrangian's domain and regular
    // there; otherwise this throws SingularLagrangianError naming the state.
    euler_lagrange_acceleration(system, initial.q, initial.w);
  }

  // h = T/N for every N of the sweep.
  std::vector<T> steps() const {
    std::vector<T> h;
    for (int N : spec.steps) h.push_back(final_time / N);
    return h;
  }
  // The order r of the case's discrete Lagrangian(s): the lower of the two sides.
  int order() const {
    if (tq) return nominal_order(*tq);
    return std::min(scheme.future.nominal_order(), scheme.past.nominal_order());
  }

  // Exact order the case declares for `claim`, if any.
  std::optional<int> expected(const std::string& claim) const {
    auto it = spec.expect.find(claim);
    if (it == spec.expect.end()) return std::nullopt;
    return it->second;
  }

  // Errors below this are at the floor: a thousand times the larger of the
  // reference tolerance and N_max rounding errors, relative to the state's size.
  T floor() const {
    using std::max;
    T scale = max(T(1), max(max_norm<T, n>(initial.q), max_norm<T, n>(initial.w)));
    return 1000 * max(reference.tolerance(), T(spec.steps.back()) * epsilon<T>()) * scale;
  }

  // Reference state F_t(initial).
  State<T, n> exact(const T& t) const { return reference.advance(initial, t); }

  // q_0, q_1 for N steps: q_1 from the reference flow (isolating the
  // method's own error) or from p_begin(q_0, q_1) = p(0).
  std::pair<Vector<T, n>, Vector<T, n>> start(const DelScheme<T>& with, const T& h) const {
    if (spec.start == "momentum")
      return {initial.q, start_from_momentum(system, with.future, initial.q, initial.w, h)};
    return {initial.q, exact(h).q};
  }

  void report(const std::string& message) const {
    if (progress) progress(message);
  }
};

}  // namespace vivv
