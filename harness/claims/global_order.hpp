// global-order: the error in q at fixed T over N = T/h DEL steps is O(h^r)
// (Marsden–West Thm 2.3.1 item 1; the corollary of paper Thm 5.5).
#pragma once

#include "harness/claims/claim.hpp"
#include "harness/claims/del_local_error.hpp"
#include "harness/claims/map_local_order.hpp"

namespace vivv {

// Final positions and end momenta p_end(q_{N−1}, q_N) of the DEL run for
// every N of the sweep, with the solver's worst iteration count and residual.
template <LagrangianSystem System>
struct SweepRun {
  using T = typename System::Scalar;
  std::vector<Vector<T, System::dimension>> q_final, p_final;
  std::vector<std::shared_ptr<const DelTrajectory<T, System::dimension>>> trajectories;
};

// x_0 … x_N: N steps of the case's one-step map from the exact initial state. A state that
// leaves the finite numbers (an explicit map blown up by too large a step) is bad input naming
// the step, N and h, not an error of NaN or infinity fitted into a verdict.
template <LagrangianSystem System>
std::vector<State<typename System::Scalar, System::dimension>> map_trajectory(const CaseContext<System>& context,
                                                                             const typename System::Scalar& h, int N) {
  using T = typename System::Scalar;
  using std::isfinite;
  std::vector<State<T, System::dimension>> x{context.initial};
  // Every state at once where the map can (a program that took up "trajectory": a batch a
  // request); a run it cannot finish so is taken a step at a time below, which says where it left.
  if (auto states = context.map_at(T(0)).trajectory(context.initial, h, N)) {
    x.insert(x.end(), states->begin(), states->end());
    return x;
  }
  for (int k = 0; k < N; ++k) {
    x.push_back(context.map_at(T(k * h)).step(x.back(), h));
    for (int i = 0; i < static_cast<int>(x.back().q.size()); ++i)
      if (!isfinite(x.back().q[i]) || !isfinite(x.back().w[i]))
        throw CaseError(context.spec.file, "steps",
                        context.map->name() + " left the finite numbers at step " + std::to_string(k + 1) +
                            " of N = " + std::to_string(N) + " (h = " + format_scalar(h, 6) +
                            "): the step is too large for this map; increase the step counts");
  }
  return x;
}

// What the map's run of N steps cost, from `meter` started before it and the program's count of
// evaluations then (`reported_before`). A map in another program evaluates its own L (or forces),
// which vivv does not see: what vivv counted are its own conversions between w and p, not the
// method's cost. Recorded as 0 (the report writes null: unknown); the program's own count where its
// answers give one.
template <LagrangianSystem System>
void record_map_run_cost(const CaseContext<System>& context, int N, const CostMeter& meter,
                         const std::optional<long>& reported_before) {
  context.run_costs[N] = meter.cost();
  if (context.spec.discretization.kind == "process") {
    context.run_costs[N].lagrangian_evaluations = 0;
    if (const std::optional<long> reported_after = context.map->reported_evaluations();
        reported_before && reported_after)
      context.run_costs[N].program_evaluations = *reported_after - *reported_before;
  }
}

// The case's one-step map run for N steps at h, computed once and kept in the context for the
// other claims that walk it.
template <LagrangianSystem System>
std::shared_ptr<const std::vector<State<typename System::Scalar, System::dimension>>>
shared_map_trajectory(const CaseContext<System>& context, const typename System::Scalar& h, int N) {
  auto& kept = context.map_runs[N];
  if (!kept) {
    const CostMeter meter;
    const std::optional<long> reported_before = context.map->reported_evaluations();
    kept = std::make_shared<const std::vector<State<typename System::Scalar, System::dimension>>>(
        map_trajectory(context, h, N));
    record_map_run_cost(context, N, meter, reported_before);
  }
  return kept;
}

// Whether a claim of the case reads a one-step map's states between x_0 and x_N (the callers of
// visit_map_trajectories below): then each run is kept whole, and no end state is taken alone.
inline bool reads_map_states_between(const CaseSpec& spec) {
  for (const std::string& claim : spec.claims)
    if (claim == "symplecticity" || claim == "energy-behaviour" || claim == "discrete-noether") return true;
  return false;
}

// x_N of the case's one-step map run for N steps at h: taken at once where the map can
// (OneStepMap::steps: a program that took up "steps" answers one request for the whole run) and no
// claim of the case reads the states between; otherwise the kept run's last state. A map that
// cannot finish at once (a state on the way not finite, or beyond the problem's scale) is run one
// step at a time, so that where it left is found and said as for any run.
template <LagrangianSystem System>
State<typename System::Scalar, System::dimension> map_end_state(const CaseContext<System>& context,
                                                                const typename System::Scalar& h, int N) {
  if (context.map_runs.count(N) || reads_map_states_between(context.spec))
    return shared_map_trajectory(context, h, N)->back();
  if (const auto kept = context.map_ends.find(N); kept != context.map_ends.end()) return kept->second;
  const CostMeter meter;
  const std::optional<long> reported_before = context.map->reported_evaluations();
  const auto end = context.map_at(typename System::Scalar(0)).steps(context.initial, h, N);
  if (!end) return shared_map_trajectory(context, h, N)->back();
  record_map_run_cost(context, N, meter, reported_before);
  return context.map_ends.emplace(N, *end).first->second;
}

// The TQ evolution of the case's discretization from the exact initial state over N steps at h,
// computed once per N and shared (global-order, twin-term-invariance).
template <LagrangianSystem System>
std::shared_ptr<const std::vector<State<typename System::Scalar, System::dimension>>>
shared_tq_trajectory(const CaseContext<System>& context, const typename System::Scalar& h, int N) {
  auto& kept = context.tq_runs[N];
  if (!kept) {
    const std::string what = "TQ sweep N = " + std::to_string(N);
    context.report(what);
    const CostMeter meter;
    kept = std::make_shared<const std::vector<State<typename System::Scalar, System::dimension>>>(
        tq_trajectory(context.system, *context.tq, context.initial, h, N,
                      context.step_progress(what)));
    context.run_costs[N] = meter.cost();
  }
  return kept;
}

// The structure claims' walk for a one-step map: `visit(h, x)` for each h with its
// trajectory x_0 … x_N, reporting "<what> over N steps at h = …" as it goes.
template <LagrangianSystem System, class Visit>
void visit_map_trajectories(const CaseContext<System>& context, const std::string& what, Visit&& visit) {
  using T = typename System::Scalar;
  const std::vector<T> steps = context.steps();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const int N = context.step_counts()[i];
    context.report(what + " over " + std::to_string(N) + " steps at h = " + to_decimal<T>(steps[i], 6));
    visit(steps[i], *shared_map_trajectory(context, steps[i], N));
  }
}

