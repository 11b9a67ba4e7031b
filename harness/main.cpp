// vivv: the command-line tool (docs/case-files.md).
//
//   vivv run [CASE.json ...] [--out DIR] [--digits D] [--scalar S] [--jobs J] [--shard I/N]
//   [--refine]
//            [--max-seconds S] [--progress]
//   vivv report REPORT.json [MORE.json ...] --out DIR   (merge and re-render)
//   vivv list
//   vivv bench reference|del|process
//
// Exit codes: 0 every claim holds (or fails as the case expects: xfail), 1 a
// claim fails, errs or passes although marked xfail, 2 bad input (the message
// names the file, the field and what was expected; no report is written).
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

#include "cases/case_file.hpp"
#include "cases/catalogue.hpp"
#include "core/discrete_lagrangian.hpp"
#include "harness/baseline.hpp"
#include "harness/claims.hpp"
#include "harness/map_process.hpp"
#include "harness/rejudge.hpp"
#include "harness/run_case.hpp"
#include "harness/version.hpp"
#include "reports/report.hpp"
#include "reports/signals.hpp"

namespace fs = std::filesystem;

namespace vivv {
namespace {

constexpr int exit_pass = 0, exit_fail = 1, exit_bad_input = 2;
// A --jobs worker ended by a signal (a crash, the kernel's out-of-memory killer): not the
// input's fault, and no verdict either.
constexpr int exit_crash = 3;
struct WorkerCrash : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The message of bad input on stderr, at most 4000 characters of it (a hostile input's value
// would otherwise be echoed whole); exit 2.
int bad_input(const std::string& message) {
  constexpr std::size_t limit = 2000;  // a message, not a dump: the first 2 KB say what is wrong
  std::cerr << "vivv: " << message.substr(0, limit);
  if (message.size() > limit) std::cerr << "... (" << message.size() - limit << " more characters)";
  std::cerr << "\n";
  return exit_bad_input;
}

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
  bool refine = false;
  // --keep-going: a case refused as bad input while it runs is recorded as refused, the other
  // cases keep their results, and the run still exits 2.
  bool keep_going = false;
  // --baseline OLD/report.json: each claim's fitted series compared with OLD's (regressed: exit 1).
  std::optional<std::string> baseline;
  double baseline_tolerance = default_baseline_tolerance;
  // --allow-process: cases may start the programs they name (discretization kind "process");
  // --process-timeout: the seconds such a program has for each answer.
  bool allow_process = false;
  double process_timeout = 30;
};

std::string default_suite_directory() { return std::string(VIVV_SOURCE_DIR) + "/cases/suite"; }

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
    else if (arg == "--quiet") options.progress = false;
    else if (arg == "--refine") options.refine = true;
    else if (arg == "--keep-going")
      options.keep_going = true;
    else if (arg == "--baseline")
      options.baseline = value();
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

// --max-seconds: what the case was computing when its budget ran out (the last progress
// message, kept where the alarm handler can write it without allocating), and the budget.
char budget_message[512] = "";
std::size_t budget_message_length = 0;
int budget_seconds = 0;
bool budget_keeps_going = false;  // --keep-going: the run goes on and writes its reports

void note_phase(const std::string& file, const std::string& phase) {
  const std::string text =
      "vivv: " + file.substr(0, 200) + ": the case ran past its budget of " +
      std::to_string(budget_seconds) +
      " s (--max-seconds) while computing: " + phase.substr(0, 200) +
      (budget_keeps_going ? "; recorded as refused (--keep-going)\n" : "; no report written\n");
  budget_message_length = std::min(text.size(), sizeof budget_message);
  std::memcpy(budget_message, text.data(), budget_message_length);
}

// Under --keep-going, the worker's file for the message of its refusal (-1: none).
int refusal_fd = -1;

extern "C" void budget_exhausted(int) {
  end_map_processes();  // no map program outlives the case
  [[maybe_unused]] auto written = ::write(STDERR_FILENO, budget_message, budget_message_length);
  if (refusal_fd >= 0) written = ::write(refusal_fd, budget_message, budget_message_length);
  std::_Exit(exit_bad_input);  // nothing was written
}

// Progress on stderr: elapsed seconds and what is being computed — and, while a phase runs
// longer than 5 s without a line of its own (the exact TQ discretization's quadrature at 1000
// digits, a step-size probe, L_d^E), a line every 5 s saying which phase is still running and
// for how long, from a thread that only prints. Lives for one case (in its worker, after fork).
class ProgressPrinter {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr auto heartbeat = std::chrono::seconds(5);

