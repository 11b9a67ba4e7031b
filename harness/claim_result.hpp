// What a claim returns: its verdict and the evidence behind it (docs/claims.md).
//
// Results are plain data, independent of the scalar type: every number that
// came out of a computation in the working precision is kept as a decimal
// string, so the report loses nothing.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "harness/order_fit.hpp"

namespace vivv {

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
  std::string explanation;
};

struct ClaimResult {
  std::string id;
  std::string source;      // where the theory states it (paper / Marsden–West)
  std::string prediction;  // what the theory predicts, in words
  // "pass", "fail", "error" (the measurement cannot be trusted), or for a claim
  // the case marks as a known failure "xfail" (it failed) / "xpass" (it passed).
  std::string verdict;
  std::string explanation; // why, in one or two sentences
  std::string xfail_reason;  // the case's reason, when it marks the claim as a known failure
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
