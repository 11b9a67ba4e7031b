// A case made concrete in scalar T for one system: the parsed numbers, the
// schemes, the reference flow and the step sweep every claim measures over.
#pragma once

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <initializer_list>
#include <mutex>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/case_file.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/lagrangian/euler_lagrange_tape.hpp"
#include "core/formulas/formula_discretization.hpp"
#include "core/maps/odeint_map.hpp"
#include "core/numerics/quadrature.hpp"
#include "core/lagrangian/state.hpp"
#include "core/tq/tq_evolution.hpp"
#include "core/maps/user_map.hpp"
#include "harness/verdicts/claim_result.hpp"
#include "harness/verdicts/order_fit.hpp"
#include "harness/process/process_map.hpp"
#include "harness/context/reference_cache.hpp"
#include "harness/context/shared_references.hpp"
#include "harness/context/reference_choice.hpp"

namespace vivv {

// The twin term a case file describes, in scalar T.
template <class T>
std::optional<TwinTerm<T>> make_twin(const std::optional<TwinSpec>& spec) {
  if (!spec) return std::nullopt;
  TwinTerm<T> twin;
  for (const auto& a : spec->a) twin.a.push_back(from_decimal<T>(a));
  twin.power = spec->power;
  return twin;
}

// The Q×Q discretization a case file describes, in scalar T (a formula's needs its system:
// the overload below). Of a TQ discretization, only the twin term is shared.
template <class T>
QxQDiscretization<T> make_discretization(const DiscretizationSpec& spec) {
  QxQDiscretization<T> d;
  d.twin = make_twin<T>(spec.twin);
  if (spec.formalism != "qxq") return d;
  d.rule = *rule_from_name(spec.kind);
  if (spec.parameter) d.parameter = from_decimal<T>(*spec.parameter);
  if (d.rule == QxQRule::galerkin)
    d.galerkin = std::make_shared<const GalerkinRule<T>>(
        GalerkinSpec{spec.galerkin_degree, spec.galerkin_quadrature == "lobatto", spec.galerkin_nodes});
  return d;
}

// The Q×Q discretization a case file describes for `system`; a formula L_d is recorded with
// the system's L and the case's parameters.
template <LagrangianSystem System>
QxQDiscretization<typename System::Scalar> make_discretization(
    const DiscretizationSpec& spec, const System& system,
    const std::vector<std::pair<std::string, std::string>>& parameters, const std::string& time_name = "t") {
  using T = typename System::Scalar;
  if (spec.formalism != "qxq" || spec.kind != "expression") return make_discretization<T>(spec);
  QxQDiscretization<T> d =
      spec.recorded
          ? recorded_discretization(system, spec.expression, *spec.recorded, spec.declared_order)
          : expression_discretization(system, spec.expression, *spec.expression_tree, parameters, spec.declared_order,
                                      time_name);
  d.twin = make_twin<T>(spec.twin);
  return d;
}

// A decimal "0.5" or a fraction "1/2", parsed in T.
template <class T>
T from_fraction(const std::string& text) {
  auto slash = text.find('/');
  if (slash == std::string::npos) return from_decimal<T>(text);
  return from_decimal<T>(text.substr(0, slash)) / from_decimal<T>(text.substr(slash + 1));
}

// The order of an exact part of a discretization: more than any sweep can measure.
constexpr int unbounded_order = 1000;

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
  d.twin = make_twin<T>(spec.twin);
  return d;
}

