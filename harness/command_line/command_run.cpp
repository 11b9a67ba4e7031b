// `vivv run`: read and check every case, compute the selected ones, compare with a baseline, write
// the reports.
#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "harness/verdicts/baseline.hpp"
#include "cases/case_reader.hpp"
#include "harness/command_line/command_line.hpp"
#include "harness/process/program.hpp"
#include "harness/verdicts/rejudge.hpp"
#include "harness/run/run_case.hpp"
#include "harness/library/version.hpp"
#include "reports/report.hpp"
#include "core/platform/signals.hpp"

namespace fs = std::filesystem;

namespace vivv::command_line {

// Before any work: DIR must be a directory vivv can create and write in.
void check_output_directory(const std::string& out, const std::string& option) {
  std::error_code error;
  if (fs::exists(out, error) && !fs::is_directory(out, error))
    throw BadInput(option + ": '" + out + "' exists and is not a directory");
  fs::create_directories(out, error);
  if (error) throw BadInput(option + ": cannot create '" + out + "': " + error.message());
  // The four files are replaced by renames at the end: one that is a directory (or a device, a
  // FIFO) would fail there, after every case computed and with the others already replaced.
  for (const char* name : {"report.json", "report.html", "junit.xml", "report.csv"}) {
    const fs::path file = fs::path(out) / name;
    const fs::file_status status = fs::symlink_status(file, error);
    if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_symlink(status))
      throw BadInput("--out: '" + file.string() +
                     "' exists and is not a regular file: vivv replaces it");
  }
  std::string probe = (fs::path(out) / ".vivv-write-test-XXXXXX").string();
  DeferInterrupts defer;
  int fd = mkstemp(probe.data());
  if (fd < 0) throw BadInput(option + ": cannot write in '" + out + "'");
  close(fd);
  fs::remove(probe, error);
}

// Before any work: a --baseline that is one of the four files the run replaces in DIR (by
// device and inode: a hard link, a symbolic link or another spelling of the path is the same
// file) would be replaced by the run it judges — the same command would then pass on its second
// run. Refused, naming both options.
void refuse_baseline_among_outputs(const std::string& baseline, const std::string& out) {
  struct stat baseline_status {};
  if (::stat(baseline.c_str(), &baseline_status) != 0) return;  // read_report names what is wrong
  for (const char* name : {"report.json", "report.html", "junit.xml", "report.csv"}) {
    const fs::path file = fs::path(out) / name;
    struct stat status {};
    if (::stat(file.c_str(), &status) == 0 && status.st_dev == baseline_status.st_dev &&
        status.st_ino == baseline_status.st_ino)
      throw BadInput("--baseline " + baseline + " is " + file.string() +
                     ", which this run replaces (--out " + out +
                     "): the baseline would be overwritten by the run it judges; copy it "
                     "elsewhere first, or write this run to another --out");
  }
}

// Writes DIR/report.json, report.html, junit.xml and report.csv, prints the claims table;
// the exit code of the verdicts.
int write_reports(const std::string& out, const nlohmann::json& report, bool verbose) {
  std::vector<std::string> paths = write_report_directory(out, report);
  print_claims_table(std::cout, report, verbose ? ConsoleDetail::verbose : ConsoleDetail::terse);
  std::cout << "report:";
  for (const auto& path : paths) std::cout << " " << path;
  std::cout << "\n";
  bool could_not_run = false;
  for (const auto& entry : report.value("refused", nlohmann::json::array())) {
    if (!vivv::could_not_run(entry)) return exit_bad_input;
    could_not_run = true;
  }
  if (could_not_run) return exit_could_not_run;
  return run_succeeded(report["summary"]) && regressed_claims(report) == 0 ? exit_pass : exit_fail;
}

// --claims: each case keeps only the selected claims (and its expectations of them). A selected
// claim no case lists is refused, naming the claims the cases do list; a case left with none is
// skipped: the entries {file, name, claims, position} returned say which.
static nlohmann::json select_claims(std::vector<CaseSpec>& specs, const std::vector<std::string>& selected) {
  nlohmann::json skipped = nlohmann::json::array();
  if (selected.empty()) return skipped;
  std::vector<std::string> listed;
  for (const auto& spec : specs)
    for (const auto& id : spec.claims)
      if (std::find(listed.begin(), listed.end(), id) == listed.end()) listed.push_back(id);
  for (const auto& id : selected)
    if (std::find(listed.begin(), listed.end(), id) == listed.end())
      throw BadInput("--claims: no case of this run lists the claim '" + id + "'" +
                     case_reading::did_you_mean(id, listed) + "; they list: " +
                     case_reading::join(listed));
  for (std::size_t k = 0; k < specs.size(); ++k) {
    CaseSpec& spec = specs[k];
    std::vector<std::string> kept;
    for (const auto& id : spec.claims)
      if (std::find(selected.begin(), selected.end(), id) != selected.end()) kept.push_back(id);
    if (kept.empty())
      skipped.push_back({{"file", report_file_name(spec.file)},
                         {"name", spec.name},
                         {"claims", spec.claims},
                         {"position", k}});
    const auto keep_only = [&kept](auto& by_claim) {
      std::erase_if(by_claim, [&kept](const auto& entry) {
        return std::find(kept.begin(), kept.end(), entry.first) == kept.end();
      });
    };
    keep_only(spec.xfail);
    keep_only(spec.expect);
    spec.claims = kept;
  }
  return skipped;
}

