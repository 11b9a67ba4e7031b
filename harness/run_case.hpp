// Running one case: MPFR at the case's precision, its system from the
// catalogue, every claim it asks for.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cases/case_file.hpp"
#include "harness/claim_result.hpp"

namespace vivv {

// The step sweep a case actually used: with --refine (or "refine": true) h is
// halved until every order-fitted series settles, within a stated budget.
struct SweepRecord {
  static constexpr int max_refinements = 4;     // at most 4 halvings of h beyond the case's own sweep
  static constexpr long max_steps = 1000000;    // and N never beyond the case file's limit
  bool refine = false;
  std::vector<int> requested_steps;  // as the case file gives them
  std::string stopped;               // why refinement stopped (empty without --refine)
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
  std::vector<ClaimResult> claims;
  SweepRecord sweep;
  // docs/theory.md (observed orders): bits >= −log2(smallest error) + guard. The smallest error of
  // any order-fitted series, and the guard bits the precision leaves below it.
  std::string smallest_error;
  double guard_bits = 0;
  double seconds = 0;
};

// Runs `spec` in its scalar (MPFR with `digits` decimal digits, the case's own
// unless overridden). Solver failures, non-regular Lagrangians and declared orders
// below the theorem's (CaseError) propagate as exceptions: they are bad input,
// not verdicts. A reference that misses its own tolerance makes every claim
// "error"; the case's xfail marks turn fail/pass into xfail/xpass.
// With `refine` (or the case's "refine": true) the sweep grows by N → 2N until
// unsettled_series finds nothing, or the budget of SweepRecord is spent.
CaseResult run_case(const CaseSpec& spec, std::optional<int> digits, bool refine,
                    const std::function<void(const std::string&)>& progress);

// The first order-fitted series that has not settled — its two finest
// pairwise orders and its fitted order not all within tolerance/4 of each
// other, or an exact prediction outside the fit's interval while the finest
// order is within the tolerance of it (more data decides), and its smallest h
// not at the floor — in words; none when all have.
// With --refine, the fit also drops leading points whose pairwise order is
// more than tolerance/4 from the finest (FitOptions::asymptote_tolerance).
std::optional<std::string> unsettled_series(const std::vector<ClaimResult>& claims, double tolerance);

}  // namespace vivv
