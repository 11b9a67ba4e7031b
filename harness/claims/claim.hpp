// What every claim shares, so that a claim states only its own formula,
// source, measurement, prediction and verdict (docs/claims.md, "Adding a claim").
//
// A claim is a type deriving from Claim<itself> with
//   static constexpr const char* id, source, prediction;
//   static constexpr const char* series_rules[];  // the rules its series may be decided by
//                                                 // (reports/SCHEMA.md): `vivv report` and
//                                                 // --baseline refuse a report naming another
//   template <LagrangianSystem System, class T = typename System::Scalar, int N = System::dimension>
//   static void measure(const CaseContext<System>&, ClaimResult& claim);
// which adds its series and evidence to the claim (result() made it, with the id, source and
// prediction) and concludes it; and, if it predicts an order, theorem_order(context) returning it
// (the default predicts none: an identity, exactness or an inconsistency). It is listed once in
// harness/claims/registry.hpp, which calls evaluate(context).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/platform/text.hpp"
#include "harness/context/case_context.hpp"
#include "harness/verdicts/finite_measurement.hpp"
#include "harness/verdicts/series.hpp"

namespace vivv {

// A claim that does not apply to the case (modified-energy on a rule its H₂ is not derived for):
// that claim is refused — `error`, naming why — and the case's other claims are judged; a case
// that lists no other claim is bad input (CaseError).
struct ClaimNotApplicable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A run of the sweep that left the problem's scale (MapDiverged): its N, its h as the map wrote
// it, and why.
struct DivergedRun {
  int N = 0;
  std::string h, why;
};

template <class Derived>
struct Claim {
  // Whether a failure of the claim is an order its series' fit shows (so that a known failure
  // states the range of that order); precision-leak judges floors, not one fitted order.
  static constexpr bool fails_by_order = true;

  // Whether the claim's measurement reads L at each state's own time, so that it applies to an L
  // that depends on time (core/lagrangian/lagrangian.hpp: at_time). A claim that does not is
  // refused for such a case, alone, naming why — and the claims that do, which a claim that
  // takes this up adds to the message below (tests/refused_claims/time-dependent-* pin it).
  static constexpr bool takes_time_dependent_lagrangians = false;
  // What measures such a case in the claim's place, said in its refusal (energy-behaviour's:
  // energy-balance); empty for none.
  static constexpr const char* in_place_for_time_dependent = "";

  // No order: the claim predicts an identity, exactness or an inconsistency.
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>&) {
    return std::nullopt;
  }

  // An empty result carrying the claim's id, source and prediction.
  static ClaimResult result() { return claim_result_for(Derived::id, Derived::source, Derived::prediction); }

  // The claim's result on the case: its id, source and prediction, and what measure() found.
  template <LagrangianSystem System>
  static ClaimResult evaluate(const CaseContext<System>& context) {
    ClaimResult claim = result();
    // A run that leaves the problem's scale at one N is left out, and the claim is judged on the
    // runs that finished (judge_finished_runs); finished_steps is the case's sweep again after.
    struct Restore {
      const CaseContext<System>& context;
      ~Restore() { context.finished_steps.reset(); }
    } restore{context};
    std::vector<DivergedRun> diverged_runs;  // in the order met
    for (;;) {
      try {
        if (!Derived::takes_time_dependent_lagrangians && depends_on_time(context.system))
          throw ClaimNotApplicable(std::string(Derived::id) + " is not measured for a Lagrangian that depends on time "
                                   "(the case's L uses '" + context.spec.formula->time_name +
                                   "'): of the claims, global-order, local-order, lagrangian-order, legendre-order, "
                                   "twin-term-invariance, symplecticity, discrete-noether, energy-balance and "
                                   "precision-leak are" +
                                   std::string(*Derived::in_place_for_time_dependent ? "; " : "") +
                                   Derived::in_place_for_time_dependent);
        Derived::measure(context, claim);
        break;
      } catch (const MapDiverged& diverged) {
        const std::optional<int> N = context.step_count_of(diverged.h);
        std::vector<int> finished;
        for (int M : context.step_counts())
          if (!N || M != *N) finished.push_back(M);
        if (!N || finished.size() < 2) {
          claim = diverged_without_verdict(context, diverged, diverged_runs);
          return claim;
        }
        diverged_runs.push_back({*N, diverged.h, diverged.what()});
        context.finished_steps = finished;
        claim = result();
      } catch (const NonFiniteMeasurement& non_finite) {  // a NaN or ∞ where a number was measured
        errs(claim, "non_finite_measurement", non_finite, "none: the measurement was not a finite number");
        return claim;
      } catch (const UnmeasurableJacobian& unmeasurable) {  // the other claims are judged
        errs(claim, "unmeasurable_jacobian", unmeasurable, "none: the map's Jacobian could not be measured");
        return claim;
      } catch (const ClaimNotApplicable& refused) {
        if (context.spec.claims.size() == 1) throw CaseError(context.spec.file, "claims", refused.what());
        errs(claim, "refused", refused, "none: the claim does not apply to this case");
        claim.explanation = std::string("refused (the case's other claims are judged): ") + refused.what();
        return claim;
      }
    }
    if (!diverged_runs.empty()) judge_finished_runs(context, claim, diverged_runs);
    return claim;
  }