// The DEL run of `scheme` over N steps at h. The case's own scheme is run once per N and kept in
// the context: every claim that walks the sweep reads the same trajectory, so a claim's result
// does not depend on which claim ran first, and a long run is not repeated per claim.
template <LagrangianSystem System>
std::shared_ptr<const DelTrajectory<typename System::Scalar, System::dimension>> del_run(
    const CaseContext<System>& context, const DelScheme<typename System::Scalar>& scheme,
    const typename System::Scalar& h, int N) {
  using T = typename System::Scalar;
  const bool own = &scheme == &context.scheme;
  if (own)
    if (auto kept = context.del_runs.find(N); kept != context.del_runs.end()) return kept->second;
  context.report("DEL sweep N = " + std::to_string(N));
  const CostMeter meter;
  auto [q0, q1] = context.start(scheme, h);
  auto run = std::make_shared<const DelTrajectory<T, System::dimension>>(
      del_trajectory(context.system, scheme, q0, q1, h, N,
                     context.step_progress("DEL sweep N = " + std::to_string(N))));
  if (own) context.del_runs[N] = run, context.run_costs[N] = meter.cost();
  return run;
}

template <LagrangianSystem System>
SweepRun<System> run_sweep(const CaseContext<System>& context, const DelScheme<typename System::Scalar>& scheme,
                           bool keep_trajectories = false) {
  using T = typename System::Scalar;
  SweepRun<System> run;
  std::vector<T> steps = context.steps();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const T& h = steps[i];
    int N = context.step_counts()[i];
    if (context.tq) {  // the TQ evolution from the exact initial state
      const State<T, System::dimension>& end = shared_tq_trajectory(context, h, N)->back();
      run.q_final.push_back(end.q);
      run.p_final.push_back(momentum(context.at_step(h, N), end.q, end.w));
      continue;
    }
    if (context.map) {  // the one-step map from the exact initial state
      context.report(context.map->name() + " sweep N = " + std::to_string(N));
      const State<T, System::dimension> end = map_end_state(context, h, N);
      run.q_final.push_back(end.q);
      run.p_final.push_back(momentum(context.at_step(h, N), end.q, end.w));
      continue;
    }
    auto trajectory = del_run(context, scheme, h, N);
    run.q_final.push_back(trajectory->q[N]);
    // The last segment starts at t0 + (N − 1)·h.
    run.p_final.push_back(
        p_end(context.at_step(h, N - 1), scheme.future, trajectory->q[N - 1], trajectory->q[N], h));
    if (keep_trajectories) run.trajectories.push_back(std::move(trajectory));
  }
  return run;
}

