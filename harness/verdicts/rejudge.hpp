// vivv report's check that each order verdict follows from its own evidence (docs/reports.md):
// a report merged from shards is only as trustworthy as the shards, so every fitted series is
// fitted and judged again from the step sizes and errors it records, with the rule vivv run used.
#pragma once

#include <map>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

namespace vivv {

// The rules each claim's series may be decided by, by claim id: the claims' own declarations
// (registered_series_rules() in harness/claims/registry.hpp), never the report's word.
using ClaimSeriesRules = std::map<std::string, std::set<std::string>>;

// Throws ReportError naming `path`, the case, the claim and the series when
// - a claim is not one of `rules`, or a series names a rule its claim never uses;
// - a series' h and error differ in length, or its recorded fit (observed order, the points it
//   used) differs from the one its h and errors give;
// - a fitted series names "order" with fewer than two errors above its floor, or "floor" with
//   two or more (the data decide which of the two rules applies);
// - a series the order rule judged (rule "order", or no rule recorded and a predicted order in a
//   claim that fits orders) is recorded as holding but fails or is inconclusive judged again;
// - a claim that decides by series passes with every series marked "none" (not judged).
// Not checked: the other direction (a claim may turn a failing series inconclusive, e.g. steps
// too large for the motion), and the other rules' own tests (lagrangian-order's signed
// coefficient, the identities' per-step tolerances, precision-leak's two floors).
void check_series_follow_from_errors(const nlohmann::json& report, const std::string& path,
                                     const ClaimSeriesRules& rules);

// read_report(path) and check_series_follow_from_errors: every check `vivv report` makes of a
// report it reads, which --baseline makes too before any case computes.
nlohmann::json read_judged_report(const std::string& path, const ClaimSeriesRules& rules);

}  // namespace vivv
