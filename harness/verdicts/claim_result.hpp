// How a claim's verdict is settled beyond its own measurement: a reference that
// misses its tolerance, a case's known failures. The result types themselves are
// the report model, reports/results.hpp.
#pragma once

#include <cmath>
#include <cstdlib>

#include <cstdio>
#include <string>
#include <vector>

#include "reports/results.hpp"

namespace vivv {

// A reference that misses its own promised tolerance voids every claim
// measured against it: each verdict becomes "error", the numbers in the
// explanation, the verdict it would have had kept in the evidence.
inline void apply_reference_check(std::vector<ClaimResult>& claims, const ReferenceCheck& reference) {
  if (reference.holds) return;
  // A finite estimate: the claims were judged against floors raised to 1000 × it (CaseContext::
  // floors, reference_error_at_T), so a verdict on errors far above the reference's own stands and
  // one near it is at the floor; each claim says so. Only a cross-check that measured nothing
  // finite voids them.
  char* end = nullptr;
  const long double estimate = std::strtold(reference.error_estimate.c_str(), &end);
  if (end != reference.error_estimate.c_str() && std::isfinite(estimate)) {
    for (auto& claim : claims)
      claim.evidence["reference_missed_its_tolerance"] = {
          {"error_estimate_at_T", reference.error_estimate},
          {"allowed", reference.allowed},
          {"rule",
           "the reference's cross-check estimates its error at T above what its promised tolerance " +
               reference.tolerance +
               " allows: every floor that rests on the reference was raised to 1000 x that estimate, so "
               "nothing below it was judged against the reference"}};
    return;
  }
  for (auto& claim : claims) {
    claim.evidence["verdict_before_reference_check"] = claim.verdict;
    claim.verdict = "error";
    claim.detection_limit = "none: nothing measured against a reference whose error is unknown can be told "
                            "from that reference's error";
    claim.explanation = "the reference flow's cross-check estimates the error at T as " + reference.error_estimate +
                        ", not a finite number: no verdict measured against the reference can be trusted";
  }
}

// A failed derivative-free cross-check (harness/run/derivative_check.hpp) voids every claim of the
// case as a failed reference does: the flow or the DEL solved equations other than L's.
inline void apply_derivative_check(std::vector<ClaimResult>& claims, const DerivativeCheck& check) {
  if (check.holds) return;
  for (auto& claim : claims) {
    claim.evidence["verdict_before_derivative_check"] = claim.verdict;
    claim.verdict = "error";
    claim.detection_limit = "none: what was measured solved other equations than L's";
    claim.explanation =
        "vivv's derivatives of L disagree with differences of its values: " + check.explanation +
        "; the reference flow or the DEL solved other equations than L's, and no verdict "
        "measured with them can be trusted";
  }
}

// An order with four significant digits.
inline std::string order_text(double order) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", order);
  return buffer;
}

// A claim the case marks as a known failure: a failing verdict becomes "xfail" when it is the
// failure the case states (for an order, the decisive series' fitted order inside the stated
// range), a passing one "xpass" (a known failure that went away must be looked at: it fails the
// run). Any other failure stays "fail"; "inconclusive" and "error" stay as they are.
inline void apply_expected_failure(ClaimResult& claim, const ExpectedFailure& expected) {
  const std::string& reason = expected.reason;
  claim.xfail_reason = reason;
  if (expected.observed_order)
    claim.evidence["xfail_expects_observed_order"] = {expected.observed_order->first,
                                                      expected.observed_order->second};
  if (claim.verdict == "fail") {
    if (expected.observed_order && !claim.series.empty()) {
      const Series& decisive = claim.series[static_cast<std::size_t>(claim.decisive_series)];
      const double low = std::stod(expected.observed_order->first),
                   high = std::stod(expected.observed_order->second);
      const bool as_expected = decisive.fit && decisive.fit->ok && decisive.fit->order >= low &&
                               decisive.fit->order <= high;
      if (!as_expected) {
        claim.explanation =
            "marked as a known failure (" + reason + ") with an observed order in [" +
            expected.observed_order->first + ", " + expected.observed_order->second +
            "], but it fails otherwise — " +
            (decisive.fit && decisive.fit->ok ? "observed order " + order_text(decisive.fit->order)
                                              : std::string("no observed order")) +
            ": " + claim.explanation;
        return;
      }
    }
    claim.verdict = "xfail";
    claim.explanation = "expected failure (" + reason + "): " + claim.explanation;
  } else if (claim.verdict == "pass") {
    claim.verdict = "xpass";
    claim.explanation = "marked as a known failure (" + reason +
                        ") but every prediction holds: look at what changed, then drop the xfail";
  }
}

// An empty result for the claim `id`, verdict still to be decided.
inline ClaimResult claim_result_for(std::string id, std::string source, std::string prediction) {
  ClaimResult claim;
  claim.id = std::move(id);
  claim.source = std::move(source);
  claim.prediction = std::move(prediction);
  return claim;
}

}  // namespace vivv
