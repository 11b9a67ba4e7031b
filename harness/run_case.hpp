// Running one case: MPFR at the case's precision, its system from the
// catalogue, every claim it asks for.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cases/case_file.hpp"
#include "harness/claim_result.hpp"

namespace vivv {

struct CaseResult {
  CaseSpec spec;
  std::string scalar;  // "mpfr"
  int digits = 0;      // decimal digits requested
  int precision_bits = 0;
  std::string reference_method, reference_tolerance, reference_cross_check;
  std::string reference_error_estimate;  // measured at T, from the cross-check
  ReferenceCheck reference_check;
  std::vector<ClaimResult> claims;
  // DESIGN §1.6: bits >= −log2(smallest error) + guard. The smallest error of
  // any order-fitted series, and the guard bits the precision leaves below it.
  std::string smallest_error;
  double guard_bits = 0;
  double seconds = 0;
};

// Runs `spec` in MPFR with `digits` decimal digits (the case's own unless
// overridden). Solver failures, non-regular Lagrangians and declared orders
// below the theorem's (CaseError) propagate as exceptions: they are bad input,
// not verdicts. A reference that misses its own tolerance makes every claim
// "error"; the case's xfail marks turn fail/pass into xfail/xpass.
CaseResult run_case(const CaseSpec& spec, std::optional<int> digits,
                    const std::function<void(const std::string&)>& progress);

}  // namespace vivv
