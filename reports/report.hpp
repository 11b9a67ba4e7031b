// The report model and its renderers: report.json (schema "vivv-report/1",
// documented in reports/SCHEMA.md) and the console claims table.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "harness/run_case.hpp"

namespace vivv {

inline constexpr const char* report_schema = "vivv-report/1";

struct RunInfo {
  std::string command_line;
  std::string versions;
};

// The whole report: schema, a "run" metadata block, the verdict summary and the cases.
nlohmann::json assemble_report(const std::vector<nlohmann::json>& cases, const RunInfo& run);

// One case as JSON; worker processes send their case in this form.
nlohmann::json case_json(const CaseResult& result);

// Writes `content` to `path` through a temporary file and a rename, so a
// reader never sees a half-written report.
void write_atomically(const std::string& path, const std::string& content);

// The aligned claims table: case, claim, verdict, observed and predicted order.
void print_claims_table(std::ostream& out, const nlohmann::json& report);

// Overall verdict counts from a report: {"pass": n, "fail": n, "error": n}.
nlohmann::json verdict_counts(const nlohmann::json& cases);

}  // namespace vivv
