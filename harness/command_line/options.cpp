// `vivv run`'s options, parsed and checked before any case runs, and the help texts.
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

#include "cases/case_reader.hpp"
#include "cases/catalogue.hpp"
#include "core/platform/text.hpp"
#include "harness/command_line/command_line.hpp"

namespace fs = std::filesystem;

namespace vivv::command_line {

// The message of bad input on stderr, at most 4000 characters of it (a hostile input's value
// would otherwise be echoed whole); exit 2.
int bad_input(const std::string& message) {
  constexpr std::size_t limit = 2000;  // a message, not a dump: the first 2 KB say what is wrong
  std::cerr << "vivv: " << terminal_safe(cut_at_character(message, limit));
  if (message.size() > limit) std::cerr << "... (" << message.size() - limit << " more characters)";
  std::cerr << "\n";
  return exit_bad_input;
}


std::string default_suite_directory() { return (fs::path(VIVV_SOURCE_DIR) / "cases" / "suite").string(); }

// The case file as report.json names it: relative to the source tree when it
// lies inside it (the same bytes from any checkout and working directory),
// else as given on the command line.
std::string report_file_name(const std::string& file) {
  std::error_code file_error, root_error;
  fs::path path = fs::weakly_canonical(fs::absolute(file), file_error);
  fs::path root = fs::weakly_canonical(VIVV_SOURCE_DIR, root_error);
  if (file_error || root_error) return file;
  fs::path relative = path.lexically_relative(root);
  if (relative.empty() || *relative.begin() == "..") return file;
  return relative.generic_string();
}

std::vector<std::string> default_suite() {
  std::vector<std::string> files;
  std::error_code error;
  if (!fs::is_directory(default_suite_directory(), error))
    throw BadInput("no case files given, and the default suite " + default_suite_directory() +
                   " (compiled in from the source tree) is not there: name the case files");
  for (const auto& entry : fs::directory_iterator(default_suite_directory()))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

namespace {

int parse_integer(const std::string& flag, const std::string& text, int low, int high) {
  try {
    std::size_t used = 0;
    int value = std::stoi(text, &used);
    if (used == text.size() && value >= low && value <= high) return value;
  } catch (const std::exception&) {
  }
  throw BadInput(flag + ": expected an integer in [" + std::to_string(low) + ", " +
                 std::to_string(high) + "], got '" + text + "'");
}

// A decimal number for `flag` that `allowed` accepts; BadInput saying what was `expected`.
template <class Allowed>
double parse_real(const std::string& flag, const std::string& text, Allowed allowed,
                  const std::string& expected) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !allowed(value))
    throw BadInput(flag + ": expected " + expected + ", got '" + text.substr(0, 40) + "'");
  return value;
}

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  if (slash != std::string::npos) {
    const std::string index = text.substr(0, slash), count = text.substr(slash + 1);
    auto digits = [](const std::string& t) {
      return !t.empty() && t.size() <= 4 && std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (digits(index) && digits(count)) {
      Shard shard{std::stoi(index), std::stoi(count)};
      if (shard.count >= 1 && shard.count <= 1000 && shard.index >= 1 && shard.index <= shard.count) return shard;
    }
  }
  throw BadInput("--shard: expected I/N with 1 <= I <= N <= 1000 (run the I-th of N shards), got '" +
                 text.substr(0, 40) + "'");
}

}  // namespace

