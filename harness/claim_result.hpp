// What a claim returns: its verdict and the evidence behind it (DESIGN §1.5, §3).
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
  std::string verdict;     // "pass", "fail" or "error"
  std::string explanation; // why, in one or two sentences
  std::vector<Series> series;  // series[0] is the claim's main measurement
  nlohmann::json evidence = nlohmann::json::object();
};

// An empty result for the claim `id`, verdict still to be decided.
inline ClaimResult claim_result_for(std::string id, std::string source, std::string prediction) {
  ClaimResult claim;
  claim.id = std::move(id);
  claim.source = std::move(source);
  claim.prediction = std::move(prediction);
  return claim;
}

}  // namespace vivv