  ProgressPrinter() : started_(Clock::now()), last_line_(started_), phase_started_(started_) {
    thread_ = std::thread([this] { beat(); });
  }
  ~ProgressPrinter() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }
  ProgressPrinter(const ProgressPrinter&) = delete;
  ProgressPrinter& operator=(const ProgressPrinter&) = delete;

  void print(const std::string& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    phase_ = message;
    last_line_ = phase_started_ = Clock::now();
    write(message);
  }

 private:
  void beat() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, std::chrono::milliseconds(250));
      if (stop_ || phase_.empty() || Clock::now() - last_line_ < heartbeat) continue;
      const double running = std::chrono::duration<double>(Clock::now() - phase_started_).count();
      std::ostringstream line;
      line << "… still: " << phase_ << " (" << std::fixed << std::setprecision(0) << running
           << " s so far)";
      write(line.str());
      last_line_ = Clock::now();
    }
  }
  void write(const std::string& message) const {
    const double elapsed = std::chrono::duration<double>(Clock::now() - started_).count();
    std::cerr << "[" << std::fixed << std::setprecision(1) << elapsed << " s] " << message << "\n";
  }

  const Clock::time_point started_;
  Clock::time_point last_line_, phase_started_;
  std::string phase_;
  bool stop_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

std::function<void(const std::string&)> progress_printer(bool enabled) {
  if (!enabled) return {};
  auto printer = std::make_shared<ProgressPrinter>();
  return [printer](const std::string& message) { printer->print(message); };
}

// Runs one case; solver failures and non-regular Lagrangians are bad input.
nlohmann::json run_one(const CaseSpec& spec, const RunOptions& options) {
  try {
    CaseSpec effective = spec;
    if (options.scalar) effective.scalar = *options.scalar;
    if (options.digits && effective.scalar != "mpfr")
      throw BadInput("--digits sets the MPFR working precision, and this case runs in \"" +
                     effective.scalar + "\"");
    std::function<void(const std::string&)> progress = progress_printer(options.progress);
    if (options.max_seconds) {
      // The budget: SIGALRM after max_seconds ends the process with the phase it was in.
      budget_seconds = *options.max_seconds;
      note_phase(spec.file, "reading the case");
      signal(SIGALRM, budget_exhausted);
      alarm(static_cast<unsigned>(budget_seconds));
      progress = [print = std::move(progress), file = spec.file](const std::string& message) {
        note_phase(file, message);
        if (print) print(message);
      };
    }
    nlohmann::json result = case_json(run_case(effective, options.digits, options.refine, progress));
    if (options.max_seconds) alarm(0);
    return result;
  } catch (const CaseError&) {
    throw;  // names the file and the field already
  } catch (const SolverError& error) {
    throw BadInput(spec.file + ": " + error.what() +
                   (error.step_sizes_probed ? "" : " (reduce h: increase the step counts)"));
  } catch (const SingularLagrangianError& error) {
    throw BadInput(spec.file + ": " + error.what());
  } catch (const std::domain_error& error) {
    throw BadInput(spec.file + ": " + error.what());
  } catch (const std::runtime_error& error) {  // e.g. a reference flow that cannot reach T
    throw BadInput(spec.file + ": " + error.what());
  }
}

volatile sig_atomic_t interrupted_by = 0;
extern "C" void note_interrupt(int signal) { interrupted_by = signal; }

