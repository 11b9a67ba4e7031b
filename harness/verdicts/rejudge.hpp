// vivv report's check that each order verdict follows from its own evidence (docs/reports.md):
// a report merged from shards is only as trustworthy as the shards, so every fitted series is
// fitted and judged again from the step sizes and errors it records, with the rule vivv run used.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace vivv {

// Throws ReportError naming `path`, the case, the claim and the series when a series' recorded
// fit (its observed order, the points it used) differs from the one its h and errors give, or
// when a series the order rule judged (rule "order") is recorded as holding but fails or
// is inconclusive when judged again. Not checked: the other direction (a claim may turn a
// failing series inconclusive, e.g. steps too large for the motion), series judged by another
// rule (lagrangian-order's signed coefficient), and the identity and drift claims' own tests.
void check_series_follow_from_errors(const nlohmann::json& report, const std::string& path);

}  // namespace vivv
