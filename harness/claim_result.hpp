// How a claim's verdict is settled beyond its own measurement: a reference that
// misses its tolerance, a case's known failures. The result types themselves are
// the report model, reports/results.hpp.
#pragma once

#include <string>

#include "reports/results.hpp"

namespace vivv {

// A reference that misses its own promised tolerance voids every claim
// measured against it: each verdict becomes "error", the numbers in the
// explanation, the verdict it would have had kept in the evidence.
inline void apply_reference_check(std::vector<ClaimResult>& claims, const ReferenceCheck& reference) {
  if (reference.holds) return;
  for (auto& claim : claims) {
    claim.evidence["verdict_before_reference_check"] = claim.verdict;
    claim.verdict = "error";
    claim.explanation = "the reference flow misses its own tolerance: its cross-check estimates the error at T as " +
                        reference.error_estimate + ", above the " + reference.allowed + " that its promised tolerance " +
                        reference.tolerance + " (with the check's own) allows; no verdict measured against it "
                        "can be trusted";
  }
}

// A claim the case marks as a known failure: a failing verdict becomes
// "xfail", a passing one "xpass" (a known failure that went away must be looked
// at: it fails the run). "error" stays "error".
inline void apply_expected_failure(ClaimResult& claim, const std::string& reason) {
  claim.xfail_reason = reason;
  if (claim.verdict == "fail") {
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