// The TQ discretization a case file describes for `system`: as above, with the
// Euler–Lagrange tape a(q, w) of its L recorded for a taylor psi.
template <LagrangianSystem System>
TQDiscretization<typename System::Scalar> make_tq_discretization(
    const DiscretizationSpec& spec, const System& system, const typename System::Scalar& curve_tolerance,
    const std::vector<std::pair<std::string, std::string>>& parameters) {
  auto d = make_tq_discretization<typename System::Scalar>(spec, curve_tolerance);
  if (d.lagrangian == TQLagrangianKind::pullback) d.qxq = make_discretization(*spec.tq->qxq, system, parameters);
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

// Order of a TQ discretization's curve segment: a linear psi agrees with the
// solution to O(t²): 1; a taylor-r psi to O(t^{r+1}): r; the exact psi is unbounded.
template <class T>
int psi_order(const TQDiscretization<T>& d) {
  return d.psi == CurveFamily::taylor ? d.r : d.psi == CurveFamily::exact ? unbounded_order : 1;
}

// Order of L_h against the action integral along its own curve: 2m for m
// Gauss–Legendre nodes, the Q×Q rule's order (without its twin term) for a
// pullback, unbounded for the exact action.
template <class T>
int action_order(const TQDiscretization<T>& d) {
  return d.lagrangian == TQLagrangianKind::quadrature ? 2 * static_cast<int>(d.nodes.size())
         : d.lagrangian == TQLagrangianKind::exact    ? unbounded_order
                                                      : d.qxq.rule_order();
}

// The power s of a twin term that changes L_h (a ≠ 0), else unbounded.
template <class T>
int twin_order(const std::optional<TwinTerm<T>>& twin) {
  return twin && has_nonzero_coefficient(*twin) ? twin->power : unbounded_order;
}

// Order r of the discrete evolution of a TQ discretization: the lower of the
// curve's and the action's. A twin term does not lower it: it cancels exactly
// in a matched step (paper §2.2; twin-term-invariance checks it).
template <class T>
int evolution_order(const TQDiscretization<T>& d) {
  return std::min(psi_order(d), action_order(d));
}

// Order r of a TQ discretization: its order of contact with the exact one
// (Definition 5.4), the lower of the curve's, the action's and the twin term's.
template <class T>
int nominal_order(const TQDiscretization<T>& d) {
  const int pulled_back_twin = d.lagrangian == TQLagrangianKind::pullback ? twin_order(d.qxq.twin) : unbounded_order;
  return std::min({evolution_order(d), twin_order(d.twin), pulled_back_twin});
}

// The order of contact of two TQ discretizations with the same α±
// (psi² = psi¹ + O(t^{r+1}), L_h² = L_h¹ + O(h^{r+1})): not just the lower of
// their orders against the exact one, but what they share. Two Taylor curves
// (linear is taylor-1) agree to the lower degree, identical curves everywhere;
// two actions along one curve agree to the lower of their orders, identical
// ones (the same node count, the same pulled-back rule) everywhere; a twin term
// on one side only, or different ones, to its power. At least min(r¹, r²).
template <class T>
int contact_order(const TQDiscretization<T>& one, const TQDiscretization<T>& two) {
  const bool same_curve = one.psi == two.psi && psi_order(one) == psi_order(two);
  const int psi_contact = same_curve ? unbounded_order : std::min(psi_order(one), psi_order(two));
  const bool same_action =
      one.lagrangian == two.lagrangian &&
      (one.lagrangian == TQLagrangianKind::exact ||
       (one.lagrangian == TQLagrangianKind::quadrature && one.nodes.size() == two.nodes.size()) ||
       (one.lagrangian == TQLagrangianKind::pullback && same_rule(one.qxq, two.qxq) && !one.qxq.twin &&
        !two.qxq.twin));
  const int action_contact = same_action ? unbounded_order : std::min(action_order(one), action_order(two));
  const bool same_twin = twin_order(one.twin) == twin_order(two.twin) &&
                         (twin_order(one.twin) == unbounded_order || one.twin->a == two.twin->a);
  const int twin_contact = same_twin ? unbounded_order : std::min(twin_order(one.twin), twin_order(two.twin));
  return std::min({psi_contact, action_contact, twin_contact});
}

// What a run costs from construction to cost(): the evaluations of L this thread made (every
// system counts them, core/lagrangian/lagrangian.hpp) and the wall time.
class CostMeter {
 public:
  RunCost cost() const {
    return {lagrangian_evaluations - evaluations_,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count(), std::nullopt};
  }

 private:
  long evaluations_ = lagrangian_evaluations;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

// An order claim's prediction: `order`, exact when the case declared it (then
// never below the theorem's own bound).
struct OrderPrediction {
  int order = 0;
  bool exact = false;
};

template <LagrangianSystem System>
struct CaseContext {
  using T = typename System::Scalar;
  static constexpr int N = System::dimension;

  const CaseSpec& spec;
  System system;
  int n;  // the system's coordinates (N, or its run-time size)
  // A closed form where the catalogue system has one (in MPFR: catalogue_closed_form), the
  // Taylor-series flow otherwise, shared by the run's cases on the same system, scalar and
  // tolerance (make_reference).
  using Reference = CaseReference<System>;
  // Where the reference came from (make_reference): made here, kept from an earlier case of the
  // run, or made here and told an earlier run's answers (--reference-cache).
  enum class ReferenceOrigin { made, kept, recalled };
  ReferenceOrigin reference_origin = ReferenceOrigin::made;
  Reference reference;
  State<T, N> initial;
  T start_time;  // t0, the initial state's time: `system` is at it (at_time)
  T final_time;  // the length of the run, T (it ends at t0 + T)
  State<T, N> final_state;  // the reference state at final_time, computed once
  // The reference's cross-check's estimate of its error at T (harness/run/run_system_impl.hpp sets
  // it before any claim runs; 0 until then): floors() rests on it where it exceeds the tolerance.
  T reference_error_at_T = 0;
  DelScheme<T> scheme;                    // formalism "qxq"
  std::optional<TQDiscretization<T>> tq;  // formalism "tq"
  std::optional<TQDiscretization<T>> tq_compare;  // contact-order's second discretization
  std::optional<TQDiscretization<T>> tq_past;     // past-future-symmetry: a mismatched past segment
  std::shared_ptr<const OneStepMap<T, N>> map;    // formalism "map": another library's stepper
  double order_tolerance;
  FitOptions fit_options;  // --refine tightens the asymptotic range (harness/run/run_case.cpp)
  std::function<void(const std::string&)> progress;
  // The case's sweep, computed once per N and shared by every claim that walks it (global-order,
  // energy-behaviour, symplecticity, discrete-noether, modified-energy, twin-term-invariance): the
  // DEL trajectories of `scheme`, the one-step map's states and the TQ evolution's
  // (harness/claims/global_order.hpp, run_sweep).
  mutable std::map<int, std::shared_ptr<const DelTrajectory<T, N>>> del_runs;
  // p_begin along each kept DEL trajectory (trajectory_momenta in harness/claims/global_order.hpp).
  mutable std::map<int, std::shared_ptr<const std::vector<Vector<T, N>>>> del_momenta;
  // What each N's run (the case's DEL, map or TQ evolution) cost: L evaluations and seconds.
  mutable std::map<int, RunCost> run_costs;
  mutable std::map<int, std::shared_ptr<const std::vector<State<T, N>>>> map_runs;
  // The map's end state x_N alone, where no claim of the case reads the states between and the
  // map takes N steps at once (OneStepMap::steps; global_order.hpp, map_end_state).
  mutable std::map<int, State<T, N>> map_ends;
  mutable std::map<int, std::shared_ptr<const std::vector<State<T, N>>>> tq_runs;  // formalism "tq"

  CaseContext(const CaseSpec& spec_, System system_, std::function<void(const std::string&)> progress_)
      : spec(spec_),
        system(system_),
        n(dimension_of(system_)),
        reference(make_reference(spec_, system_, reference_origin)),
        start_time(from_decimal<T>(spec_.start_time)),
        final_time(from_decimal<T>(spec_.final_time)),
        order_tolerance(std::stod(spec_.order_tolerance)),
        progress(serialized(std::move(progress_))) {
    initial = {zero_vector<T, N>(n), zero_vector<T, N>(n)};
    for (int i = 0; i < n; ++i) {
      initial.q[i] = from_decimal<T>(spec.q[i]);
      initial.w[i] = from_decimal<T>(spec.w[i]);
    }
    // A program is greeted first: one that declines the system or fails stops the case before the
    // reference flow's minutes (its orbit's size is widened by the state at T below).
    std::shared_ptr<ProcessMap<System>> program;
    if (spec.discretization.formalism == "map" && spec.discretization.kind == "process") program = make_process_map();
    reference.set_progress(flow_progress("reference flow"), flow_progress("reference flow's cross-check"));
    report("reference flow to T = " + spec.final_time +
           (reference_origin == ReferenceOrigin::kept
                ? " (the flow an earlier case on this system made, kept for this one)"
            : reference_origin == ReferenceOrigin::recalled
                ? " (with the answers an earlier run of this vivv kept, --reference-cache)"
                : ""));
    // The reference's cross-check (harness/run/run_system_impl.hpp, check_reference) is an
    // integration as long as the flow's: a Taylor reference begins it now, on a thread beside this
    // one (its progress lines are serialized with this thread's: progress_).
    if constexpr (requires { reference.start_check(initial, final_time); }) reference.start_check(initial, final_time);
    final_state = reference.advance(initial, final_time);
    if (program) {
      program->widen_orbit(orbit_size({final_state}));
      map = program;
    } else if (spec.discretization.formalism == "map") {
      map = make_map();
    }
    if (spec.discretization.formalism == "tq") {
      // An exact psi runs at the reference's step tolerance.
      T curve_tolerance = reference.tolerance() / 1000;
      tq = make_tq_discretization(spec.discretization, system, curve_tolerance, spec.parameters);
      if (spec.compare_discretization)
        tq_compare = make_tq_discretization(*spec.compare_discretization, system, curve_tolerance, spec.parameters);
      if (spec.past_discretization)
        tq_past = make_tq_discretization(*spec.past_discretization, system, curve_tolerance, spec.parameters);
    }
    const std::string time_name = spec.formula ? spec.formula->time_name : "t";
    scheme.future = make_discretization(spec.discretization, system, spec.parameters, time_name);
    scheme.past = spec.past_discretization && !tq_past
                      ? make_discretization(*spec.past_discretization, system, spec.parameters, time_name)
                      : scheme.future;
    scheme.mismatched = spec.past_discretization.has_value() && !tq_past;
    // The initial state must be inside the Lagrangian's domain and regular
    // there; otherwise this throws SingularLagrangianError naming the state.
    euler_lagrange_acceleration(system, initial.q, initial.w);
  }

  // The reference, if shared with later cases of the run, stops reporting this case's progress.
  ~CaseContext() { reference.set_progress({}, {}); }
  CaseContext(const CaseContext&) = delete;
  CaseContext& operator=(const CaseContext&) = delete;

  // The case's reference flow: a closed form made here (it costs nothing), a Taylor flow the one
  // an earlier case of the run on the same system, scalar and tolerance made, if it was kept for
  // this one (harness/context/shared_references.hpp), its trajectories and cross-checks with it.
  static Reference make_reference(const CaseSpec& spec, const System& system, ReferenceOrigin& origin) {
    const T tolerance =
        reference_tolerance_for<T>(spec.digits, spec.discretization.process_precision == "double");
    origin = ReferenceOrigin::made;
    if (auto closed = catalogue_closed_form<System>(spec)) return Reference(system, std::move(*closed));
    const std::string key = reference_key(spec);
    bool kept = false;
    Reference reference = shared_reference<Reference>(
        key,
        [&] {
          Reference made(system, tolerance);
          if (recall_reference_answers(made, key, spec.dimension)) origin = ReferenceOrigin::recalled;
          return made;
        },
        kept);
    if (kept) origin = ReferenceOrigin::kept;
    return reference;
  }

  // With --reference-cache, the answers the reference gave, written for the next run.
  void save_reference_answers() const {
    if (!reference.closed_form()) keep_reference_answers(reference, reference_key(spec));
  }

  // A state of the run for a message: the initial state as the case file writes it, another with
  // 6 significant digits.
  std::string where_sampled(const State<T, N>& x) const {
    if (x.q == initial.q && x.w == initial.w) {
      std::string q, w;
      for (std::size_t i = 0; i < spec.q.size(); ++i) q += (i ? ", " : "") + spec.q[i];
      for (std::size_t i = 0; i < spec.w.size(); ++i) w += (i ? ", " : "") + spec.w[i];
      return "the initial state q = (" + q + "), w = (" + w + ")";
    }
    return "q = " + to_decimal_tuple<T, N>(x.q, 6) + ", w = " + to_decimal_tuple<T, N>(x.w, 6) +
           (x.q == final_state.q && x.w == final_state.w
                ? " (the reference's state at T)"
                : " (a mixture of the initial state and the reference's at T)");
  }

  // The odeint stepper of the case on the system's separable form, after checking that L is
  // ½ wᵀ M w − V(q) with M constant at the initial and final states and their two mixtures.
  std::shared_ptr<const OneStepMap<T, N>> make_map() const {

    std::vector<State<T, N>> samples = {initial, final_state, {initial.q, final_state.w}, {final_state.q, initial.w}};
    if (auto defect = separability_defect(system, samples))
      throw CaseError(
          spec.file,
          spec.discretization.kind == "odeint" ? "discretization.stepper" : "discretization.name",
          spec.discretization.kind + " " + spec.discretization.stepper +
              " steps a separable system, L = 1/2 w^T M w - V(q) with M constant, and this "
              "Lagrangian is not one: " +
              defect->quantity + " = " + format_scalar(defect->size, 3) + " at " +
              where_sampled(defect->at));
    if (spec.discretization.kind == "odeint")
      return make_odeint_map<T, N>(spec.discretization.stepper, separable_form(system, initial));
    const auto& factories = map_factories<T, N>();
    const auto factory = factories.find(spec.discretization.stepper);
    if (factory == factories.end())
      throw CaseError(spec.file, "discretization.name",
                      "'" + spec.discretization.stepper + "' is not registered for " + scalar_name<T>() + " and " +
                          std::to_string(n) + " coordinates");
    return factory->second(separable_form(system, initial));
  }

  // max |q_i|, |p_i| over `states`: by it an answer far beyond the orbit is a divergence (ProcessMap).
  T orbit_size(std::initializer_list<State<T, N>> states) const {
    using std::abs, std::max;
    T size = 0;
    for (const State<T, N>& x : states) {
      const Vector<T, N> p = momentum(system, x.q, x.w);
      for (int i = 0; i < n; ++i) size = max({size, T(abs(x.q[i])), T(abs(p[i]))});
    }
    return size;
  }

  // The case's map in another program (kind "process"), started only where the run allows it, its
  // orbit's size that of the initial state until the reference's state at T widens it.
  std::shared_ptr<ProcessMap<System>> make_process_map() const {
    const DiscretizationSpec& d = spec.discretization;
    if (!d.process_allowed) {  // a run that did not call permit_process (harness/process/program.hpp)
      CaseSpec refused = spec;
      permit_process(refused, false, 0, "vivv run --allow-process");
    }
    nlohmann::json system_json = spec.source.contains("system") && spec.source["system"].is_object()
                                     ? spec.source["system"]
                                     : nlohmann::json{{"name", spec.system}};
    system_json["params"] =
        parameters_as_written(spec.parameters, [](const std::string&, const std::string& value) { return value; });
    MapProcess::Options options;
    options.command = d.command;
    options.directory = std::filesystem::absolute(spec.file).parent_path().string();
    options.timeout_seconds = d.process_timeout_seconds;
    return std::make_shared<ProcessMap<System>>(system, options, system_json, d.declared_order,
                                                orbit_size({initial}), d.process_precision == "double");
  }

  // The step counts the claims walk: the case's sweep, or, while a claim is judged again on the
  // runs that finished after one diverged (Claim::evaluate, harness/claims/claim.hpp), those.
  mutable std::optional<std::vector<int>> finished_steps;
  const std::vector<int>& step_counts() const { return finished_steps ? *finished_steps : spec.steps; }

  // h = T/N for every N of the sweep.
  std::vector<T> steps() const {
    std::vector<T> h;
    for (int N : step_counts()) h.push_back(final_time / N);
    return h;
  }

  // The N of the sweep whose h = T/N a diverged run names ("0.0025", 6 significant digits).
  std::optional<int> step_count_of(const std::string& h) const {
    using std::abs;
    T value;
    try {
      value = from_decimal<T>(h);
    } catch (const std::exception&) {
      return std::nullopt;
    }
    for (int N : step_counts())
      if (abs(T(final_time / N - value)) <= T(1e-5) * abs(value)) return N;
    return std::nullopt;
  }
  // The order r of the case's discrete Lagrangian(s), twin terms included: the
  // lower of the two sides. What lagrangian-order and legendre-order predict from.
  int lagrangian_order() const {
    if (tq) return nominal_order(*tq);
    return std::min(scheme.future.nominal_order(), scheme.past.nominal_order());
  }

  // The order of the case's discrete evolution, what global-order and order
  // predict from: that of the discretization without its twin terms, which
  // cancel exactly in a matched DEL (paper §2.2). So midpoint + a·h·(q_e − q_b)
  // is an order-1 L_d with an order-2 map. On a mismatched pair it is the order
  // the variational integrator would have; the mismatch is what fails it.
  int map_order() const {
    if (map) return map->order();
    if (tq) return evolution_order(*tq);
    return std::min(scheme.future.rule_order(), scheme.past.rule_order());
  }

  // What an order claim predicts for its main series: the theorem's order, a
  // lower bound, or the exact order the case declares — never below the
  // theorem's (check_declared_orders in harness/claims/registry.hpp).
  OrderPrediction predict(const std::string& claim, int theorem) const {
    auto it = spec.expect.find(claim);
    if (it == spec.expect.end()) return {theorem, false};
    return {it->second, true};
  }

  // Errors below this are at the floor: a thousand times the larger of the
  // reference tolerance and N_max rounding errors, relative to the state's size — and never below
  // a thousand times the reference's error at T as its cross-check estimates it
  // (reference_error_at_T), where that is more than its tolerance promised.
  // floors() keeps the two apart (harness/verdicts/order_fit.hpp, Floor).
  Floor<T> floors() const {
    using std::max;
    const T scale = max(T(1), max(max_norm<T, N>(initial.q), max_norm<T, N>(initial.w)));
    const T steps = T(step_counts().back());
    return {1000 * steps * working_epsilon() * scale, 1000 * max(T(reference.tolerance() * scale), reference_error_at_T),
            static_cast<long double>(scale), static_cast<long double>(step_counts().back()),
            spec.discretization.process_precision == "double"};
  }
  T floor() const { return floors().value(); }

  // The unit roundoff of what is judged: T's, or a double's for a program that computes in double
  // ("precision": "double"), whose case computes vivv's side in a wider T (harness/run/run_case.cpp).
  // Every rounding allowance of the map claims is a multiple of it.
  T working_epsilon() const {
    if (spec.discretization.process_precision == "double") return T(std::numeric_limits<double>::epsilon());
    return epsilon<T>();
  }

  // The floor of a quantity the reference does not enter (two discretizations compared, a
  // displacement F_h(v) − v): rounding only, unless one of the case's TQ discretizations has an
  // exact part, computed to the reference's tolerance.
  Floor<T> floors_without_reference() const {
    Floor<T> f = floors();
    const auto exact_part = [](const std::optional<TQDiscretization<T>>& d) {
      return d && (d->psi == CurveFamily::exact || d->lagrangian == TQLagrangianKind::exact);
    };
    if (!exact_part(tq) && !exact_part(tq_compare) && !exact_part(tq_past)) f.reference = 0;
    return f;
  }

  // Reference state F_t(initial), at t0 + t.
  State<T, N> exact(const T& t) const { return reference.advance(initial, t); }

  // The exact state s after x, where x is the reference orbit's state at t0 + t (x = exact(t)):
  // for an L that depends on time the orbit itself at t0 + t + s, since the reference flow starts
  // at t0 (the flow from x at its own time is the same orbit); any other system's F_s(x).
  State<T, N> exact_after(const State<T, N>& x, const T& t, const T& s) const {
    return depends_on_time(system) ? reference.advance(initial, T(t + s)) : reference.advance(x, s);
  }

  // The system at t0 + t (an autonomous one at any t).
  System at(const T& t) const { return at_time(system, T(start_time + t)); }

  // The system at t0 + k·h, the time of q_k in a run of steps h (for an L that depends on time;
  // any other system is the same at every time).
  System at_step(const T& h, long k) const { return at_time(system, T(start_time + k * h)); }

  // The case's map with its clock at t0 + t, for the calls that follow from a state at that time
  // (OneStepMap::set_time: a program of an L that depends on time is sent the time in its
  // requests; any other map ignores it).
  const OneStepMap<T, N>& map_at(const T& t) const {
    map->set_time(T(start_time + t));
    return *map;
  }

  // q_0, q_1 for N steps: q_1 from the reference flow (isolating the
  // method's own error) or from p_begin(q_0, q_1) = p(0).
  std::pair<Vector<T, N>, Vector<T, N>> start(const DelScheme<T>& with, const T& h) const {
    if (spec.start == "momentum")
      return {initial.q, start_from_momentum(system, with.future, initial.q, initial.w, h)};
    return {initial.q, exact(h).q};
  }

  void report(const std::string& message) const {
    if (progress) progress(message);
  }

  // `print` called by one thread at a time: the reference's cross-check reports from its own.
  static std::function<void(const std::string&)> serialized(std::function<void(const std::string&)> print) {
    if (!print) return print;
    return [print = std::move(print), mutex = std::make_shared<std::mutex>()](const std::string& message) {
      std::lock_guard<std::mutex> lock(*mutex);
      print(message);
    };
  }

  // For a long loop of steps: "<what>: step k of N" at most every five seconds (none without
  // progress), so that a million-step sweep is not minutes of silence.
  std::function<void(int, int)> step_progress(const std::string& what) const {
    if (!progress) return {};
    using clock = std::chrono::steady_clock;
    return [print = progress, what, last = clock::now()](int k, int steps) mutable {
      if (clock::now() - last < std::chrono::seconds(5)) return;
      last = clock::now();
      print(what + ": step " + std::to_string(k) + " of " + std::to_string(steps));
    };
  }

  // The same for a flow integrating towards a time: "<what> at t = … of …".
  std::function<void(const T&, const T&)> flow_progress(const std::string& what) const {
    if (!progress) return {};
    using clock = std::chrono::steady_clock;
    return [print = progress, what, last = clock::now()](const T& reached, const T& target) mutable {
      if (clock::now() - last < std::chrono::seconds(5)) return;
      last = clock::now();
      // A trajectory extended by whole Taylor steps may end past its target: "of T" is where it
      // was asked to go, and t is not said beyond it.
      using std::abs;
      const T shown = abs(reached) > abs(target) ? target : reached;
      print(what + " at t = " + to_decimal<T>(shown, 6) + " of " + to_decimal<T>(target, 6));
    };
  }
};

}  // namespace vivv
