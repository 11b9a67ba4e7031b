// junit.xml for CI dashboards: one <testsuite> per case, one <testcase> per
// claim (classname = case name, name = claim id); a failing claim carries a
// <failure> with its explanation and an evidence summary, a claim in error an
// <error>; every test case's <system-out> holds the evidence summary.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace vivv {

std::string render_junit(const nlohmann::json& report);

// The claim's evidence in a few lines of plain text: source, prediction,
// observed against predicted order per series, points used and dropped.
std::string evidence_summary(const nlohmann::json& claim);

}  // namespace vivv
