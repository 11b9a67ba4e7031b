// vivv: the command-line tool (docs/case-files.md).
//
//   vivv run [CASE.json ...] [--out DIR] [--digits D] [--scalar S] [--jobs J] [--shard I/N]
//   [--refine]
//            [--max-seconds S] [--progress]
//   vivv report REPORT.json [MORE.json ...] --out DIR   (merge and re-render)
//   vivv list
//   vivv bench reference|del|process|size
//
// Exit codes: 0 every claim holds (or fails as the case expects: xfail), 1 a
// claim fails, errs or passes although marked xfail, 2 bad input (the message
// names the file, the field and what was expected; no report is written), 3 a --jobs worker
// ended by a signal, 4 a case could not run (its map program failed while it ran; recorded).
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "core/platform/text.hpp"
#include "harness/command_line/command_line.hpp"
#include "harness/library/version.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  using namespace vivv;
  using namespace vivv::command_line;
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string command_line;
  for (int i = 0; i < argc; ++i) {
    if (i > 0) command_line += ' ';
    command_line += argv[i];
  }
  if (args.empty()) return usage(std::cerr, exit_bad_input);
  std::string command = args.front();
  args.erase(args.begin());
  try {
    // `vivv run --help`, `vivv report -h`, ...: the usage, exit 0.
    if (std::find_if(args.begin(), args.end(), [](const std::string& a) { return a == "--help" || a == "-h"; }) !=
        args.end())
      return command == "run" ? run_help(std::cout) : usage(std::cout, exit_pass);
    if (command == "run") return command_run(args, command_line);
    if (command == "list") {
      if (!args.empty()) return bad_input("vivv list takes no arguments, got '" + args.front() + "'");
      return command_list();
    }
    if (command == "bench") {
      const bool size_table = args.size() == 2 && args[0] == "size";  // `vivv bench size gravity_double`
      if ((args.size() != 1 && !size_table) ||
          (args[0] != "reference" && args[0] != "del" && args[0] != "process" && args[0] != "size")) {
        std::cerr << "vivv bench: expected one of: reference (the Taylor reference flow against "
                     "Boost.Odeint), del (a DEL step against the L evaluations it needs), process "
                     "(protocol vivv-map/1's overhead per step against a DEL step), size (the cost of a DEL step, a "
                     "reference step and a symplecticity check against the number of coordinates; size chain_double, "
                     "chain_mpfr or gravity_double: that table alone)\n";
        return exit_bad_input;
      }
      // The benchmarks are a program of their own beside vivv (bench/commands/main.cpp), so that
      // building the tool for a run does not compile them.
      const fs::path bench = fs::read_symlink("/proc/self/exe").parent_path() / "vivv-bench";
      std::error_code missing;
      if (!fs::exists(bench, missing))
        return bad_input("vivv bench runs " + bench.string() +
                         ", which is not built: cmake --build build --target benchmarks (bash "
                         "bootstrap.sh slow builds it)");
      std::cout.flush();
      const std::string name = "vivv-bench";
      std::vector<char*> argv{const_cast<char*>(name.c_str()), args[0].data(), nullptr, nullptr};
      if (size_table) argv[2] = args[1].data();
      execv(bench.c_str(), argv.data());
      return bad_input("vivv bench: cannot run " + bench.string() + ": " + std::strerror(errno));
    }
    if (command == "report") return command_report(args, command_line);
    if (command == "--help" || command == "help") return usage(std::cout, exit_pass);
    if (command == "--version" || command == "version") {
      std::cout << library_versions() << "\n";
      return exit_pass;
    }
    std::cerr << "vivv: unknown command '" << terminal_safe(cut_at_character(command, 100)) << "'\n";
    return usage(std::cerr, exit_bad_input);
  } catch (const WorkerCrash& error) {
    std::cerr << "vivv: " << terminal_safe(error.what()) << "\n";
    return exit_crash;
  } catch (const nlohmann::json::exception& error) {  // a report.json of the wrong shape
    return bad_input(std::string("malformed input: ") + error.what());
  } catch (
      const std::exception& error) {  // CaseError, BadInput, ReportError and anything else: exit 2
    return bad_input(error.what());
  }
}