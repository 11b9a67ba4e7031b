// `vivv report`: merge the cases of several reports (runs split across machines) and render them again.
#include <fcntl.h>
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

#include "harness/command_line/command_line.hpp"
#include "harness/run/run_case.hpp"
#include "harness/verdicts/rejudge.hpp"
#include "harness/library/version.hpp"
#include "reports/report.hpp"

namespace fs = std::filesystem;

namespace vivv::command_line {

// vivv report A.json [B.json ...] --out DIR: the cases of every report in one,
// re-rendered (runs split across machines). Duplicate case names and other
// schemas are bad input.
int command_report(const std::vector<std::string>& args, const std::string& command_line) {
  std::string out;
  bool verbose = false;
  std::vector<std::pair<std::string, nlohmann::json>> inputs;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--out") {
      if (i + 1 >= args.size()) throw BadInput("--out: missing value");
      out = args[++i];
      if (out.rfind("--", 0) == 0)
        throw BadInput("--out: expected a directory, got the option '" + out + "' (write ./" + out +
                       " for a directory of that name)");
    } else if (args[i] == "--verbose") {
      verbose = true;
    } else if (args[i].rfind("--", 0) == 0) {
      throw BadInput("unknown option '" + args[i] + "'");
    } else {
      try {
        inputs.emplace_back(args[i], read_judged_report(args[i], claim_series_rules()));
      } catch (const nlohmann::json::exception& error) {  // a shape the schema does not rule out
        throw BadInput(args[i] + ": a field is missing or of an unexpected type for vivv report (" +
                       error.what() + "): a damaged or edited report");
      }
    }
  }
  if (inputs.empty()) throw BadInput("vivv report: expected at least one report.json");
  if (out.empty()) throw BadInput("vivv report: expected --out DIR");
  check_output_directory(out);
  nlohmann::json merged;
  try {
    merged = merge_reports(inputs, {command_line, library_versions()});
  } catch (const nlohmann::json::exception& error) {
    std::string names;
    for (const auto& input : inputs) names += (names.empty() ? "" : ", ") + input.first;
    throw BadInput("merging " + names + ": a field is missing or of an unexpected type (" +
                   error.what() + "): a damaged or edited report");
  }
  return write_reports(out, merged, verbose);
}

}  // namespace vivv::command_line
