// vivv run --baseline OLD/report.json: each claim's fitted series compared with the same case's
// and claim's in an earlier report (docs/case-files.md (regression baselines)). An order can hold
// while the error constant doubles; a project that tests its integrator in CI wants to see that.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace vivv {

// The default allowed growth of the leading error constant: 10 %.
inline constexpr double default_baseline_tolerance = 0.1;

// Compares every series the order rule judged in `report` (rule "order") with the series of the
// same label, claim and case in `baseline` and records the outcome: in each compared claim a "baseline" object
// (status "regressed", "improved", "unchanged" or "not compared", the orders and the constant's
// ratio per series, and why), and in report["run"]["baseline"] the baseline's path, the
// tolerance and the counts. A series regresses when its observed order dropped below the
// baseline's by more than the case's order tolerance, or when its leading error constant grew by
// more than `constant_tolerance` (a fraction); the constant's ratio is measured at the step sizes
// both fits used, as the geometric mean of error_now / error_before there (with the order
// unchanged, C_now / C_before at every h).
void compare_with_baseline(nlohmann::json& report, const nlohmann::json& baseline, const std::string& baseline_path,
                           double constant_tolerance);

// The number of regressed claims recorded by compare_with_baseline (0 without a baseline).
int regressed_claims(const nlohmann::json& report);

}  // namespace vivv