// The structure claims' walk: the case's DEL sweep (run once for all claims), then
// `visit(h, q)` for each h with its trajectory q_0 … q_N, reporting
// "<what> over N steps at h = …" as it goes.
template <LagrangianSystem System, class Visit>
void visit_trajectories(const CaseContext<System>& context, const std::string& what, Visit&& visit) {
  using T = typename System::Scalar;
  SweepRun<System> run = run_sweep(context, context.scheme, true);
  const std::vector<T> steps = context.steps();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const auto& q = run.trajectories[i]->q;
    context.report(what + " over " + std::to_string(q.size() - 1) + " steps at h = " + to_decimal<T>(steps[i], 6));
    visit(steps[i], q);
  }
}

// p_k = p_begin[L_d](q_k, q_{k+1}) = −D1 L_d(q_k, q_{k+1}), k = 0 … N − 1: the momenta a DEL
// trajectory q of the case's sweep carries. They are computed once per N and shared by the claims
// that read them (energy-behaviour, modified-energy, discrete-noether); a trajectory that is not
// the sweep's kept one gets its own.
template <LagrangianSystem System>
std::shared_ptr<const std::vector<VectorOf<System>>>
trajectory_momenta(const CaseContext<System>& context,
                   const std::vector<VectorOf<System>>& q, const typename System::Scalar& h) {
  using Momenta = std::vector<VectorOf<System>>;
  const int N = static_cast<int>(q.size()) - 1;
  const auto kept_run = context.del_runs.find(N);
  const bool kept = kept_run != context.del_runs.end() && &kept_run->second->q == &q;
  if (kept)
    if (auto known = context.del_momenta.find(N); known != context.del_momenta.end())
      return known->second;
  auto momenta = std::make_shared<Momenta>();
  momenta->reserve(q.size() - 1);
  const bool timed = depends_on_time(context.system);
  for (std::size_t k = 0; k + 1 < q.size(); ++k)
    momenta->push_back(timed ? p_begin(context.at_step(h, static_cast<long>(k)), context.scheme.future, q[k], q[k + 1], h)
                             : p_begin(context.system, context.scheme.future, q[k], q[k + 1], h));
  if (kept) context.del_momenta[N] = momenta;
  return momenta;
}

// Steps too large for the motion are not evidence against an order: a failing series whose
// error at the smallest h is still above 1% of the motion's size A = max(|q(0)|, |q(T)|,
// |q(T) − q(0)|), and whose fit's interval does not exclude the prediction, has not reached the
// asymptotic range. It becomes inconclusive, asking for more steps. A scheme converging to a
// wrong solution still fails: its pairwise orders settle near 0 and the interval excludes the
// prediction. (Duffing at T = 40 with N = 2 … 32, errors larger than the motion itself, once
// failed at 1.34 against 2.) Nor does an interval that excludes the prediction refute it while the
// pairwise orders still rise, positive, by more than the noise at each of the last two changes: the
// error of a chaotic motion saturates at the motion's size and leaves it slowly as h falls, while
// a converged wrong solution's orders fall toward 0. The frozen argon crystal (seven Lennard-Jones
// atoms, a correct midpoint rule in double) at T = 0.02 ns, N = 1000 … 8000, had errors 0.053 …
// 0.036 nm (9–13% of the motion's size), orders 0.06, 0.19, 0.28 and an interval [0.03, 0.32],
// and failed.
inline bool orders_still_rising(const OrderFit& fit) {
  const std::vector<double> orders = orders_above_floor(fit);
  if (orders.size() < 3) return false;
  const double a = orders[orders.size() - 3], b = orders[orders.size() - 2], c = orders.back();
  return a > 0 && b - a > receding_noise && c - b > receding_noise;
}