// While alive (the --jobs parent), SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1 and SIGUSR2 are noted
// instead of ending the process, so that it can stop its workers and remove its temporary directory
// first; a signal ignored when vivv started stays ignored. restore() gives back the dispositions
// vivv started with (to the workers, and before the parent ends by the signal it noted).
class NoteInterrupts {
 public:
  NoteInterrupts() {
    for (std::size_t i = 0; i < signals_.size(); ++i) {
      sigaction(signals_[i], nullptr, &previous_[i]);
      if (previous_[i].sa_handler == SIG_IGN) continue;
      struct sigaction action {};
      action.sa_handler = note_interrupt;
      sigemptyset(&action.sa_mask);
      sigaction(signals_[i], &action, nullptr);
    }
  }
  ~NoteInterrupts() { restore(); }
  NoteInterrupts(const NoteInterrupts&) = delete;
  NoteInterrupts& operator=(const NoteInterrupts&) = delete;
  void restore() {
    for (std::size_t i = 0; i < signals_.size(); ++i) sigaction(signals_[i], &previous_[i], nullptr);
  }

 private:
  // Every signal whose default action ends the process and that a user or a job scheduler
  // sends: SIGQUIT and SIGUSR1 once orphaned the workers and left the directory behind.
  std::array<int, 6> signals_{SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2};
  std::array<struct sigaction, 6> previous_{};
};