  // A message quoted in an explanation: its start (what diverged) and its end (the number and
  // the bound) kept, the middle — a request's long list of numbers — cut; the whole is in the
  // evidence.
  static std::string middle_cut(const std::string& text, std::size_t at_most = 320) {
    if (text.size() <= at_most) return text;
    std::size_t head = at_most / 2, tail = text.size() - at_most / 2;
    while (head > 0 && (static_cast<unsigned char>(text[head]) & 0xC0) == 0x80) --head;
    while (tail < text.size() && (static_cast<unsigned char>(text[tail]) & 0xC0) == 0x80) ++tail;
    return text.substr(0, head) + " … " + text.substr(tail);
  }

  // A run of the sweep in words: "N = 400 (h = 0.0025)".
  template <LagrangianSystem System>
  static std::string run_words(const CaseContext<System>& context, int N) {
    return "N = " + std::to_string(N) + " (h = " + to_decimal<typename System::Scalar>(context.final_time / N, 6) + ")";
  }

  // The claim judged on the runs that finished. A run that diverged at a step coarser than every
  // finished one is an honest method beyond its stability (the finished, finer runs decide); a
  // run that diverged at a step finer than one that finished is not what a convergent map does —
  // its runs approach the flow as h falls — so such a claim does not pass: a failure of the
  // finished runs stands, a pass becomes inconclusive.
  template <LagrangianSystem System>
  static void judge_finished_runs(const CaseContext<System>& context, ClaimResult& claim,
                                  const std::vector<DivergedRun>& diverged_runs) {
    const std::vector<int>& finished = context.step_counts();
    std::string finished_text, diverged_text;
    for (int N : finished) finished_text += (finished_text.empty() ? "" : ", ") + std::to_string(N);
    bool finer_diverged = false;
    nlohmann::json record = nlohmann::json::array();
    for (const auto& [N, h, why] : diverged_runs) {
      diverged_text += (diverged_text.empty() ? "" : "; ") + run_words(context, N) + ": " + middle_cut(why);
      finer_diverged = finer_diverged || N > finished.front();
      record.push_back({{"N", N}, {"h", to_decimal<typename System::Scalar>(context.final_time / N, 8)}, {"message", why}});
    }
    claim.evidence["divergence"] = {{"diverged", record}, {"judged_on_steps", finished}};
    const std::string judged = "judged on the runs that finished (N = " + finished_text + "); the run at " +
                               diverged_text + " diverged";
    if (finer_diverged && claim.verdict == "pass") {
      claim.verdict = "inconclusive";
      claim.explanation = "the runs that finished (N = " + finished_text + ") pass, but the map diverged at " +
                          diverged_text + ", a step finer than one whose run finished: a convergent map's runs "
                          "approach the flow as h falls; to decide: find why that run left the problem's scale "
                          "(its message names the request), then run the sweep again";
      return;
    }
    claim.explanation = judged + "; " + claim.explanation;
  }

