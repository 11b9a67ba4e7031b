// The command line of the vivv tool: what its commands share — the exit codes, bad input, the
// options of `vivv run` and the reports they write. One file per command beside this header
// (command_run.cpp, command_report.cpp, command_list.cpp), the options and help texts in
// options.cpp, the --jobs workers, signals and the --max-seconds budget in workers.cpp;
// harness/command_line/main.cpp dispatches. Not part of the library the package installs.
#pragma once

#include <unistd.h>

#include <iosfwd>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/case_file.hpp"
#include "harness/verdicts/baseline.hpp"

namespace vivv::command_line {

constexpr int exit_pass = 0, exit_fail = 1, exit_bad_input = 2;
// A --jobs worker ended by a signal (a crash, the kernel's out-of-memory killer): not the
// input's fault, and no verdict either.
constexpr int exit_crash = 3;
struct WorkerCrash : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// A case that could not run to its end because its map program crashed, hung or broke the
// protocol once the options and case files had been read: recorded in report.json and
// junit.xml (refused, kind "could-not-run"), the other cases keep their results, and the run
// exits 4 — neither a verdict, nor bad input (2, found before anything computes), nor a killed
// worker (3).
constexpr int exit_could_not_run = 4;
struct CouldNotRun : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The message of bad input on stderr, at most 2000 characters of it (a hostile input's value
// would otherwise be echoed whole); exit 2.
int bad_input(const std::string& message);

// --shard I/N: the cases at positions I − 1, I − 1 + N, I − 1 + 2N, ... of the suite.
struct Shard {
  int index = 1, count = 1;
};

struct RunOptions {
  std::vector<std::string> case_files;
  std::string out = "vivv-report";
  std::optional<int> digits;
  std::optional<std::string> scalar;
  int jobs = 1;
  std::optional<Shard> shard;
  std::optional<int> max_seconds;  // --max-seconds: each case's budget of wall time
  bool progress = isatty(STDERR_FILENO);
  // --verbose: the console lists every claim and each pass's detection limit, not only the
  // claims that did not pass.
  bool verbose = false;
  bool refine = false;
  // --keep-going: a case refused as bad input while it runs is recorded as refused, the other
  // cases keep their results, and the run still exits 2.
  bool keep_going = false;
  // --baseline OLD/report.json: each claim's fitted series compared with OLD's (regressed: exit 1).
  std::optional<std::string> baseline;
  double baseline_tolerance = default_baseline_tolerance;
  // --claims a,b: only these of each case's claims run; a case that lists none is skipped and
  // reported as skipped. Empty: every claim of every case.
  std::vector<std::string> claims;
  // --plan: print what each case will compute and hold (harness/command_line/plan.cpp), compute
  // nothing, write no report.
  bool plan = false;
  // --allow-process: cases may start the programs they name (discretization kind "process");
  // --process-timeout: the seconds such a program has for each answer.
  bool allow_process = false;
  double process_timeout = 30;
  // --reference-cache DIR: Taylor reference flows keep their answers there between runs
  // (harness/context/reference_cache.hpp).
  std::optional<std::string> reference_cache;
};

// The default suite: every case file in the source tree's cases/suite, sorted.
std::string default_suite_directory();
std::vector<std::string> default_suite();
// The case file as report.json names it: relative to the source tree when it
// lies inside it (the same bytes from any checkout and working directory),
// else as given on the command line.
std::string report_file_name(const std::string& file);

RunOptions parse_run_options(const std::vector<std::string>& args);
int usage(std::ostream& out, int code);
int run_help(std::ostream& out);

// Runs the cases in up to `jobs` worker processes (MPFR's working precision
// is process-wide in Boost 1.74, so parallel cases need processes, not threads). A worker that
// finished a case asks for the next, and takes one on the same reference flow first, which it
// keeps (harness/context/shared_references.hpp); without --jobs one process keeps the flows the
// cases after it need. Each case's result, in order; under --keep-going a case refused as bad
// input is {"refused": message} (each case then runs in a worker process of its own, so that a
// --max-seconds budget that ends it leaves the others).
std::vector<nlohmann::json> run_all(const std::vector<CaseSpec>& specs, const RunOptions& options);

// `check(spec)` (reading a case file and checking it against the options) under the --max-seconds
// budget of a case: expanding a formula is work the budget covers. Past it, vivv ends with exit 2
// naming the file and the phase, and writes no report.
CaseSpec within_reading_budget(const std::string& file, const RunOptions& options,
                               const std::function<CaseSpec()>& read);

// Before any work: DIR must be a directory vivv can create and write in (`option` names it).
void check_output_directory(const std::string& out, const std::string& option = "--out");
// Writes DIR/report.json, report.html and junit.xml, prints the claims table;
// the exit code of the verdicts.
int write_reports(const std::string& out, const nlohmann::json& report, bool verbose);

int command_run(const std::vector<std::string>& args, const std::string& command_line);

// `vivv run --plan`: each case's work and memory estimate, printed to `out`; exit 0.
int print_plan(std::ostream& out, const std::vector<CaseSpec>& specs, const RunOptions& options);
int command_report(const std::vector<std::string>& args, const std::string& command_line);
int command_list();

}  // namespace vivv::command_line
