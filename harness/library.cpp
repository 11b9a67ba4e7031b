// vivv as a library (harness/vivv.hpp): runs case files as `vivv run` does and writes the
// same three report files.
#include <filesystem>
#include <set>
#include <stdexcept>

#include "harness/version.hpp"
#include "harness/vivv.hpp"

namespace vivv {

Run run(const std::vector<std::string>& case_files) {
  Run result;
  std::vector<nlohmann::json> cases;
  std::set<std::string> names;
  std::vector<CaseSpec> specs;
  for (const auto& file : case_files) {
    specs.push_back(read_case_file(file));
    if (!names.insert(specs.back().name).second)
      throw CaseError(file, "name", "'" + specs.back().name + "' is the name of another case of this run");
  }
  for (const auto& spec : specs) {
    result.results.push_back(run_case(spec, std::nullopt, false, nullptr));
    cases.push_back(case_json(result.results.back()));
    cases.back()["file"] = std::filesystem::path(spec.file).filename().string();
  }
  result.report = assemble_report(cases, {"vivv::run (library)", library_versions()});
  return result;
}

std::vector<std::string> write_reports(const Run& run, const std::string& directory) {
  std::filesystem::create_directories(directory);
  return write_report_directory(directory, run.report);
}

bool holds(const Run& run) { return run_succeeded(run.report["summary"]); }

std::string failures(const Run& run) {
  std::string lines;
  for (const auto& result : run.results)
    for (const auto& claim : result.claims)
      if (claim.verdict != "pass" && claim.verdict != "xfail")
        lines += result.spec.name + " / " + claim.id + ": " + claim.verdict + ": " + claim.explanation + "\n";
  return lines;
}

}  // namespace vivv