int command_run(const std::vector<std::string>& args, const std::string& command_line) {
  RunOptions options = parse_run_options(args);
  if (!options.plan) {  // a plan writes nothing
    check_output_directory(options.out);
    if (options.reference_cache) check_output_directory(*options.reference_cache, "--reference-cache");
  }
  std::vector<CaseSpec> specs;
  std::map<std::string, std::string> names;
  for (const auto& file : options.case_files) {
    specs.push_back(within_reading_budget(file, options, [&file] { return read_case_file(file); }));
    auto [it, fresh] = names.emplace(specs.back().name, file);
    if (!fresh)
      throw CaseError(file, "name", "'" + specs.back().name + "' is also the name of " + it->second);
    // What the case reads and nothing computes with, said before the run (also with --quiet).
    for (const auto& warning : specs.back().warnings) std::cerr << "vivv: warning: " << file << ": " << warning << "\n";
  }
  // The baseline is read and checked like any input of vivv report — schema, shape, every fit
  // and order verdict judged again by its claim's rules — before any case computes.
  std::optional<nlohmann::json> baseline;
  if (options.baseline) {
    refuse_baseline_among_outputs(*options.baseline, options.out);
    try {
      baseline = read_judged_report(*options.baseline, claim_series_rules());
    } catch (const std::exception& error) {
      throw BadInput("--baseline " + *options.baseline + ": " + error.what());
    }
  }
  // The options against every case before any computes: a case they cannot run refuses the run.
  for (const auto& spec : specs)
    within_reading_budget(spec.file, options, [&] {
      check_precision_options(spec, options.scalar, options.digits);
      return CaseSpec{};
    });
  const nlohmann::json skipped = select_claims(specs, options.claims);
  for (auto& spec : specs)
    permit_process(spec, options.allow_process, options.process_timeout,
                   "vivv run --allow-process");
  // Every case file is read and checked above, so that each shard refuses the same bad input;
  // a shard then computes its own positions.
  const auto in_this_shard = [&options](std::size_t k) {
    return !options.shard || static_cast<int>(k % options.shard->count) == options.shard->index - 1;
  };
  std::vector<std::size_t> positions;
  for (std::size_t k = 0; k < specs.size(); ++k)
    if (in_this_shard(k) && !specs[k].claims.empty()) positions.push_back(k);
  std::vector<CaseSpec> selected;
  for (std::size_t k : positions) selected.push_back(specs[k]);
  if (options.plan) return print_plan(std::cout, selected, options);
  std::vector<nlohmann::json> results = run_all(selected, options);
  std::vector<nlohmann::json> cases;
  std::vector<std::size_t> case_positions;
  nlohmann::json refused = nlohmann::json::array();
  nlohmann::json case_paths = nlohmann::json::object();  // absolute paths: run block only
  for (std::size_t i = 0; i < selected.size(); ++i) {
    case_paths[selected[i].name] = fs::absolute(selected[i].file).lexically_normal().string();
    if (results[i].contains("refused") || results[i].contains("could_not_run")) {
      // The message without the file it begins with (the entry names the file).
      const bool could_not_run = results[i].contains("could_not_run");
      std::string message = results[i][could_not_run ? "could_not_run" : "refused"].get<std::string>();
      if (message.rfind(selected[i].file + ": ", 0) == 0)
        message.erase(0, selected[i].file.size() + 2);
      nlohmann::json entry = {{"file", report_file_name(selected[i].file)},
                              {"name", selected[i].name},
                              {"message", message},
                              {"kind", could_not_run ? "could-not-run" : "bad-input"}};
      if (options.shard) entry["position"] = positions[i];
      refused.push_back(entry);
      continue;
    }
    results[i]["file"] = report_file_name(selected[i].file);
    cases.push_back(std::move(results[i]));
    case_positions.push_back(positions[i]);
  }
  nlohmann::json report = assemble_report(cases, {command_line, library_versions()});
  if (!refused.empty()) report["refused"] = refused;
  if (baseline) {
    try {
      compare_with_baseline(report, *baseline, *options.baseline, options.baseline_tolerance);
    } catch (const std::exception& error) {
      throw BadInput("--baseline " + *options.baseline + ": comparing with it: " + error.what());
    }
  }
  report["run"]["case_paths"] = case_paths;
  report["run"]["overrides"] = {
      {"digits", options.digits ? nlohmann::json(*options.digits) : nlohmann::json()},
      {"scalar", options.scalar ? nlohmann::json(*options.scalar) : nlohmann::json()},
      {"refine", options.refine},
      {"claims", options.claims.empty() ? nlohmann::json() : nlohmann::json(options.claims)}};
  // Cases --claims left without a claim: skipped, each with the claims its file lists (in a
  // shard, only its own).
  nlohmann::json skipped_here = nlohmann::json::array();
  for (const auto& entry : skipped) {
    if (!in_this_shard(entry["position"].get<std::size_t>())) continue;
    nlohmann::json copy = entry;
    if (!options.shard) copy.erase("position");
    skipped_here.push_back(copy);
  }
  if (!skipped_here.empty()) report["run"]["skipped_cases"] = skipped_here;
  if (options.shard) {
    nlohmann::json suite = nlohmann::json::array();  // every shard's check that it split the same list
    for (const auto& spec : specs) suite.push_back(spec.name);
    report["run"]["shard"] = {{"index", options.shard->index},
                              {"count", options.shard->count},
                              {"suite_size", specs.size()},
                              {"suite", suite},
                              {"positions", case_positions}};
  }
  return write_reports(options.out, report, options.verbose);
}

}  // namespace vivv::command_line