// Runs the cases in up to `jobs` worker processes (MPFR's working precision
// is process-wide in Boost 1.74, so parallel cases need processes, not threads).
// Each case's result, in order; under --keep-going a case refused as bad input is
// {"refused": message} (each case then runs in a worker process, so that a --max-seconds budget
// that ends it leaves the others).
std::vector<nlohmann::json> run_all(const std::vector<CaseSpec>& specs, const RunOptions& options) {
  std::vector<nlohmann::json> results(specs.size());
  if (options.jobs == 1 && !options.keep_going) {
    for (std::size_t i = 0; i < specs.size(); ++i) results[i] = run_one(specs[i], options);
    return results;
  }
  // A private directory (mode 0700, unpredictable name) for the workers' results, each file
  // created exclusively and never through a link.
  std::string work_template = (fs::temp_directory_path() / "vivv-XXXXXX").string();
  if (!mkdtemp(work_template.data()))
    throw BadInput("cannot create a private temporary directory under " + fs::temp_directory_path().string());
  fs::path work = work_template;
  NoteInterrupts notes;
  const pid_t parent = getpid();
  std::map<pid_t, std::size_t> running;
  std::string failures, crashes;
  std::size_t next = 0;
  // Waits for a worker to end, looking every 50 ms whether the run was interrupted.
  auto reap = [&]() {
    int status = 0;
    pid_t pid = 0;
    while ((pid = waitpid(-1, &status, WNOHANG)) == 0 && !interrupted_by) {
      const struct timespec pause = {0, 50'000'000};
      nanosleep(&pause, nullptr);
    }
    if (pid <= 0) return;  // interrupted
    std::size_t index = running.at(pid);
    running.erase(pid);
    if (WIFSIGNALED(status)) {  // no message of its own: say what ended it
      const int signal = WTERMSIG(status);
      crashes += specs[index].file + ": its worker process was ended by signal " +
                 std::to_string(signal) + " (" + strsignal(signal) + ")" +
                 (signal == SIGKILL ? ", perhaps by the kernel for want of memory" : "") + "\n";
      return;
    }
    if (options.keep_going && WIFEXITED(status) && WEXITSTATUS(status) == exit_bad_input) {
      std::ifstream in(work / (std::to_string(index) + ".refused"));
      std::string message((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      while (!message.empty() && message.back() == '\n') message.pop_back();
      if (message.rfind("vivv: ", 0) == 0) message.erase(0, 6);  // the budget's stderr line
      if (const std::string unwritten = "; recorded as refused (--keep-going)";
          message.size() >= unwritten.size() &&
          message.compare(message.size() - unwritten.size(), unwritten.size(), unwritten) == 0)
        message.erase(message.size() - unwritten.size());
      results[index] = {{"refused", message.empty()
                                        ? "refused in its worker process (see the messages above)"
                                        : message}};
      return;
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      failures += specs[index].file + " failed in its worker process\n";
      return;
    }
    std::ifstream in(work / (std::to_string(index) + ".json"));
    results[index] = nlohmann::json::parse(in);
  };
  while ((next < specs.size() || !running.empty()) && !interrupted_by) {
    if (next < specs.size() && static_cast<int>(running.size()) < options.jobs) {
      std::cout.flush();
      std::cerr.flush();
      pid_t pid = 0;
      {
        // The worker starts with vivv's own dispositions before any signal reaches it.
        DeferInterrupts defer;
        pid = fork();
        if (pid == 0) {
          notes.restore();
          // A worker never outlives the run: when the parent ends, however (SIGKILL included),
          // the kernel sends the worker SIGTERM; a parent already gone ends the worker now.
          prctl(PR_SET_PDEATHSIG, SIGTERM);
          if (getppid() != parent) std::_Exit(128 + SIGTERM);
        }
      }
      if (pid == 0) {
        int code = 0;
        if (options.keep_going)
          refusal_fd = ::open((work / (std::to_string(next) + ".refused")).c_str(),
                              O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
        try {
          write_exclusively(work / (std::to_string(next) + ".json"), run_one(specs[next], options).dump());
        } catch (const std::exception& error) {
          code = bad_input(error.what());
          if (refusal_fd >= 0) {
            const std::string message = std::string(error.what()).substr(0, 2000);
            [[maybe_unused]] auto written = ::write(refusal_fd, message.data(), message.size());
          }
        }
        std::_Exit(code);
      }
      if (pid < 0) {
        // No worker can start (the process limit): stop those running, remove their directory,
        // and say so; nothing is left behind.
        const int reason = errno;
        for (const auto& [running_pid, index] : running) kill(running_pid, SIGTERM);
        for (const auto& [running_pid, index] : running) waitpid(running_pid, nullptr, 0);
        std::error_code ignored;
        fs::remove_all(work, ignored);
        throw BadInput(std::string("cannot start a worker process for --jobs ") +
                       std::to_string(options.jobs) + ": " + std::strerror(reason) +
                       " (a lower --jobs, or the process limit ulimit -u, decides)");
      }
      running[pid] = next++;
    } else {
      reap();
    }
  }
  if (interrupted_by) {
    // Interrupted: stop the workers, remove what they wrote, and end by the same signal
    // (no report is written; an earlier one stays as it was).
    for (const auto& [pid, index] : running) kill(pid, SIGTERM);
    for (const auto& [pid, index] : running) waitpid(pid, nullptr, 0);
    std::error_code ignored;
    fs::remove_all(work, ignored);
    const int signal = interrupted_by;
    notes.restore();
    std::cerr << "vivv: interrupted (signal " << signal << "); no report written\n";
    raise(signal);
    std::_Exit(128 + signal);
  }
  fs::remove_all(work);
  if (!crashes.empty())
    throw WorkerCrash(crashes + failures + "(no report written; exit " +
                      std::to_string(exit_crash) + ": a crash, not a verdict and not bad input)");
  if (!failures.empty()) throw BadInput(failures + "(see the messages above)");
  return results;
}

int write_reports(const std::string& out, const nlohmann::json& report);

// Before any work: DIR must be a directory vivv can create and write in.
void check_output_directory(const std::string& out) {
  std::error_code error;
  if (fs::exists(out, error) && !fs::is_directory(out, error))
    throw BadInput("--out: '" + out + "' exists and is not a directory");
  fs::create_directories(out, error);
  if (error) throw BadInput("--out: cannot create '" + out + "': " + error.message());
  // The three files are replaced by renames at the end: one that is a directory (or a device, a
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
  if (fd < 0) throw BadInput("--out: cannot write in '" + out + "'");
  close(fd);
  fs::remove(probe, error);
}

int command_run(const std::vector<std::string>& args, const std::string& command_line) {
  RunOptions options = parse_run_options(args);
  check_output_directory(options.out);
  std::vector<CaseSpec> specs;
  std::map<std::string, std::string> names;
  for (const auto& file : options.case_files) {
    specs.push_back(read_case_file(file));
    auto [it, fresh] = names.emplace(specs.back().name, file);
    if (!fresh)
      throw CaseError(file, "name", "'" + specs.back().name + "' is also the name of " + it->second);
  }
  // The baseline is read (and checked like any input of vivv report) before any case computes.
  std::optional<nlohmann::json> baseline;
  if (options.baseline) {
    try {
      baseline = read_report(*options.baseline);
    } catch (const std::exception& error) {
      throw BadInput("--baseline: " + std::string(error.what()));
    }
  }
  // The options against every case before any computes: a case they cannot run refuses the run.
  for (const auto& spec : specs) check_precision_options(spec, options.scalar, options.digits);
  for (auto& spec : specs)
    permit_process(spec, options.allow_process, options.process_timeout,
                   "vivv run --allow-process");
  // Every case file is read and checked above, so that each shard refuses the same bad input;
  // a shard then computes its own positions.
  std::vector<std::size_t> positions;
  for (std::size_t k = 0; k < specs.size(); ++k)
    if (!options.shard || static_cast<int>(k % options.shard->count) == options.shard->index - 1)
      positions.push_back(k);
  std::vector<CaseSpec> selected;
  for (std::size_t k : positions) selected.push_back(specs[k]);
  budget_keeps_going = options.keep_going;
  std::vector<nlohmann::json> results = run_all(selected, options);
  std::vector<nlohmann::json> cases;
  std::vector<std::size_t> case_positions;
  nlohmann::json refused = nlohmann::json::array();
  nlohmann::json case_paths = nlohmann::json::object();  // absolute paths: run block only
  for (std::size_t i = 0; i < selected.size(); ++i) {
    case_paths[selected[i].name] = fs::absolute(selected[i].file).lexically_normal().string();
    if (results[i].contains("refused")) {
      // The message without the file it begins with (the entry names the file).
      std::string message = results[i]["refused"].get<std::string>();
      if (message.rfind(selected[i].file + ": ", 0) == 0)
        message.erase(0, selected[i].file.size() + 2);
      nlohmann::json entry = {{"file", report_file_name(selected[i].file)},
                              {"name", selected[i].name},
                              {"message", message}};
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
  if (baseline)
    compare_with_baseline(report, *baseline, *options.baseline, options.baseline_tolerance);
  report["run"]["case_paths"] = case_paths;
  report["run"]["overrides"] = {
      {"digits", options.digits ? nlohmann::json(*options.digits) : nlohmann::json()},
      {"scalar", options.scalar ? nlohmann::json(*options.scalar) : nlohmann::json()},
      {"refine", options.refine}};
  if (options.shard) {
    nlohmann::json suite = nlohmann::json::array();  // every shard's check that it split the same list
    for (const auto& spec : specs) suite.push_back(spec.name);
    report["run"]["shard"] = {{"index", options.shard->index},
                              {"count", options.shard->count},
                              {"suite_size", specs.size()},
                              {"suite", suite},
                              {"positions", case_positions}};
  }
  return write_reports(options.out, report);
}

// Writes DIR/report.json, report.html and junit.xml, prints the claims table;
// the exit code of the verdicts.
int write_reports(const std::string& out, const nlohmann::json& report) {
  std::vector<std::string> paths = write_report_directory(out, report);
  print_claims_table(std::cout, report);
  std::cout << "report:";
  for (const auto& path : paths) std::cout << " " << path;
  std::cout << "\n";
  if (report.contains("refused") && !report["refused"].empty()) return exit_bad_input;
  return run_succeeded(report["summary"]) && regressed_claims(report) == 0 ? exit_pass : exit_fail;
}

// vivv report A.json [B.json ...] --out DIR: the cases of every report in one,
// re-rendered (runs split across machines). Duplicate case names and other
// schemas are bad input.
int command_report(const std::vector<std::string>& args, const std::string& command_line) {
  std::string out;
  std::vector<std::pair<std::string, nlohmann::json>> inputs;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--out") {
      if (i + 1 >= args.size()) throw BadInput("--out: missing value");
      out = args[++i];
      if (out.rfind("--", 0) == 0)
        throw BadInput("--out: expected a directory, got the option '" + out + "' (write ./" + out +
                       " for a directory of that name)");
    } else if (args[i].rfind("--", 0) == 0) {
      throw BadInput("unknown option '" + args[i] + "'");
    } else {
      try {
        inputs.emplace_back(args[i], read_report(args[i]));
        check_series_follow_from_errors(inputs.back().second, args[i]);
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
  return write_reports(out, merged);
}

int command_list() {
  std::cout << "systems:\n";
  for (const auto& system : system_catalogue()) {
    std::cout << "  " << system.name << " (n = " << system.dimension << ")";
    for (const auto& p : system.parameters) std::cout << " " << p.name << "=" << p.default_value;
    std::cout << "\n";
  }
  std::cout << "  or your own: {\"name\", \"lagrangian\": a formula, \"coordinates\", \"velocities\", \"params\"}"
               " (n = 1..4; optional \"symmetry\": the generator xi(q), a formula per coordinate)\n";
  std::cout << "discretizations (Q×Q rules):\n";
  for (const auto& rule : rule_names()) {
    std::cout << "  " << rule;
    if (rule == "expression") std::cout << " (with \"L_d\": a formula in qb, qe, h, L(x, v), and your \"order\")";
    if (rule == "galerkin")
      std::cout << " (with \"degree\": 1..8, \"quadrature\": gauss | lobatto, \"nodes\": degree..16; "
                   "order min(2 degree, 2 nodes), Lobatto min(2 degree, 2 nodes - 2))";
    std::cout << "\n";
  }
  std::cout << "discretizations of TQ (\"formalism\": \"tq\", \"theta\": a fraction in [0, 1]):\n"
               "  psi: linear | taylor (with \"r\": 1..8) | exact\n"
               "  lagrangian: quadrature (with \"nodes\") | pullback (with a Q×Q \"qxq\") | exact (psi exact only)\n";
  std::cout << "one-step maps of Boost.Odeint (\"kind\": \"odeint\", \"stepper\"; a separable system "
               "1/2 w^T M w - V(q); claims";
  for (const auto& id : map_claim_ids()) std::cout << " " << id;
  std::cout << "):\n";
  for (const auto& stepper : odeint_steppers())
    std::cout << "  " << stepper.name << " (order " << stepper.order << (stepper.symplectic ? ", symplectic" : ", not symplectic")
              << ")\n";
  std::cout << "one-step maps of your own (\"kind\": \"map\", \"name\"): registered by a program that links vivv "
               "(vivv::register_map, docs/library.md); none in this tool\n";
  std::cout << "one-step maps in another program (\"kind\": \"process\", \"command\": [program, "
               "args...], "
               "\"order\"): protocol vivv-map/1 over its standard input and output "
               "(docs/process-protocol.md); "
               "needs vivv run --allow-process\n";
  std::cout << "claims:\n";
  for (const auto& claim : registered_claims())
    std::cout << "  " << claim.id << " [" << claim.source << "]: " << claim.prediction << "\n";
  std::cout << "cases (" << default_suite_directory() << "):\n";
  for (const auto& file : default_suite()) std::cout << "  " << fs::path(file).filename().string() << "\n";
  return exit_pass;
}

int usage(std::ostream& out, int code) {
  out << "usage: vivv run [CASE.json ...] [--out DIR] [--digits D] [--scalar S] [--jobs J] "
         "[--shard I/N] [--refine]\n"
         "                [--max-seconds S] [--keep-going] [--baseline OLD/report.json "
         "[--baseline-tolerance X]]\n"
         "                [--allow-process [--process-timeout S]]\n"
         "                [--progress|--quiet]\n"
         "       vivv report REPORT.json [MORE.json ...] --out DIR\n"
         "       vivv list\n"
         "       vivv bench reference|del|process\n"
         "       vivv --version\n"
         "run `vivv run --help` for what each option does\n";
  return code;
}

// `vivv run --help`: every option and what it does.
int run_help(std::ostream& out) {
  out << "vivv run [CASE.json ...] [options]: compute each case's claims and write "
         "DIR/report.json,\n"
         "report.html and junit.xml (the default suite when no case file is given). Exit 0 when "
         "every\n"
         "claim passes (or fails as its case expects), 1 when one fails, is inconclusive, errs or "
         "passes\n"
         "unexpectedly, 2 for bad input (nothing written; with --keep-going, a case refused while "
         "it "
         "runs).\n"
         "  --out DIR          where the three files go (default vivv-report); checked before any "
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
         "  --baseline-tolerance X\n"
         "                     the allowed growth of the error constant, a fraction (default 0.1: "
         "10 %)\n"
         "  --keep-going       a case refused while it runs (bad input, past its budget) is "
         "recorded as\n"
         "                     refused in the reports and the others keep their results; exit "
         "still 2\n"
         "  --allow-process    let cases start the programs they name (discretization kind "
         "\"process\",\n"
         "                     protocol vivv-map/1); without it such a case refuses the run\n"
         "  --process-timeout S\n"
         "                     seconds a map program may take for its greeting and each answer "
         "(default 30)\n"
         "  --progress         progress lines on stderr (the default on a terminal)\n"
         "  --quiet            no progress lines\n"
         "  --help, -h         this text\n";
  return exit_pass;
}

}  // namespace
}  // namespace vivv

int main(int argc, char** argv) {
  using namespace vivv;
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
      if (args.size() != 1 ||
          (args[0] != "reference" && args[0] != "del" && args[0] != "process")) {
        std::cerr << "vivv bench: expected one of: reference (the Taylor reference flow against "
                     "Boost.Odeint), del (a DEL step against the L evaluations it needs), process "
                     "(protocol vivv-map/1's overhead per step against a DEL step)\n";
        return exit_bad_input;
      }
      // The benchmarks are a program of their own beside vivv (harness/bench_main.cpp), so that
      // building the tool for a run does not compile them.
      const fs::path bench = fs::read_symlink("/proc/self/exe").parent_path() / "vivv-bench";
      std::error_code missing;
      if (!fs::exists(bench, missing))
        return bad_input("vivv bench runs " + bench.string() +
                         ", which is not built: cmake --build build --target vivv-bench (the test "
                         "command builds it)");
      std::cout.flush();
      const std::string name = "vivv-bench";
      std::vector<char*> argv{const_cast<char*>(name.c_str()), args[0].data(), nullptr};
      execv(bench.c_str(), argv.data());
      return bad_input("vivv bench: cannot run " + bench.string() + ": " + std::strerror(errno));
    }
    if (command == "report") return command_report(args, command_line);
    if (command == "--help" || command == "help") return usage(std::cout, exit_pass);
    if (command == "--version" || command == "version") {
      std::cout << library_versions() << "\n";
      return exit_pass;
    }
    std::cerr << "vivv: unknown command '" << command << "'\n";
    return usage(std::cerr, exit_bad_input);
  } catch (const WorkerCrash& error) {
    std::cerr << "vivv: " << error.what() << "\n";
    return exit_crash;
  } catch (const nlohmann::json::exception& error) {  // a report.json of the wrong shape
    return bad_input(std::string("malformed input: ") + error.what());
  } catch (
      const std::exception& error) {  // CaseError, BadInput, ReportError and anything else: exit 2
    return bad_input(error.what());
  }
}
