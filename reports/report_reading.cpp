// Reading reports back: `vivv report`'s merge of several runs (shards included), and the checks
// a report.json passes before anything reads it (its schema, its shape, its verdicts agreeing
// with its series). Writing them is reports/report.cpp.
#include "reports/report.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cases/case_file.hpp"
#include "reports/schema_check.hpp"
#include "core/platform/signals.hpp"

namespace vivv {

nlohmann::json run_block(const RunInfo& run);  // reports/report.cpp

namespace {

// The suite position of every case of `inputs`, in input order, when the inputs are the
// shards of one `vivv run --shard I/N` split (each run block's "shard"); none when no input
// is a shard. Mixed, repeated, overlapping or missing shards are a ReportError naming them.
std::optional<std::vector<std::size_t>> shard_positions(
    const std::vector<std::pair<std::string, nlohmann::json>>& inputs) {
  const auto is_shard = [](const nlohmann::json& report) {
    return report.contains("run") && report["run"].is_object() && report["run"].contains("shard");
  };
  const auto first = std::find_if(inputs.begin(), inputs.end(), [&](const auto& in) { return is_shard(in.second); });
  if (first == inputs.end()) return std::nullopt;
  const nlohmann::json& reference = first->second["run"]["shard"];
  const auto count = reference.at("count").get<std::size_t>(), size = reference.at("suite_size").get<std::size_t>();
  std::map<std::size_t, std::string> shards;     // index -> file
  std::map<std::size_t, std::string> positions;  // position -> file
  std::vector<std::size_t> order;
  for (const auto& [file, report] : inputs) {
    if (!is_shard(report))
      throw ReportError(file + ": run.shard: not a shard, while " + first->first +
                        " is one: merge the shards of one split, or unsharded reports");
    const nlohmann::json& shard = report["run"]["shard"];
    if (shard.at("count").get<std::size_t>() != count || shard.at("suite_size").get<std::size_t>() != size)
      throw ReportError(file + ": run.shard: a shard of " + shard.at("count").dump() + " over " +
                        shard.at("suite_size").dump() + " cases, while " + first->first + " is one of " +
                        std::to_string(count) + " over " + std::to_string(size));
    const auto index = shard.at("index").get<std::size_t>();
    if (auto [it, fresh] = shards.emplace(index, file); !fresh)
      throw ReportError(file + ": run.shard: shard " + std::to_string(index) + " of " + std::to_string(count) +
                        " is also " + it->second);
    const nlohmann::json overrides = report["run"].value("overrides", nlohmann::json());
    const nlohmann::json reference_overrides =
        first->second["run"].value("overrides", nlohmann::json());
    if (overrides != reference_overrides)
      throw ReportError(
          file + ": run.overrides: " + overrides.dump() + ", while " + first->first + " ran with " +
          reference_overrides.dump() +
          ": the shards of one split must run with the same --digits, --scalar, --refine and --claims");
    if (shard.at("suite") != reference.at("suite") || shard.at("suite").size() != size)
      throw ReportError(file + ": run.shard.suite: not the list of cases " + first->first +
                        " was split from: every shard must be given the same case files in the same order");
    const nlohmann::json& at = shard.at("positions");
    if (!at.is_array() || at.size() != report.at("cases").size())
      throw ReportError(file + ": run.shard.positions: expected one position per case");
    // A case refused (or that could not run), and a case --claims skipped, holds its position
    // too (it is not in "cases").
    std::vector<std::pair<std::string, nlohmann::json>> held;  // field, entry
    const nlohmann::json refused = report.value("refused", nlohmann::json::array());
    for (std::size_t i = 0; i < refused.size(); ++i)
      held.emplace_back("refused[" + std::to_string(i) + "]", refused[i]);
    const nlohmann::json skipped = report["run"].value("skipped_cases", nlohmann::json::array());
    for (std::size_t i = 0; i < skipped.size(); ++i)
      held.emplace_back("run.skipped_cases[" + std::to_string(i) + "]", skipped[i]);
    for (const auto& [field, entry] : held) {
      if (!entry.contains("position"))
        throw ReportError(file + ": " + field + ".position: missing in a shard");
      const auto k = entry["position"].get<std::size_t>();
      if (k >= size || entry.at("name") != shard["suite"][k])
        throw ReportError(file + ": " + field + ": '" + entry.at("name").get<std::string>() +
                          "' is not the suite's case at position " + entry["position"].dump());
      if (auto [it, fresh] = positions.emplace(k, file); !fresh)
        throw ReportError(file + ": " + field + ".position: position " + std::to_string(k) +
                          " is also in " + it->second);
    }
    for (std::size_t i = 0; i < at.size(); ++i) {
      const nlohmann::json& position = at[i];
      const auto k = position.get<std::size_t>();
      if (k >= size) throw ReportError(file + ": run.shard.positions: " + position.dump() + " is outside the suite");
      if (report["cases"][i].at("name") != shard["suite"][k])
        throw ReportError(file + ": cases[" + std::to_string(i) + "]: '" + report["cases"][i]["name"].get<std::string>() +
                          "' is not the suite's case at position " + std::to_string(k));
      if (auto [it, fresh] = positions.emplace(k, file); !fresh)
        throw ReportError(file + ": run.shard.positions: position " + position.dump() + " is also in " + it->second);
      order.push_back(k);
    }
  }
  for (std::size_t index = 1; index <= count; ++index)
    if (!shards.count(index))
      throw ReportError("shard " + std::to_string(index) + " of " + std::to_string(count) +
                        " is missing: the merged report would not be the suite");
  if (positions.size() != size)
    throw ReportError("the shards hold " + std::to_string(positions.size()) + " of the suite's " +
                      std::to_string(size) + " cases");
  return order;
}

}  // namespace

nlohmann::json merge_reports(const std::vector<std::pair<std::string, nlohmann::json>>& inputs,
                             const RunInfo& run) {
  nlohmann::json run_json = run_block(run);
  run_json["merged_from"] = nlohmann::json::array();
  nlohmann::json cases = nlohmann::json::array();
  nlohmann::json refused = nlohmann::json::array();
  std::map<std::string, std::string> seen;  // case name -> report it came from
  for (const auto& [file, report] : inputs) {
    if (!readable_report_schema(report))
      throw ReportError(
          file + ": schema: expected " + readable_report_schemas + ", got " +
          (report.is_object() && report.contains("schema") ? report["schema"].dump() : "none"));
    for (const auto& c : report.at("cases")) {
      std::string name = c.at("name");
      auto [it, fresh] = seen.emplace(name, file);
      if (!fresh)
        throw ReportError(file + ": cases: the case '" + name + "' is also in " + it->second);
      cases.push_back(c);
    }
    for (const auto& entry : report.value("refused", nlohmann::json::array())) {
      std::string name = entry.at("name");
      auto [it, fresh] = seen.emplace(name, file);
      if (!fresh)
        throw ReportError(file + ": refused: the case '" + name + "' is also in " + it->second);
      refused.push_back(entry);
    }
    const nlohmann::json& source_run = report.at("run");
    const nlohmann::json case_seconds = source_run.value("case_seconds", nlohmann::json::object());
    for (const auto& [name, seconds] : case_seconds.items())
      run_json["case_seconds"][name] = seconds;
    const nlohmann::json claim_seconds = source_run.value("claim_seconds", nlohmann::json::object());
    for (const auto& [name, claims] : claim_seconds.items()) run_json["claim_seconds"][name] = claims;
    const nlohmann::json run_seconds = source_run.value("run_seconds", nlohmann::json::object());
    for (const auto& [name, runs] : run_seconds.items()) run_json["run_seconds"][name] = runs;
    const nlohmann::json case_paths = source_run.value("case_paths", nlohmann::json::object());
    for (const auto& [name, path] : case_paths.items()) run_json["case_paths"][name] = path;
    for (const auto& entry : source_run.value("skipped_cases", nlohmann::json::array())) {
      auto [it, fresh] = seen.emplace(entry.at("name").get<std::string>(), file);
      if (!fresh)
        throw ReportError(file + ": run.skipped_cases: the case '" + entry.at("name").get<std::string>() +
                          "' is also in " + it->second);
      run_json["skipped_cases"].push_back(entry);
    }
    run_json["merged_from"].push_back({{"report", file}, {"run", source_run}});
  }
  // The shards of one split merge into the suite's order: the unsharded run's report.
  if (auto positions = shard_positions(inputs)) {
    // Suite order; the positions of refused cases stay empty and are dropped.
    std::map<std::size_t, nlohmann::json> by_position;
    for (std::size_t i = 0; i < positions->size(); ++i) by_position[(*positions)[i]] = cases[i];
    cases = nlohmann::json::array();
    for (auto& [position, c] : by_position) cases.push_back(std::move(c));
    std::sort(refused.begin(), refused.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
      return a.at("position").get<std::size_t>() < b.at("position").get<std::size_t>();
    });
  }
  nlohmann::json merged = {{"schema", report_schema},
                           {"run", run_json},
                           {"summary", verdict_counts(cases)},
                           {"cases", cases}};
  if (!refused.empty()) merged["refused"] = refused;
  // Never write a report that breaks the schema: every input followed it, so this is vivv's
  // own error, but it is caught before any file is written.
  if (auto violation = schema_violation(merged))
    throw ReportError("the merged report: " + *violation + " (reports/schema.json)");
  return merged;
}

