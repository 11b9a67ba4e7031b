// The report model and its renderers: report.json (schema "vivv-report/6",
// documented in reports/SCHEMA.md and reports/schema.json), the console claims
// table, and the report directory (report.json, report.html, junit.xml).
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "reports/results.hpp"

namespace vivv {

inline constexpr const char* report_schema = "vivv-report/6";
// The schemas `vivv report` and `--baseline` read: this one and the two before it (vivv-report/6
// added the kind of a refused case, "could-not-run"; /5 the exact-coefficients rule, local-order
// and evidence fields to /4; every /4 and /5 report is a valid /6 one).
inline bool readable_report_schema(const nlohmann::json& report) {
  if (!report.is_object() || !report.contains("schema")) return false;
  const nlohmann::json& schema = report["schema"];
  return schema == report_schema || schema == "vivv-report/5" || schema == "vivv-report/4";
}
// The schemas readable_report_schema accepts, for messages.
inline constexpr const char* readable_report_schemas =
    "\"vivv-report/6\", \"vivv-report/5\" or \"vivv-report/4\"";

// A refused case (report["refused"]) whose map program crashed, hung or broke the protocol while
// it ran (kind "could-not-run", exit 4), not bad input (kind "bad-input" or none, exit 2).
inline bool could_not_run(const nlohmann::json& refused_entry) {
  return refused_entry.is_object() && refused_entry.value("kind", "") == "could-not-run";
}

struct RunInfo {
  std::string command_line;
  std::string versions;
};

// A report that cannot be read, merged or written: bad input (exit 2).
struct ReportError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The whole report: schema, the verdict summary, the cases and one "run"
// block holding everything that may differ between two runs of the same input
// (command line, versions, wall times). Each case's "seconds" moves into
// run.case_seconds, so the rest is a function of the input and the precision.
nlohmann::json assemble_report(std::vector<nlohmann::json> cases, const RunInfo& run);

// The cases of several reports in one (`vivv report a.json b.json`): each input
// is (file name, report). Throws ReportError on a schema other than
// report_schema or a case name that occurs twice. The run block records each
// input's own run block under "merged_from".
nlohmann::json merge_reports(const std::vector<std::pair<std::string, nlohmann::json>>& inputs,
                             const RunInfo& run);

// Reads a report.json; ReportError if it is not JSON or not of report_schema.
nlohmann::json read_report(const std::string& path);

// report.csv: every point of every series, one row each (case, claim, series, h, N, error, floor,
// and the run's L evaluations and seconds at that N), for a user's own plots.
std::string render_csv(const nlohmann::json& report);

// Writes DIR/report.json, DIR/report.html, DIR/junit.xml and DIR/report.csv: all rendered
// first, then each written atomically, so a failure leaves none half-written. Bytes that are
// not UTF-8 in any string of `report` are written as U+FFFD. Returns the four paths.
std::vector<std::string> write_report_directory(const std::string& directory,
                                                const nlohmann::json& report);

// One case as JSON; worker processes send their case in this form.
nlohmann::json case_json(const CaseResult& result);

// Writes `content` to `path` through a temporary file and a rename, so a
// reader never sees a half-written report.
void write_atomically(const std::string& path, const std::string& content);

// Writes `content` to a new file `path`: created exclusively, never through a
// symbolic link (O_CREAT | O_EXCL | O_NOFOLLOW), mode 0600.
void write_exclusively(const std::string& path, const std::string& content);

// How much of the run the console shows: the claims that did not pass, why, and the summary
// (terse, vivv run's default), or every claim and each pass's detection limit too (verbose).
enum class ConsoleDetail { terse, verbose };

// The aligned claims table: case, claim, verdict, observed and predicted order — every claim, or
// (terse) only those that did not pass, with a line counting the passes left out — then why each
// claim that did not pass did not, what each pass could have caught (verbose), and the summary;
// control characters shown escaped (terminal_safe).
void print_claims_table(std::ostream& out, const nlohmann::json& report,
                        ConsoleDetail detail = ConsoleDetail::verbose);

// Every verdict a claim can have, in the order summaries list them.
const std::vector<std::string>& verdict_names();

// Overall verdict counts from a report: {"pass": n, "fail": n, "error": n, "xfail": n, "xpass": n}.
nlohmann::json verdict_counts(const nlohmann::json& cases);

// "3 pass, 0 fail, 0 error, 1 xfail, 0 xpass".
std::string summary_text(const nlohmann::json& summary);

// A run succeeds when no claim fails, errs, or passes although marked as a known failure.
bool run_succeeded(const nlohmann::json& summary);

// Whether a case's order_tolerance is the default (then reports need not show it).
bool default_tolerance(const std::string& tolerance);

}  // namespace vivv