// `one_step_sound`: one step of the same evolution, measured at its order, passed or approaches
// it (evidence.one_step); `parting`: how far the two finest runs end from each other. An error
// that refutes the order while one step is sound, the runs end as far from each other as from
// the reference (more than half the finest error: they do not converge to a common limit, as a
// method converging to the wrong solution's do), and the error does not grow as h shrinks (as an
// unstable method's does) is the runs parting from the reference over T — a chaotic motion does
// this at any step a sweep affords — and refutes nothing: a correct Störmer–Verlet on a five-atom
// Morse cluster (15 coordinates, T = 40, N = 800 … 3200) ended 1.2, 1.05, 0.83 from q(T) and failed
// global-order at 0.26 while one step approached 4. A method that steps another system fails that
// one step, which then decides the claim.
template <class T>
void unresolved_motion_is_inconclusive(Series& series, const T& size, double tolerance,
                                       int finest_steps, bool one_step_sound = false, const T& parting = 0) {
  if (!series.holds || *series.holds || series.inconclusive || !series.fit || !series.fit->ok ||
      !series.predicted_order || series.error.empty() || !(size > 0))
    return;
  const OrderFit& fit = *series.fit;
  const T finest_error = from_decimal<T>(series.error[static_cast<std::size_t>(fit.sorted.back())]);
  const T coarsest_error = from_decimal<T>(series.error[static_cast<std::size_t>(fit.sorted.front())]);
  const bool unresolved = finest_error > size / 100;
  const bool saturated = one_step_sound && parting > finest_error / 2 && !(finest_error > coarsest_error);
  const bool refuted_by_fit = fit.confidence_high < *series.predicted_order - tolerance;
  const bool refuted = refuted_by_fit && !orders_still_rising(fit) && !saturated;
  if (!unresolved || refuted) return;
  series.inconclusive = true;
  series.to_decide =
      "step counts from N = " + std::to_string(4 * finest_steps) +
      " up (the error must fall well below the motion before its order means anything)" +
      std::string(refuted_by_fit ? ", or a shorter T, over which the error grows less" : "");
  const std::string fails = ": fails";
  if (series.explanation.size() >= fails.size() &&
      series.explanation.compare(series.explanation.size() - fails.size(), fails.size(), fails) ==
          0)
    series.explanation.resize(series.explanation.size() - fails.size());
  series.explanation +=
      "; but the error at the smallest h, " + format_scalar(finest_error) + ", is " +
      format_scalar(T(100 * finest_error / size), 3) + "% of the motion's size " +
      format_scalar(size) +
      std::string(saturated && refuted_by_fit && !orders_still_rising(fit)
                      ? ", while one step of the same evolution converges at its order (evidence.one_step) and the "
                        "two finest runs end " + format_scalar(parting) + " apart, as far as from the reference: the "
                        "runs part from the reference and from each other over T, as a chaotic motion's do, and "
                        "the steps are "
                      : refuted_by_fit ? " and the pairwise orders still rise: the steps are "
                                       : " and the fit's interval does not exclude the prediction: the steps are ") +
      "too large for the motion, which neither confirms nor refutes the order; to decide: " +
      series.to_decide;
}

struct GlobalOrderClaim : Claim<GlobalOrderClaim> {
  static constexpr const char* id = "global-order";
  static constexpr bool takes_time_dependent_lagrangians = true;  // each step and end momentum at its own time
  static constexpr const char* series_rules[] = {"order", "floor", "none"};
  static constexpr const char* source = "Marsden–West Thm 2.3.1 (1); paper Thm 5.5 corollary";
  static constexpr const char* prediction =
      "|q_N − q(T)| = O(h^r) after N = T/h steps of an order-r discrete Lagrangian";

