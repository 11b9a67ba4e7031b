// Running the cases of `vivv run`: one at a time or in --jobs worker processes, each under its
// --max-seconds budget, with progress lines, and the signals that stop a run cleanly.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
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
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/lagrangian/lagrangian.hpp"
#include "core/numerics/newton.hpp"
#include "harness/command_line/command_line.hpp"
#include "harness/process/program.hpp"
#include "harness/run/run_case.hpp"
#include "harness/context/shared_references.hpp"
#include "reports/report.hpp"
#include "core/platform/signals.hpp"
#include "core/platform/text.hpp"

namespace fs = std::filesystem;

namespace vivv::command_line {

namespace {

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

// In a --jobs worker, the pipe to the parent, which alone writes progress lines to stderr (-1:
// this process writes them itself).
int progress_fd = -1;

// Progress on stderr, one line every few seconds per case (documented in README, "Progress"):
//   [ELAPSED s] CASE: WHAT              the phase the case is in, when it changed
//   [ELAPSED s] … still: CASE: WHAT (N s so far)   the same phase, still running
// ELAPSED counts from the case's start; in a run of several cases it reads "ELAPSED s, case I of
// N" (I the case's place in the run's list). The case's first message is written at once; then a
// thread that only prints writes the phase every `interval`, never a line per step count. Each
// line is one write() of at most a few hundred bytes — in a worker, into the pipe the parent
// reads (atomic below PIPE_BUF), so that lines of parallel cases never interleave. Lives for
// one case (in its worker, after fork).
class ProgressPrinter {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr auto interval = std::chrono::seconds(3);

  // `place`: ", case I of N" in a run of several cases, else empty.
  explicit ProgressPrinter(std::string place)
      : place_(std::move(place)), started_(Clock::now()), last_line_(started_), phase_started_(started_) {
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
    if (message != phase_) phase_ = message, phase_started_ = Clock::now();
    if (!written_) write(phase_), written_ = true, printed_ = phase_, last_line_ = Clock::now();
  }

 private:
  void beat() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, std::chrono::milliseconds(250));
      if (stop_ || phase_.empty() || Clock::now() - last_line_ < interval) continue;
      if (phase_ != printed_) {
        write(phase_);
      } else {
        const double running = std::chrono::duration<double>(Clock::now() - phase_started_).count();
        std::ostringstream line;
        line << "… still: " << phase_ << " (" << std::fixed << std::setprecision(0) << running
             << " s so far)";
        write(line.str());
      }
      printed_ = phase_;
      last_line_ = Clock::now();
    }
  }
  void write(const std::string& message) const {
    const double elapsed = std::chrono::duration<double>(Clock::now() - started_).count();
    std::ostringstream line;
    line << "[" << std::fixed << std::setprecision(1) << elapsed << " s" << place_ << "] "
         << terminal_safe(cut_at_character(message, 600)) << "\n";
    const std::string text = line.str();
    if (progress_fd >= 0) {
      [[maybe_unused]] auto written = ::write(progress_fd, text.data(), text.size());
    } else {
      std::cerr << text << std::flush;
    }
  }

  const std::string place_;
  const Clock::time_point started_;
  Clock::time_point last_line_, phase_started_;
  std::string phase_, printed_;
  bool written_ = false, stop_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

std::function<void(const std::string&)> progress_printer(bool enabled, std::size_t index, std::size_t count) {
  if (!enabled) return {};
  auto printer = std::make_shared<ProgressPrinter>(
      count > 1 ? ", case " + std::to_string(index + 1) + " of " + std::to_string(count) : "");
  return [printer](const std::string& message) { printer->print(message); };
}

// What a refusal or a case that could not run records of its error: at most 2000 bytes, in
// UTF-8, its beginning and its end (the program, the request and the failure come first, the
// program's standard error last, and the end of that — the exception's line — says why), cut in
// the middle between characters.
std::string recorded_message(const std::exception& error) {
  return repaired_utf8(cut_in_the_middle(error.what(), 2000));
}

