// The result model: what a run of vivv produced, as plain data. harness/
// computes it, reports/ renders it (report.json, HTML, JUnit, the console
// table); this header depends on neither, only on the case it describes.
//
// Results are independent of the scalar type: every number that came out of
// a computation in the working precision is kept as a decimal string, so the
// report loses nothing.
#pragma once

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cases/case_file.hpp"

namespace vivv {

// A point left out of the fit: its index into the caller's arrays and why.
using DroppedPoint = std::pair<int, std::string>;

// The observed order of a sweep, with the evidence for it.
struct OrderFit {
  bool ok = false;               // false if fewer than 2 usable points (then `reason` explains)
  std::string reason;            // empty when ok
  double order = NAN;            // least-squares slope of log e against log h over the used points
  double standard_error = NAN;   // of the slope; NaN with exactly 2 points
  double confidence_low = NAN;   // order ∓ t·standard_error (Student's t, n − 2 degrees of
  double confidence_high = NAN;  // freedom); ∓inf with exactly 2 points
  double confidence = NAN;       // the level of that interval (FitOptions::confidence)
  double log_constant = NAN;     // intercept: e ≈ C h^order, log C
  std::vector<int> sorted;       // every index, by decreasing h (ties in the caller's order)
  std::vector<double> pairwise_orders;  // between sorted[k] and sorted[k+1]; NaN where undefined
  std::vector<double> log_h;            // log h of sorted[k] (the verdict's detection limit)
  // How many of `sorted`, from the largest h, lie above the floor (none masked or dropped at it):
  // the points whose pairwise orders show where the sweep is heading.
  int above_floor = 0;
  std::vector<int> used;                // indices used in the fit, ascending
  // The last FitOptions::finest_orders pairwise orders between consecutive used points
  // (largest h first): the small-h end, where an asymptotic statement lives.
  std::vector<double> finest_orders;
  std::vector<DroppedPoint> dropped;    // indices left out and why, ascending by index
  std::vector<std::string> notes;       // what the reader should know but no rule acted on
};

// One measured quantity over the step sweep, with its fitted order.
struct Series {
  std::string label;               // what was measured, e.g. "|q_N − q(T)|"
  std::vector<std::string> h;      // step sizes, decimal strings
  std::vector<std::string> error;  // measured errors, decimal strings
  std::string floor;               // error level treated as round-off / reference floor
  std::optional<OrderFit> fit;
  std::optional<double> predicted_order;
  bool exact_order = false;        // predicted order is exact, not a lower bound
  std::optional<bool> holds;       // verdict of this series alone
  // Which rule decided `holds` (reports/SCHEMA.md): "order" (the fitted and finest pairwise orders
  // against the prediction), "floor" (fewer than two errors above the floor), "none" (not judged),
  // or the claim's own rule ("signed-coefficient", "exact-coefficients", "energy-drift",
  // "per-step-tolerance", "does-not-converge", "step-size-search"). `vivv report` judges "order" series again.
  std::string rule = "none";
  // The evidence cannot decide (holds is then false): not yet asymptotic, a floor set by the
  // reference or the precision, an interval too wide. `to_decide` says what would decide it.
  bool inconclusive = false;
  std::string to_decide;
  std::string explanation;
  // The smallest deviation from the prediction this series would have shown as a failure, in
  // words: "orders below 1.8 fail; the fit resolves the order to ±0.05" (empty when not judged).
  std::string detection_limit;
  // Where the floor comes from: the rounding of the working precision over the sweep, or the
  // reference's promised accuracy (the larger of the two sets it; both decimal strings).
  std::string rounding_floor, reference_floor;
};

struct ClaimResult {
  std::string id;
  std::string source;      // where the theory states it (paper / Marsden–West)
  std::string prediction;  // what the theory predicts, in words
  // "pass", "fail", "inconclusive" (the evidence cannot decide: `explanation` says what would),
  // "error" (the measurement cannot be trusted), or for a claim the case marks as a known
  // failure "xfail" (it failed) / "xpass" (it passed).
  std::string verdict;
  std::string explanation; // why, in one or two sentences
  int decisive_series = 0;  // the series that decided the verdict (a failing or inconclusive one)
  std::string detection_limit;  // what this claim could have caught (the decisive series')
  std::string xfail_reason;  // the case's reason, when it marks the claim as a known failure
  // A pass much weaker than the scalar promises: its tolerance or floor carried noise a program's
  // answers showed, far above the rounding of the precision they are sent in (why, in words;
  // empty otherwise). Listed in the console beside failures; --baseline regresses a claim that
  // was not weak before.
  std::string weakness;
  // Wall time of the claim's evaluation: its judgement and the sweep runs it was the first of the
  // case's claims to need (a later claim reuses them); under --refine, summed over the rounds.
  // In the report's run block (run.claim_seconds), which two runs may differ in.
  double seconds = 0;
  std::vector<Series> series;  // series[0] is the claim's main measurement
  nlohmann::json evidence = nlohmann::json::object();
};

// What the case's reference flow promises and what its own cross-check measured.
struct ReferenceCheck {
  std::string tolerance;       // promised: |error_i| <= tolerance·(1 + |y_i|)
  std::string error_estimate;  // measured at T by the independent cross-check
  std::string allowed;         // (tolerance + the check's own)·(1 + |F_T(v)|_max): what the estimate may reach
  bool holds = true;
};

// The cross-check of vivv's derivatives from values of L and L_d alone
// (harness/run/derivative_check.hpp): residuals and what each may reach, decimal strings; the DEL's
// empty for a case that is not Q×Q. A check that fails voids every claim of the case.
struct DerivativeCheck {
  std::string euler_lagrange_residual, euler_lagrange_allowed;
  std::string del_residual, del_allowed;
  bool holds = true;
  std::string explanation;  // what failed, empty when it holds
};

// The step sweep a case actually used: with --refine (or "refine": true) h is
// halved until every order-fitted series settles, within a stated budget.
struct SweepRecord {
  static constexpr int max_refinements = 4;     // at most 4 halvings of h beyond the case's own sweep
  static constexpr long max_steps = 1000000;    // and N never beyond the case file's limit
  bool refine = false;
  std::vector<int> requested_steps;  // as the case file gives them
  std::string stopped;               // why refinement stopped (empty without --refine)
};

// What one run of the sweep (N steps) cost: the evaluations of L it made (deterministic: the
// work-precision diagram's axis) and its wall time.
struct RunCost {
  long lagrangian_evaluations = 0;
  double seconds = 0;
  // A program's map: the evaluations its answers say it made (extension "evaluations"), if it said.
  std::optional<long> program_evaluations;
};

struct CaseResult {
  CaseSpec spec;
  std::string scalar;          // "double", "long double", "float128" or "mpfr"
  std::string implementation;  // how L was run: compiled, a formula, a catalogue system's formula twin
  std::string formula;         // the formula of L that ran, if one did
  int digits = 0;      // decimal digits requested
  int precision_bits = 0;
  std::string reference_method, reference_tolerance, reference_cross_check;
  std::string reference_error_estimate;  // measured at T, from the cross-check
  ReferenceCheck reference_check;
  DerivativeCheck derivative_check;
  std::vector<ClaimResult> claims;
  SweepRecord sweep;
  // docs/theory.md (observed orders): bits >= −log2(smallest error) + guard. The smallest error of
  // any order-fitted series, and the guard bits the precision leaves below it.
  std::string smallest_error;
  double guard_bits = 0;
  double seconds = 0;
  std::map<int, RunCost> run_costs;  // by N
};

}  // namespace vivv
