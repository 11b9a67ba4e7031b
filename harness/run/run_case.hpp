// Running one case: MPFR at the case's precision, its system from the
// catalogue, every claim it asks for.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cases/case_file.hpp"
#include "harness/verdicts/rejudge.hpp"
#include "reports/results.hpp"

namespace vivv {

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
// order is within the tolerance of it but not within a quarter of it (more data
// decides), and its smallest h
// not at the floor — in words; none when all have.
// With --refine, the fit also drops leading points whose pairwise order is
// more than tolerance/4 from the finest (FitOptions::asymptote_tolerance).
std::optional<std::string> unsettled_series(const std::vector<ClaimResult>& claims, double tolerance);

// The registered claims' series rules (registered_series_rules), for re-judging a report
// without including every claim.
ClaimSeriesRules claim_series_rules();

}  // namespace vivv