RunOptions parse_run_options(const std::vector<std::string>& args) {
  RunOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw BadInput(arg + ": missing value");
      return args[++i];
    };
    if (arg == "--out") {
      options.out = value();
      // `--out --quiet` once made a directory named --quiet.
      if (options.out.rfind("--", 0) == 0)
        throw BadInput("--out: expected a directory, got the option '" + options.out +
                       "' (write ./" + options.out + " for a directory of that name)");
    } else if (arg == "--digits")
      options.digits = parse_integer(arg, value(), 20, maximum_digits);
    else if (arg == "--scalar") {
      options.scalar = value();
      const auto& names = scalar_names();
      if (std::find(names.begin(), names.end(), *options.scalar) == names.end())
        throw BadInput("--scalar: expected double, \"long double\", float128 or mpfr, got '" + *options.scalar + "'");
    } else if (arg == "--jobs") options.jobs = parse_integer(arg, value(), 1, 64);
    else if (arg == "--shard") options.shard = parse_shard(value());
    else if (arg == "--max-seconds") options.max_seconds = parse_integer(arg, value(), 1, 1000000);
    else if (arg == "--progress") options.progress = true;
    else if (arg == "--reference-cache") {
      options.reference_cache = value();
      if (options.reference_cache->rfind("--", 0) == 0)
        throw BadInput("--reference-cache: expected a directory, got the option '" + *options.reference_cache + "'");
    }
    else if (arg == "--quiet") options.progress = false;
    else if (arg == "--verbose") options.verbose = true;
    else if (arg == "--refine") options.refine = true;
    else if (arg == "--plan") options.plan = true;
    else if (arg == "--keep-going")
      options.keep_going = true;
    else if (arg == "--baseline")
      options.baseline = value();
    else if (arg == "--claims") {
      // Claim ids, comma-separated, each known to vivv (which cases list them is checked once the
      // case files are read).
      const std::string list = value();
      std::size_t start = 0;
      while (start <= list.size()) {
        const std::size_t end = std::min(list.find(',', start), list.size());
        const std::string id = list.substr(start, end - start);
        const auto& known = claim_ids();
        if (std::find(known.begin(), known.end(), id) == known.end())
          throw BadInput("--claims: '" + std::string(cut_at_character(id, 100)) + "' is not a claim" +
                         case_reading::did_you_mean(id, known) + "; vivv list names every claim");
        if (std::find(options.claims.begin(), options.claims.end(), id) == options.claims.end())
          options.claims.push_back(id);
        start = end + 1;
      }
      // The same set is the same selection, in the registry's order: shards run with
      // "global-order,local-order" and "local-order,global-order" merge.
      const auto& known = claim_ids();
      const auto rank = [&](const std::string& id) { return std::find(known.begin(), known.end(), id) - known.begin(); };
      std::sort(options.claims.begin(), options.claims.end(),
                [&](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
    }
    else if (arg == "--baseline-tolerance")
      // Above 0 (a constant equal to the last digit would regress) and at most 10 (×11).
      options.baseline_tolerance = parse_real(
          arg, value(), [](double x) { return x > 0 && x <= 10; },
          "the allowed growth of the error constant as a fraction in (0, 10] (0.1 allows 10 %)");
    else if (arg == "--allow-process")
      options.allow_process = true;
    else if (arg == "--process-timeout")
      options.process_timeout = parse_real(
          arg, value(), [](double x) { return x >= 0.1 && x <= 3600; },
          "the seconds a map program may take to answer, from 0.1 to 3600");
    else if (arg.rfind("--", 0) == 0)
      throw BadInput("unknown option '" + arg + "'");
    else options.case_files.push_back(arg);
  }
  if (options.case_files.empty()) options.case_files = default_suite();
  return options;
}

int usage(std::ostream& out, int code) {
  out << "usage: vivv run [CASE.json ...] [--out DIR] [--digits D] [--scalar S] [--jobs J] "
         "[--shard I/N] [--refine]\n"
         "                [--max-seconds S] [--keep-going] [--baseline OLD/report.json "
         "[--baseline-tolerance X]]\n"
         "                [--allow-process [--process-timeout S]] [--reference-cache DIR]\n"
         "                [--progress|--quiet] [--verbose] [--plan]\n"
         "       vivv report REPORT.json [MORE.json ...] --out DIR [--verbose]\n"
         "       vivv list\n"
         "       vivv bench reference|del|process|size\n"
         "       vivv --version\n"
         "run `vivv run --help` for what each option does\n";
  return code;
}