  // r: the order of the discrete evolution (twin terms cancel).
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>& context) {
    return context.map_order();
  }

  template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
  static void measure(const CaseContext<System>& context, ClaimResult& claim) {
    SweepRun<System> run = run_sweep(context, context.scheme);
    const State<T, N>& final_state = context.final_state;
    Vector<T, N> p_exact = momentum(at_time(context.system, T(context.start_time + context.final_time)), final_state.q,
                                    final_state.w);
    std::vector<T> q_error, p_error;
    for (std::size_t i = 0; i < run.q_final.size(); ++i) {
      q_error.push_back(max_norm<T, N>(run.q_final[i] - final_state.q));
      p_error.push_back(max_norm<T, N>(run.p_final[i] - p_exact));
    }
    claim.series.push_back(sweep_series(context, "|q_N − q(T)|", q_error, predicted(context)));
    using std::max;
    const T size = nan_max({max_norm<T, N>(context.initial.q), max_norm<T, N>(final_state.q),
                        max_norm<T, N>(Vector<T, N>(final_state.q - context.initial.q))});
    claim.series.push_back(sweep_series(
        context, context.tq || context.map ? "|FL(v_N) − p(T)|" : "|p_end(q_{N−1}, q_N) − p(T)|", p_error,
        std::nullopt));
    judge_one_step(context, claim);
    const std::string one_step =
        claim.evidence.contains("one_step") ? claim.evidence["one_step"].value("verdict", std::string()) : "";
    const T parting = run.q_final.size() >= 2
                          ? max_norm<T, N>(Vector<T, N>(run.q_final.back() - run.q_final[run.q_final.size() - 2]))
                          : T(0);
    unresolved_motion_is_inconclusive(claim.series.front(), size, context.order_tolerance,
                                      context.step_counts().back(), one_step == "pass" || one_step == "inconclusive",
                                      parting);
    conclude(claim);
    // One step of order about 1 (global order 0) is another system, and local-order's words say
    // so and where the error sits: global-order's failure says the same (evidence.one_step).
    if (claim.verdict == "fail" && claim.evidence.contains("one_step") &&
        claim.evidence["one_step"].contains("another_system"))
      claim.explanation += ". " + claim.evidence["one_step"]["another_system"].get<std::string>();
  }

 private:
  // One step (docs/claims.md, global-order): a lower-order term too small for the global sweep
  // to resolve shows at once in one step of the same evolution, at the case's steps and up to
  // one_step_halvings below its finest (to the floor). For a
  // one-step map, global-order iterates that map from (q0, p0), and its step is local-order's
  // measurement (order r + 1); for a DEL, one step of the two-step recurrence from exact q(t),
  // q(t + h) (order r + 2, harness/claims/del_local_error.hpp) — not the DEL's map on (q, p),
  // whose momenta may be off where the trajectory is not. An off-centre node (0.45 for ½) on an
  // elastic pendulum passed global-order at 2.14 under --refine while one step showed the
  // missing order. A failing step is evidence of an order defect, and global-order does not pass
  // over it: the failing series joins the claim's and decides it. A step that passes or cannot
  // decide leaves the verdict to the global sweep (evidence.one_step). TQ discretizations have
  // the claim "order" for this.
  //
  // How far below the sweep's finest step one step looks: 2^-10, where a term one order lower
  // than the method's, whose share of the error at the finest step is 10^-3 (below the global
  // sweep's resolution, a share of about 0.03), has grown to the method's own. A smaller term — a
  // double literal's 10^-17 in an MPFR map — shows only far deeper: local-order and precision-leak
  // judge it (precision-leak names the format).
  static constexpr int one_step_halvings = 10;

  template <LagrangianSystem System>
  static void judge_one_step(const CaseContext<System>& context, ClaimResult& claim) {
    if (context.tq) return;
    ClaimResult local = MapLocalOrderClaim::result();
    const int order = predicted(context).order + (context.map ? 1 : 2);
    // What stops one step from being measured (a step too large for the map or its solver from a
    // state of the orbit, an error that is not finite, a map that diverged) leaves the verdict to
    // the global sweep, recorded.
    const auto not_measured = [&claim](const std::exception& why) {
      claim.evidence["one_step"] = {{"verdict", "not measured"}, {"explanation", why.what()}};
    };
    try {
      if (context.map) {
        MapLocalOrderClaim::measure_to(context, local, one_step_halvings);
      } else {
        local.series = del_local_error_series(context, order, 4, one_step_halvings);
        conclude(local);
      }
    } catch (const CaseError& error) {
      return not_measured(error);
    } catch (const SolverError& error) {
      return not_measured(error);
    } catch (const std::domain_error& error) {
      return not_measured(error);
    } catch (const MapDiverged& diverged) {
      return not_measured(diverged);
    }
    claim.evidence["one_step"] = {{"verdict", local.verdict},
                                  {"predicted_order", order},
                                  {"measurement", context.map ? "local-order's: one step of the map from (q, p)"
                                                              : "one DEL step from exact q(t), q(t + h) against q(t + 2h)"},
                                  {"explanation", local.explanation}};
    if (local.evidence.contains("error_location")) {
      claim.evidence["one_step"]["error_location"] = local.evidence["error_location"];
      const std::size_t another = local.explanation.find("One step errs like h^");
      if (another != std::string::npos)
        claim.evidence["one_step"]["another_system"] = local.explanation.substr(another);
    }
    if (local.verdict != "fail") return;
    for (Series& series : local.series)
      if (series.holds && !*series.holds && !series.inconclusive) {
        series.label = "one step: " + series.label;
        series.explanation += std::string(context.map ? " (local-order's measurement" : " (one step of the DEL") +
                              ", which global-order includes: one step shows a lower-order term the global sweep "
                              "does not yet resolve)";
        claim.series.push_back(std::move(series));
        return;
      }
  }
};

}  // namespace vivv