// Runs one case, the index-th of count; solver failures and non-regular Lagrangians are bad input.
nlohmann::json run_one(const CaseSpec& spec, const RunOptions& options, std::size_t index, std::size_t count) {
  try {
    CaseSpec effective = spec;
    if (options.scalar) effective.scalar = *options.scalar;
    if (options.digits && effective.scalar != "mpfr")
      throw BadInput("--digits sets the MPFR working precision, and this case runs in \"" +
                     effective.scalar + "\"");
    std::function<void(const std::string&)> progress = progress_printer(options.progress, index, count);
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
  } catch (const MapProcessError& error) {  // the program, not the input: the case could not run
    throw CouldNotRun(spec.file + ": " + error.what());
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

}  // namespace

CaseSpec within_reading_budget(const std::string& file, const RunOptions& options,
                               const std::function<CaseSpec()>& read) {
  if (!options.max_seconds) return read();
  budget_seconds = *options.max_seconds;
  const bool keeps_going = budget_keeps_going;
  budget_keeps_going = false;  // a case file not read refuses the whole run, --keep-going or not
  note_phase(file, "reading the case");
  signal(SIGALRM, budget_exhausted);
  alarm(static_cast<unsigned>(budget_seconds));
  CaseSpec spec;
  try {
    spec = read();
  } catch (...) {
    alarm(0);
    budget_keeps_going = keeps_going;
    throw;
  }
  alarm(0);
  budget_keeps_going = keeps_going;
  return spec;
}

namespace {

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

// Each case's reference key (harness/context/shared_references.hpp), as it will run: --scalar and
// --digits applied.
std::vector<std::string> reference_keys(const std::vector<CaseSpec>& specs, const RunOptions& options) {
  std::vector<std::string> keys;
  for (CaseSpec effective : specs) {
    if (options.scalar) effective.scalar = *options.scalar;
    if (options.digits) effective.digits = *options.digits;
    keys.push_back(reference_key(effective));
  }
  return keys;
}

// The references the cases from `from` on still need, in a run that computes them in order: kept,
// every other one released.
void keep_references_from(const std::vector<std::string>& keys, std::size_t from) {
  keep_references(std::set<std::string>(keys.begin() + static_cast<std::ptrdiff_t>(from), keys.end()));
}

// Each case's reference key with its initial state and T: cases that agree on it share the flow's
// cross-check at T as well.
std::vector<std::string> check_keys(const std::vector<CaseSpec>& specs, const std::vector<std::string>& keys) {
  std::vector<std::string> checks;
  for (std::size_t i = 0; i < specs.size(); ++i)
    checks.push_back(keys[i] + '\n' + nlohmann::json({specs[i].q, specs[i].w, specs[i].final_time}).dump());
  return checks;
}

// The case a worker computes next, marked started: the first not started on the reference of
// the case it computed before (`previous`: that flow is in its memory) — from the same state to the
// same T first, whose cross-check it holds too — else the first not started; none when every case
// has started. Workers take cases as they finish, so a long case does not hold back the others,
// and a reference is computed at most once per worker.
std::optional<std::size_t> next_case(std::vector<bool>& started, const std::vector<std::string>& keys,
                                     const std::vector<std::string>& checks, std::optional<std::size_t> previous) {
  std::optional<std::size_t> chosen;
  for (std::size_t i = 0; i < started.size() && !chosen; ++i)
    if (!started[i] && previous && checks[i] == checks[*previous]) chosen = i;
  for (std::size_t i = 0; i < started.size() && !chosen; ++i)
    if (!started[i] && previous && keys[i] == keys[*previous]) chosen = i;
  for (std::size_t i = 0; i < started.size() && !chosen; ++i)
    if (!started[i]) chosen = i;
  if (chosen) started[*chosen] = true;
  return chosen;
}

// A line from `fd` without its newline (a worker's question, the parent's answer); none at the end
// of the stream or on an error.
std::optional<std::string> read_line(int fd) {
  std::string line;
  char c = 0;
  for (;;) {
    const ssize_t got = ::read(fd, &c, 1);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return std::nullopt;
    if (c == '\n') return line;
    line += c;
  }
}

bool write_line(int fd, const std::string& line) {
  const std::string text = line + "\n";
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t put = ::write(fd, text.data() + done, text.size() - done);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) return false;
    done += static_cast<std::size_t>(put);
  }
  return true;
}

}  // namespace

