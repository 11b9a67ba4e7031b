// Which reference a case runs against, at what tolerance, and how its promise is checked: a
// closed form chosen at run time for a catalogue system that has one (in MPFR), the Taylor flow
// otherwise (references/case_reference.hpp); CaseContext (case_context.hpp) makes it.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/case_file.hpp"
#include "cases/catalogue.hpp"
#include "core/lagrangian/state.hpp"
#include "core/numerics/scalar.hpp"
#include "reports/results.hpp"
#include "references/case_reference.hpp"

namespace vivv {

// Reference tolerance for a case computed in MPFR with `digits` decimal digits: ten
// digits of the working precision are kept as guard. In double, long double and
// float128 the reference runs in the same scalar: 1000 ε, three digits of guard.
// A program that computes in double (`double_program`) is judged in float128 at a double's
// rounding (working_epsilon): its reference needs 10⁻⁶ of a double's ε, 2.2e-22, which puts
// the floors' reference part (1000·tolerance) 10⁻⁶ below their rounding part (1000·N·ε of a
// double) and costs a Taylor order of 30 where float128's own floor, 1.9e-30, cost 39 (the
// 114-coordinate LJ38 case: its reference and cross-check 36 s → see docs/performance.md).
template <class T>
T reference_tolerance_for(int digits, bool double_program = false) {
  using std::pow;
  using std::max;
  if (double_program) return max(T(T(1e-6) * T(std::numeric_limits<double>::epsilon())), T(1000 * epsilon<T>()));
  if constexpr (is_mpfr_v<T>) return pow(T(10), -(digits - 10));
  else return 1000 * epsilon<T>();
}

// The reference's own cross-check against what it promises: the distance
// estimate_error(v, T) of the reference from an independent check may reach
// (tolerance + the check's own tolerance)·(1 + |F_T(v)|_max), the max-norm form
// of |error_i| <= tolerance·(1 + |y_i|) for each of the two.
template <class Reference, class T, int N>
ReferenceCheck check_reference(const Reference& reference, const State<T, N>& initial, const T& final_time) {
  using std::max;
  const State<T, N> end = reference.advance(initial, final_time);
  const T allowed = (reference.tolerance() + reference.check_tolerance()) *
                    (1 + max(max_norm<T, N>(end.q), max_norm<T, N>(end.w)));
  const T estimate = reference.estimate_error(initial, final_time);
  return {to_decimal<T>(reference.tolerance()), to_decimal<T>(estimate), to_decimal<T>(allowed),
          estimate <= allowed};
}

// The closed-form flow of the case's catalogue system, chosen at run time
// (references/case_reference.hpp): in MPFR, for a catalogue system with a ClosedFormFlow
// (references/reference_flow.hpp: the harmonic oscillator, the pendulum, Kepler's problem), whose
// claims run on its formula twin; none for a formula or a registered system. In double, long
// double and float128 every system's reference is the Taylor flow at its floor, cheap there, as it
// was before closed forms were chosen at run time (every verdict kept); in MPFR the Taylor flow's
// order and cost grow with the digits, and a closed form costs nothing.
template <LagrangianSystem System>
std::optional<typename CaseReference<System>::ClosedForm> catalogue_closed_form(const CaseSpec& spec) {
  using T = typename System::Scalar;
  using Full = State<T, System::dimension>;
  using ClosedForm = typename CaseReference<System>::ClosedForm;
  std::optional<ClosedForm> closed;
  if constexpr (is_mpfr_v<T>) {
    if (spec.formula) return closed;
    const auto choose = [&](auto catalogue) {
      using Catalogue = decltype(catalogue);
      if constexpr (has_closed_form_v<Catalogue>) {
        if (closed || spec.system != Catalogue::name) return;
        std::vector<T> values;
        for (const auto& [name, value] : spec.parameters) values.push_back(from_decimal<T>(value));
        catalogue.set(values);
        const auto advance = [catalogue](const Full& start, const T& t) {
          constexpr int d = Catalogue::dimension;
          if (start.q.size() != d || start.w.size() != d)
            throw std::logic_error(std::string("the closed form of ") + Catalogue::name + " asked for a state of " +
                                   std::to_string(start.q.size()) + " coordinates");
          State<T, d> x;
          for (int i = 0; i < d; ++i) x.q[i] = start.q[i], x.w[i] = start.w[i];
          const State<T, d> y = ClosedFormFlow<Catalogue>::advance(catalogue, x, t);
          Full end{zero_vector<T, System::dimension>(d), zero_vector<T, System::dimension>(d)};
          for (int i = 0; i < d; ++i) end.q[i] = y.q[i], end.w[i] = y.w[i];
          return end;
        };
        closed.emplace(ClosedForm{advance, ClosedFormFlow<Catalogue>::method()});
      }
    };
    std::apply([&](auto... catalogue) { (choose(catalogue), ...); }, CatalogueSystems<T>{});
  }
  return closed;
}

}  // namespace vivv