  // No verdict: the runs diverged where too few others are left to judge (or at a step outside the
  // sweep): the first divergence quoted, every step that diverged and what is left named.
  template <LagrangianSystem System>
  static ClaimResult diverged_without_verdict(const CaseContext<System>& context, const MapDiverged& diverged,
                                              std::vector<DivergedRun> runs) {
    ClaimResult claim = result();
    claim.verdict = "inconclusive";
    const std::optional<int> last = context.step_count_of(diverged.h);
    runs.push_back({last.value_or(0), diverged.h, diverged.what()});
    std::string left, steps;
    for (int N : context.step_counts())
      if (last != N) left += (left.empty() ? "" : ", ") + std::to_string(N);
    for (const auto& run : runs)
      if (run.N > 0) steps += (steps.empty() ? "" : ", ") + run_words(context, run.N);
    claim.explanation = "the run diverged at h = " + runs.front().h + ": " + middle_cut(runs.front().why) +
                        (runs.size() > 1 ? "; runs diverged at " + steps : std::string()) +
                        (left.empty() ? std::string() : "; the other step counts (N = " + left + ") are too few to judge") +
                        "; to decide: steps small enough for the map to stay within the problem's scale (step counts "
                        "larger than those that diverged), or a map that does not diverge";
    nlohmann::json record = nlohmann::json::array();
    for (const auto& run : runs) record.push_back({{"N", run.N}, {"h", run.h}, {"message", run.why}});
    claim.evidence["divergence"] = {{"h", runs.front().h}, {"message", runs.front().why}, {"diverged", record}};
    return claim;
  }

  // The claim as `error` for a measurement that cannot be trusted: the cause as its explanation
  // and under `key` in the evidence, and what it could have caught (nothing, and why).
  static void errs(ClaimResult& claim, const char* key, const std::exception& cause, const char* limit) {
    claim = result();
    claim.verdict = "error";
    claim.explanation = cause.what();
    claim.evidence[key] = cause.what();
    claim.detection_limit = limit;
  }

  // The prediction for the claim's main series: the theorem's order, or the
  // exact order the case declares for this claim.
  template <LagrangianSystem System>
  static OrderPrediction predicted(const CaseContext<System>& context) {
    return context.predict(Derived::id, *Derived::theorem_order(context));
  }
};

// `measure(h)` at every h of the sweep, reporting "<what> at h = …" as it goes.
template <LagrangianSystem System, class Measure>
std::vector<typename System::Scalar> measure_each_step(const CaseContext<System>& context, const std::string& what,
                                                       Measure&& measure) {
  using T = typename System::Scalar;
  std::vector<T> values;
  for (const T& h : context.steps()) {
    context.report(what + " at h = " + to_decimal<T>(h, 6));
    values.push_back(measure(h));
  }
  return values;
}

// A series over the case's sweep, fitted with `floors` (the case's, reference included, unless
// given) and its options, and judged against `predicted` (none: fitted and shown, not judged).
template <LagrangianSystem System>
Series sweep_series(const CaseContext<System>& context, const std::string& label,
                    const std::vector<typename System::Scalar>& error,
                    std::optional<OrderPrediction> predicted,
                    std::optional<Floor<typename System::Scalar>> floors = std::nullopt) {
  return make_series(label, context.steps(), error, floors ? *floors : context.floors(),
                     predicted ? std::optional<double>(predicted->order) : std::nullopt,
                     predicted && predicted->exact, context.order_tolerance, context.fit_options);
}

// Identities judge scaling too: a defect that falls with h like a power of h is truncation,
// not rounding, whatever its size. Given each h's value and its rounding unit (what one
// rounding of the computation is worth there), the values more than `above` units at two or
// more h, each pair of consecutive ones falling at pairwise order >= 1 (in decreasing h), are
// truncation: the description says so; empty when they are not.
template <class T>
std::string truncation_scaling(const std::vector<T>& h, const std::vector<T>& value,
                               const std::vector<T>& unit, double above) {
  using std::log;
  std::vector<std::size_t>
      resolved;  // indices above the rounding, in the sweep's (decreasing h) order
  for (std::size_t i = 0; i < value.size(); ++i)
    if (unit[i] > 0 && value[i] > T(above) * unit[i]) resolved.push_back(i);
  if (resolved.size() < 2) return "";
  std::string orders;
  for (std::size_t k = 0; k + 1 < resolved.size(); ++k) {
    const std::size_t a = resolved[k], b = resolved[k + 1];
    const T order = log(T(value[a] / value[b])) / log(T(h[a] / h[b]));
    if (!(order >= 1)) return "";
    orders += (orders.empty() ? "" : ", ") + format_scalar(order, 3);
  }
  return "at " + std::to_string(resolved.size()) + " step sizes the defect is more than " +
         format_scalar(above) + " rounding units and falls with h at pairwise orders " + orders +
         ": a defect that falls like a power of h is truncation, not rounding";
}