std::vector<nlohmann::json> run_all(const std::vector<CaseSpec>& specs, const RunOptions& options) {
  std::vector<nlohmann::json> results(specs.size());
  const std::vector<std::string> keys = reference_keys(specs, options);
  if (options.reference_cache) {
    set_reference_cache(fs::path(*options.reference_cache));
    try {
      executable_fingerprint();  // read once, before any case computes or a worker forks
    } catch (const std::exception& error) {
      throw BadInput(error.what());
    }
  }
  if (options.jobs == 1 && !options.keep_going) {
    for (std::size_t i = 0; i < specs.size(); ++i) {
      keep_references_from(keys, i);
      try {
        results[i] = run_one(specs[i], options, i, specs.size());
      } catch (const CouldNotRun& error) {
        results[i] = {{"could_not_run", recorded_message(error)}};
      } catch (...) {
        keep_references({});
        throw;
      }
    }
    keep_references({});  // before the statics of MPFR and of the process go
    return results;
  }
  // A private directory (mode 0700, unpredictable name) for the workers' results, each file
  // created exclusively and never through a link.
  std::string work_template = (fs::temp_directory_path() / "vivv-XXXXXX").string();
  if (!mkdtemp(work_template.data()))
    throw BadInput("cannot create a private temporary directory under " + fs::temp_directory_path().string());
  fs::path work = work_template;
  // The workers' progress lines come through one pipe, and the parent alone writes them.
  int progress_pipe[2] = {-1, -1};
  if (options.progress && pipe2(progress_pipe, O_CLOEXEC | O_NONBLOCK) != 0)
    progress_pipe[0] = progress_pipe[1] = -1;
  std::string progress_buffer;
  auto forward_progress = [&]() {
    if (progress_pipe[0] < 0) return;
    char chunk[4096];
    ssize_t got = 0;
    while ((got = ::read(progress_pipe[0], chunk, sizeof chunk)) > 0) progress_buffer.append(chunk, static_cast<std::size_t>(got));
    const std::size_t end = progress_buffer.rfind('\n');
    if (end == std::string::npos) return;
    std::cerr << progress_buffer.substr(0, end + 1) << std::flush;
    progress_buffer.erase(0, end + 1);
  };
  // A worker: the case it computes (none once it was told there is no other), and the parent's end
  // of the socket on which it asks for the next one ("next" → the case's index, or "none").
  struct Worker {
    std::optional<std::size_t> current;
    int socket = -1;
  };
  NoteInterrupts notes;
  const pid_t parent = getpid();
  std::map<pid_t, Worker> workers;
  std::vector<bool> started(specs.size(), false);
  const std::vector<std::string> checks = check_keys(specs, keys);
  std::string failures, crashes;
  // What the worker wrote of a case: its result, why it could not run, or why it was refused.
  auto written = [&](std::size_t index, const char* extension) -> std::optional<std::string> {
    std::ifstream in(work / (std::to_string(index) + extension));
    if (!in) return std::nullopt;
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  // The case's result as its worker wrote it; false if it wrote none.
  auto collect = [&](std::size_t index) {
    if (auto result = written(index, ".json")) {
      results[index] = nlohmann::json::parse(*result);
    } else if (auto message = written(index, ".could-not-run")) {
      results[index] = {{"could_not_run", message->empty() ? "its map program failed in the worker process" : *message}};
    } else {
      return false;
    }
    return true;
  };
  // A worker that ended: the case it was computing, collected, or what ended it said.
  auto ended = [&](pid_t pid, int status) {
    const Worker worker = workers.at(pid);
    workers.erase(pid);
    close(worker.socket);
    const bool clean = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!worker.current) {
      if (!clean) failures += "a worker process failed after its cases (exit status " + std::to_string(status) + ")\n";
      return;
    }
    const std::size_t index = *worker.current;
    if (collect(index) && clean) return;
    if (WIFSIGNALED(status)) {  // no message of its own: say what ended it
      const int signal = WTERMSIG(status);
      crashes += specs[index].file + ": its worker process was ended by signal " +
                 std::to_string(signal) + " (" + strsignal(signal) + ")" +
                 (signal == SIGKILL ? ", perhaps by the kernel for want of memory" : "") + "\n";
      return;
    }
    if (options.keep_going && WIFEXITED(status) && WEXITSTATUS(status) == exit_bad_input) {
      std::string message = written(index, ".refused").value_or("");
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
    failures += specs[index].file + " failed in its worker process\n";
  };
  // A worker's question: its case is done (collected), and it is given the next one, or none.
  auto answer = [&](Worker& worker) {
    const std::optional<std::string> question = read_line(worker.socket);
    if (!question) return;  // it ended: ended() says how
    if (worker.current && !collect(*worker.current))
      failures += specs[*worker.current].file + ": its worker process asked for another case without a result\n";
    worker.current = next_case(started, keys, checks, worker.current);
    write_line(worker.socket, worker.current ? std::to_string(*worker.current) : "none");
  };
  auto unstarted = [&] { return std::find(started.begin(), started.end(), false) != started.end(); };
  while ((unstarted() || !workers.empty()) && !interrupted_by) {
    if (unstarted() && static_cast<int>(workers.size()) < options.jobs) {
      const std::size_t first = *next_case(started, keys, checks, std::nullopt);
      int sockets[2] = {-1, -1};
      if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0) sockets[0] = sockets[1] = -1;
      std::cout.flush();
      std::cerr.flush();
      pid_t pid = 0;
      {
        // The worker starts with vivv's own dispositions before any signal reaches it.
        DeferInterrupts defer;
        pid = sockets[0] < 0 ? -1 : fork();
        if (pid == 0) {
          notes.restore();
          if (progress_pipe[0] >= 0) {
            close(progress_pipe[0]);
            progress_fd = progress_pipe[1];
            fcntl(progress_fd, F_SETFL, 0);  // blocking: a line is never dropped
          }
          close(sockets[0]);
          for (const auto& [other, worker] : workers) close(worker.socket);
          // A worker never outlives the run: when the parent ends, however (SIGKILL included),
          // the kernel sends the worker SIGTERM; a parent already gone ends the worker now.
          prctl(PR_SET_PDEATHSIG, SIGTERM);
          if (getppid() != parent) std::_Exit(128 + SIGTERM);
        }
      }
      if (pid == 0) {
        // The worker's cases one after another, each result in its file; a case that could not run
        // is recorded and the worker asks for the next one, as without --jobs. A refusal ends it, and
        // under --keep-going so does every case (a --max-seconds budget ends the worker with its case).
        int code = 0;
        std::size_t index = first;
        for (bool more = true; more && code == 0;) {
          keep_references({keys[index]});
          if (options.keep_going)
            refusal_fd = ::open((work / (std::to_string(index) + ".refused")).c_str(),
                                O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
          try {
            write_exclusively(work / (std::to_string(index) + ".json"),
                              run_one(specs[index], options, index, specs.size())
                                  .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
          } catch (const CouldNotRun& error) {
            try {
              write_exclusively(work / (std::to_string(index) + ".could-not-run"), recorded_message(error));
            } catch (const std::exception& unwritten) {
              code = bad_input(std::string(error.what()) + " (and its record: " + unwritten.what() + ")");
            }
          } catch (const std::exception& error) {
            // Under --keep-going the refusal is recorded, and the console lists it with the refused
            // cases: printed here as well, it appeared twice.
            if (refusal_fd >= 0) {
              const std::string message = recorded_message(error);
              [[maybe_unused]] auto put = ::write(refusal_fd, message.data(), message.size());
              code = exit_bad_input;
            } else {
              code = bad_input(error.what());
            }
          }
          if (code != 0 || options.keep_going || !write_line(sockets[1], "next")) break;
          const std::optional<std::string> reply = read_line(sockets[1]);
          more = reply && *reply != "none";
          if (more) index = std::stoul(*reply);
        }
        std::_Exit(code);
      }
      if (pid < 0) {
        // No worker can start (the process limit): stop those running, remove their directory,
        // and say so; nothing is left behind.
        const int reason = errno;
        for (int fd : sockets)
          if (fd >= 0) close(fd);
        for (const auto& [running_pid, worker] : workers) kill(running_pid, SIGTERM);
        for (const auto& [running_pid, worker] : workers) waitpid(running_pid, nullptr, 0);
        std::error_code ignored;
        fs::remove_all(work, ignored);
        throw BadInput(std::string("cannot start a worker process for --jobs ") +
                       std::to_string(options.jobs) + ": " + std::strerror(reason) +
                       " (a lower --jobs, or the process limit ulimit -u, decides)");
      }
      close(sockets[1]);
      workers[pid] = {first, sockets[0]};
      continue;
    }
    // Every 50 ms at most: the workers' questions and progress lines, and the workers that ended.
    std::vector<struct pollfd> watched;
    std::vector<pid_t> asking;
    if (progress_pipe[0] >= 0) watched.push_back({progress_pipe[0], POLLIN, 0});
    for (const auto& [pid, worker] : workers) {
      watched.push_back({worker.socket, POLLIN, 0});
      asking.push_back(pid);
    }
    if (poll(watched.data(), watched.size(), 50) > 0) {
      const std::size_t offset = progress_pipe[0] >= 0 ? 1 : 0;
      if (offset && watched[0].revents) forward_progress();
      for (std::size_t k = 0; k < asking.size(); ++k)
        if (watched[offset + k].revents & POLLIN) answer(workers.at(asking[k]));
    }
    int status = 0;
    pid_t pid = 0;
    while ((pid = waitpid(-1, &status, WNOHANG)) > 0) ended(pid, status);
  }
  if (interrupted_by) {
    // Interrupted: stop the workers, remove what they wrote, and end by the same signal
    // (no report is written; an earlier one stays as it was).
    for (const auto& [pid, worker] : workers) kill(pid, SIGTERM);
    for (const auto& [pid, worker] : workers) waitpid(pid, nullptr, 0);
    std::error_code ignored;
    fs::remove_all(work, ignored);
    const int signal = interrupted_by;
    notes.restore();
    std::cerr << "vivv: interrupted (signal " << signal << "); no report written\n";
    raise(signal);
    std::_Exit(128 + signal);
  }
  forward_progress();
  if (!progress_buffer.empty()) std::cerr << progress_buffer << "\n";
  for (int fd : progress_pipe)
    if (fd >= 0) close(fd);
  fs::remove_all(work);
  if (!crashes.empty())
    throw WorkerCrash(crashes + failures + "(no report written; exit " +
                      std::to_string(exit_crash) + ": a crash, not a verdict and not bad input)");
  if (!failures.empty()) throw BadInput(failures + "(see the messages above)");
  return results;
}

}  // namespace vivv::command_line