// `vivv run --help`: every option and what it does.
int run_help(std::ostream& out) {
  out << "vivv run [CASE.json ...] [options]: compute each case's claims and write "
         "DIR/report.json,\n"
         "report.html, junit.xml and report.csv (the default suite when no case file is given). "
         "Exit 0 when every\n"
         "claim passes (or fails as its case expects), 1 when one fails, is inconclusive, errs or "
         "passes\n"
         "unexpectedly, 2 for bad input (nothing written; with --keep-going, a case refused while "
         "it runs),\n"
         "3 when a --jobs worker is ended by a signal (nothing written), 4 when a case could not "
         "run: its\n"
         "map program failed while it ran (recorded in the four files, the others judged).\n"
         "  --out DIR          where the four files go (default vivv-report); checked before any "
         "case runs\n"
         "  --digits D         MPFR working precision in decimal digits, 20 … "
      << maximum_digits
      << ", for every case\n"
         "                     (overrides the cases' \"digits\"; refused for a case that runs in "
         "another scalar)\n"
         "  --scalar S         double, \"long double\", float128 or mpfr for every case (overrides "
         "\"scalar\")\n"
         "  --jobs J           run up to J cases at once, each in its own process (1 … 64)\n"
         "  --shard I/N        compute only cases I, I + N, I + 2N, … of the list (1 <= I <= N <= "
         "1000);\n"
         "                     `vivv report` merges the N shards' reports into the suite's\n"
         "  --refine           halve h until every fitted order settles, within a budget; the "
         "report\n"
         "                     says why the sweep stopped\n"
         "  --max-seconds S    wall-time budget of each case; past it the case is refused naming "
         "its phase\n"
         "  --baseline OLD/report.json\n"
         "                     compare each claim's fitted orders and error constants with OLD's "
         "(same case,\n"
         "                     claim and series): an order that dropped by more than the order "
         "tolerance, or\n"
         "                     a constant grown by more than --baseline-tolerance, is a "
         "regression (exit 1)\n"
         "  --claims A,B       run only these of each case's claims; a case that lists none of "
         "them is skipped\n"
         "                     (and reported as skipped); a name no case lists is refused\n"
         "  --baseline-tolerance X\n"
         "                     the allowed growth of the error constant, a fraction (default 0.1: "
         "10 %)\n"
         "  --reference-cache DIR\n"
         "                     keep the Taylor reference flows' answers in DIR and reuse them in the "
         "next run\n"
         "                     of this same vivv on the same system, scalar and precision (the same "
         "numbers\n"
         "                     to the bit; another build's or another system's are not used)\n"
         "  --keep-going       a case refused while it runs (bad input, past its budget) is "
         "recorded as\n"
         "                     refused in the reports and the others keep their results; exit "
         "still 2\n"
         "                     (a case whose map program fails while it runs is recorded with or "
         "without it:\n"
         "                     it could not run, exit 4)\n"
         "  --allow-process    let cases start the programs they name (discretization kind "
         "\"process\",\n"
         "                     protocol vivv-map/1); without it such a case refuses the run\n"
         "  --process-timeout S\n"
         "                     seconds a map program may take for its greeting and each answer "
         "(default 30)\n"
         "  --progress         progress lines on stderr (the default on a terminal)\n"
         "  --quiet            no progress lines\n"
         "  --verbose          list every claim and each pass's detection limit (by default the\n"
         "                     console lists the claims that did not pass, why, and the summary)\n"
         "  --plan             read and check every case, then print what each will compute (the reference\n"
         "                     flow's orders, the sweep, each claim's work) and its memory estimate part by\n"
         "                     part; nothing is computed and no report written\n"
         "  --help, -h         this text\n";
  return exit_pass;
}

}  // namespace vivv::command_line