namespace {

// What the renderers read without checking: each case an object with a non-empty string name,
// an object initial and a list of claims; each claim an object with a string id and a known
// verdict. Throws ReportError naming the field.
void check_report_shape(const nlohmann::json& report, const std::string& path) {
  const nlohmann::json& cases = report.at("cases");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string where = path + ": cases[" + std::to_string(i) + "]";
    const nlohmann::json& c = cases[i];
    if (!c.is_object()) throw ReportError(where + ": expected an object");
    if (!c.contains("name") || !c["name"].is_string() || c["name"].get<std::string>().empty())
      throw ReportError(where + ".name: expected a non-empty string");
    if (!c.contains("initial") || !c["initial"].is_object())
      throw ReportError(where + ".initial: expected an object");
    if (!c.contains("claims") || !c["claims"].is_array()) throw ReportError(where + ".claims: expected a list");
    for (std::size_t k = 0; k < c["claims"].size(); ++k) {
      const std::string at = where + ".claims[" + std::to_string(k) + "]";
      const nlohmann::json& claim = c["claims"][k];
      if (!claim.is_object()) throw ReportError(at + ": expected an object");
      if (!claim.contains("id") || !claim["id"].is_string()) throw ReportError(at + ".id: expected a string");
      const auto& names = verdict_names();
      if (!claim.contains("verdict") || !claim["verdict"].is_string() ||
          std::find(names.begin(), names.end(), claim["verdict"].get<std::string>()) == names.end())
        throw ReportError(
            at + ".verdict: expected one of pass, fail, inconclusive, error, xfail, xpass");
      if (claim.contains("xfail_reason") && !claim["xfail_reason"].is_string())
        throw ReportError(at + ".xfail_reason: expected a string");
      if (claim.contains("series") && !claim["series"].is_array())
        throw ReportError(at + ".series: expected a list");
    }
  }
}