// The size of the terms each momentum component p_i = ∂L/∂w_i is made of, max(|p_i|, |(M w)_i|,
// |(∂L/∂w − M w)_i|): what its rounding scales with, however small p_i is (a vector potential's
// p_x = v_x − B·y of terms near 0.8). NaN where a term is.
template <LagrangianSystem System>
VectorOf<System> momentum_term_sizes(const System& system, const VectorOf<System>& q, const VectorOf<System>& w) {
  using T = typename System::Scalar;
  using std::abs;
  const auto d = lagrangian_derivatives(system, q, w);
  const VectorOf<System> kinetic = d.d2L_dw2 * w;
  VectorOf<System> size = kinetic;
  for (int i = 0; i < size.size(); ++i)
    size[i] = nan_max(T(abs(d.dL_dw[i])), nan_max(T(abs(kinetic[i])), T(abs(T(d.dL_dw[i] - kinetic[i])))));
  return size;
}

// An identity checked at each h against its own tolerance: the measured values
// as a series (not fitted against a prediction), the verdict `holds` stated
// in words, and a row per h in the evidence under "per_step".
template <class T>
struct PerStepCheck {
  std::vector<T> values;
  bool holds = true;
  nlohmann::json rows = nlohmann::json::array();
  std::string
      scaling_failure;  // truncation_scaling's finding, when the values fall like a power of h
  std::string scaling_limit;  // what the scaling test would have caught
  // Beyond the tolerance, but in a way the evidence cannot tell from rounding: why, and what
  // would decide (the claim is then inconclusive, not failed).
  struct Undecided {
    std::string why, to_decide;
  };
  Undecided undecided;
  std::vector<T> tolerances;
  T smallest_tolerance = 0, largest_tolerance = 0;
  // The step that failed by the most (value / tolerance largest), and how many failed.
  struct Worst {
    T h = 0, value = 0, tolerance = 0;
    int failed = 0;
  };
  Worst worst;

  // Where the check failed, for a failing verdict's explanation: the largest excess, with its
  // h and tolerance, and how many of the steps failed.
  std::string worst_text() const {
    if (worst.failed == 0) return "";
    return "at h = " + format_scalar(worst.h, 4) + " it measured " + format_scalar(worst.value, 3) +
           " against the tolerance " + format_scalar(worst.tolerance, 3) + " (" +
           std::to_string(worst.failed) + " of " + std::to_string(values.size()) +
           " step sizes beyond their tolerance; each in the per-step evidence)";
  }

  // What the check could have caught: a value above the tolerance at its h.
  std::string detection_limit() const {
    if (tolerances.empty()) return "";
    return "a value above " + format_scalar(smallest_tolerance) +
           (largest_tolerance > smallest_tolerance ? " … " + format_scalar(largest_tolerance)
                                                   : std::string()) +
           " (the tolerance at each h) would have failed" +
           (scaling_limit.empty() ? "" : "; so would " + scaling_limit);
  }

  // Records `value` at h against `tolerance`; `row` may carry more columns, and
  // `also` a further condition the step must meet (its columns in `row`).
  // A value or tolerance that is not a finite number throws NonFiniteMeasurement.
  bool add(const T& h, const T& value, const T& tolerance, nlohmann::json row = nlohmann::json::object(),
           bool also = true) {
    require_finite(value, "at h = " + format_scalar(h, 6) + " the measured value");
    require_finite(tolerance, "at h = " + format_scalar(h, 6) + " the tolerance");
    const bool ok = value <= tolerance && also;
    if (!ok) {
      // Compared as value·tolerance' > value'·tolerance: no division by a zero tolerance.
      if (worst.failed == 0 || value * worst.tolerance > worst.value * tolerance)
        worst.h = h, worst.value = value, worst.tolerance = tolerance;
      ++worst.failed;
    }
    if (tolerances.empty() || tolerance < smallest_tolerance) smallest_tolerance = tolerance;
    if (tolerances.empty() || tolerance > largest_tolerance) largest_tolerance = tolerance;
    tolerances.push_back(tolerance);
    holds = holds && ok;
    values.push_back(value);
    row["h"] = to_decimal<T>(h);
    row["measured"] = to_decimal<T>(value);
    row["tolerance"] = to_decimal<T>(tolerance);
    row["holds"] = ok;
    rows.push_back(std::move(row));
    return ok;
  }

  // Adds the series and the per-step evidence to `claim` and concludes it.
  template <LagrangianSystem System>
  void conclude_claim(ClaimResult& claim, const CaseContext<System>& context, const std::string& label,
                      const std::string& held, const std::string& failed) const {
    claim.evidence["per_step"] = rows;
    Series series = sweep_series(context, label, values, std::nullopt);
    series.rule = "per-step-tolerance";
    series.holds = holds && scaling_failure.empty();
    series.explanation = *series.holds ? held : !holds ? failed + ": " + worst_text() : scaling_failure;
    if (!holds && !scaling_failure.empty()) series.explanation += "; and " + scaling_failure;
    if (!holds && scaling_failure.empty() && !undecided.why.empty()) {
      series.inconclusive = true;
      series.to_decide = undecided.to_decide;
      series.explanation = undecided.why + "; to decide: " + undecided.to_decide;
    }
    series.detection_limit = detection_limit();
    claim.series.push_back(series);
    conclude(claim);
  }
};

// A program that computes in double may answer with less than a double's digits (float32 in
// one term, an implicit solver stopped early): its map measures the noise (fourth differences of
// its answers, OneStepMap::answer_noise_in_ulps), and a claim whose tolerance or floor carried that
// noise — symplecticity's per-step tolerance, local-order's floor — is only as strong as the noise
// is small. Recorded in the evidence; a pass with `weak_answer_noise_ulps` or more of a double's ε
// of it — answers with fewer than 12 of a double's 16 digits — is weak (ClaimResult::weakness):
// its tolerance or floor is then 10³ … 10⁴ times a double's, since local-order's floor grows with
// the noise as it is and symplecticity's tolerance with 1.5·r·10⁴/|J|. Measured: correct NumPy
// maps of tests/process and examples/python-integrator 0.25 … 1.1 ε; the midpoint DEL of an
// elastic pendulum in Python floats, Newton stopped at 10^-15 with p' from (q' − q)/h, 1470 ε
// (symplecticity's tolerance raised up to 48 times; not weak); a Verlet whose force is rounded to
// float32 1.5·10⁶ … 2.4·10⁷ ε (weak).
inline constexpr double weak_answer_noise_ulps = 1e4;
template <LagrangianSystem System>
void record_answer_noise(const CaseContext<System>& context, ClaimResult& claim, const std::string& carried_by) {
  if (!context.map) return;
  const std::optional<double> ulps = context.map->answer_noise_in_ulps();
  if (!ulps) return;
  const double relative = *ulps * std::numeric_limits<double>::epsilon();
  const double digits = relative > 0 ? -std::log10(relative) : std::numeric_limits<double>::digits10 + 1;
  claim.evidence["answer_noise"] = {
      {"relative", format_scalar(relative, 3)},
      {"double_ulps", format_scalar(*ulps, 3)},
      {"significant_digits", format_scalar(digits, 2)},
      {"carried_by", carried_by},
      {"rule",
       "the largest spread of the program's answers' rounding, |Δ⁴ y_i| / √70 over fourth differences of its "
       "answers at spacings 10^-8 and 10^-6, relative to max(1, |y_i|); a pass with " +
           format_scalar(weak_answer_noise_ulps, 3) + " or more double ulps of it is weak"}};
  if (claim.verdict == "pass" && *ulps >= weak_answer_noise_ulps)
    claim.weakness = "the program's answers carry noise of " + format_scalar(relative, 2) +
                     " of their size (about " + format_scalar(digits, 2) + " significant digits, not the " +
                     std::to_string(std::numeric_limits<double>::digits10 + 1) + " of a double: " +
                     format_scalar(*ulps, 2) + " times its rounding), and " + carried_by +
                     " carried it: a defect below that noise could not have failed";
}

}  // namespace vivv