// What vivv run writes holds together: a claim that passed (or xpassed) has no series that
// fails, and the summary counts the claims' verdicts. A verdict edited by hand, or a summary
// left from another report, breaks one of them: refused, naming where.
void check_verdicts_agree(const nlohmann::json& report, const std::string& path) {
  const nlohmann::json& cases = report.at("cases");
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (std::size_t k = 0; k < cases[i]["claims"].size(); ++k) {
      const nlohmann::json& claim = cases[i]["claims"][k];
      const std::string verdict = claim["verdict"].get<std::string>();
      if (verdict != "pass" && verdict != "xpass") continue;
      const nlohmann::json series = claim.value("series", nlohmann::json::array());
      for (std::size_t j = 0; j < series.size(); ++j)
        if (series[j].is_object() &&
            series[j].value("holds", nlohmann::json()) == nlohmann::json(false))
          throw ReportError(
              path + ": cases[" + std::to_string(i) + "].claims[" + std::to_string(k) +
              "].verdict: \"" + verdict + "\" while its series[" + std::to_string(j) +
              "] does not hold: the report was edited or damaged after vivv wrote it");
    }
  const nlohmann::json counted = verdict_counts(cases);
  if (report.contains("summary") && report["summary"] != counted)
    throw ReportError(path + ": summary: " + report["summary"].dump() +
                      " does not count the claims' verdicts " + counted.dump() +
                      ": the report was edited or damaged after vivv wrote it");
}

// Each case of a report appears once, judged or recorded as refused (or as not run): the same
// name twice — a refused entry that is also a judged case, a refused entry written twice — is an
// edited report, refused by vivv report and --baseline alike.
void check_names_once(const nlohmann::json& report, const std::string& path) {
  std::map<std::string, std::string> seen;  // name -> where
  const auto see = [&](const nlohmann::json& entry, const std::string& where) {
    if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string()) return;  // the schema says
    const auto [it, fresh] = seen.emplace(entry["name"].get<std::string>(), where);
    if (!fresh)
      throw ReportError(path + ": " + where + ": the case '" + it->first + "' is also in " + it->second +
                        ": a case appears once in a report; the report was edited or damaged after vivv wrote it");
  };
  const nlohmann::json& cases = report.at("cases");
  for (std::size_t i = 0; i < cases.size(); ++i) see(cases[i], "cases[" + std::to_string(i) + "]");
  const nlohmann::json refused = report.value("refused", nlohmann::json::array());
  if (refused.is_array())
    for (std::size_t i = 0; i < refused.size(); ++i) see(refused[i], "refused[" + std::to_string(i) + "]");
}

}  // namespace

nlohmann::json read_report(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw ReportError(path + ": not a regular file");
  std::ifstream in(path);
  if (!in) throw ReportError(path + ": cannot open");
  nlohmann::json report;
  try {
    report = parse_json_strictly(in, path);
  } catch (const CaseError& error) {
    throw ReportError(error.what());
  }
  if (!readable_report_schema(report))
    throw ReportError(
        path + ": schema: expected " + std::string(readable_report_schemas) + ", got " +
        (report.is_object() && report.contains("schema") ? report["schema"].dump().substr(0, 80) : "none"));
  if (!report.contains("cases") || !report["cases"].is_array() || !report.contains("run") ||
      !report["run"].is_object())
    throw ReportError(path + ": expected the fields \"cases\" (a list) and \"run\" (an object)");
  check_report_shape(report, path);
  if (auto violation = schema_violation(report))
    throw ReportError(path + ": " + *violation +
                      " (reports/schema.json): a damaged or edited report");
  check_verdicts_agree(report, path);
  check_names_once(report, path);
  return report;
}

}  // namespace vivv
