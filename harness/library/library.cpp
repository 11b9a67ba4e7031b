// vivv as a library (harness/library/vivv.hpp): runs case files as `vivv run` does and writes the
// same report files.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include "core/numerics/newton.hpp"
#include "harness/process/program.hpp"
#include "harness/library/version.hpp"
#include "harness/library/vivv.hpp"

namespace vivv {
namespace {

// The case file as the report names it: its file name.
std::string report_name(const CaseSpec& spec) {
  return std::filesystem::path(spec.file).filename().string();
}

// What a worker sends back: the case's JSON, or the exception that refused it.
nlohmann::json run_in_worker(const CaseSpec& spec, const RunOptions& options) {
  try {
    return {{"case", case_json(run_case(spec, options.digits, options.refine, options.progress))}};
  } catch (const CaseError& error) {
    return {{"exception", "case"},
            {"file", error.file},
            {"field", error.field},
            {"message", error.what()}};
  } catch (const SolverError& error) {
    return {{"exception", "solver"}, {"message", error.what()}};
  } catch (const SingularLagrangianError& error) {
    return {{"exception", "singular"}, {"message", error.what()}};
  } catch (const std::domain_error& error) {
    return {{"exception", "domain"}, {"message", error.what()}};
  } catch (const std::exception& error) {
    return {{"exception", "other"}, {"message", error.what()}};
  }
}

// The worker's exception, thrown again in this process as its own type.
[[noreturn]] void rethrow(const nlohmann::json& sent) {
  const std::string kind = sent["exception"], message = sent["message"];
  if (kind == "case") {
    // CaseError composes "file: field 'x': message" itself: pass the message part once.
    const std::string file = sent["file"], field = sent["field"];
    const std::string prefix = file + ": " + (field.empty() ? "" : "field '" + field + "': ");
    throw CaseError(file, field,
                    message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message);
  }
  if (kind == "solver") throw SolverError(message);
  if (kind == "singular") throw SingularLagrangianError(message);
  if (kind == "domain") throw std::domain_error(message);
  throw std::runtime_error(message);
}

struct Worker {
  pid_t pid;
  int output;  // the read end of its pipe
  std::string received;
  std::chrono::steady_clock::time_point deadline;
};

// Each case in a worker process forked from this one, at most options.jobs at once; the
// cases' JSON in order. A refused case throws its exception here once every worker has ended.
std::vector<nlohmann::json> run_in_workers(const std::vector<CaseSpec>& specs,
                                           const RunOptions& options) {
  using Clock = std::chrono::steady_clock;
  std::vector<nlohmann::json> cases(specs.size());
  std::map<std::size_t, Worker> running;
  std::optional<nlohmann::json> refusal;  // the first case's exception
  std::size_t next = 0;
  auto stop_all = [&] {
    for (auto& [index, worker] : running) {
      kill(worker.pid, SIGKILL);
      waitpid(worker.pid, nullptr, 0);
      close(worker.output);
    }
    running.clear();
  };
  while ((next < specs.size() && !refusal) || !running.empty()) {
    if (next < specs.size() && !refusal && static_cast<int>(running.size()) < options.jobs) {
      int pipe_ends[2];
      if (pipe2(pipe_ends, O_CLOEXEC) != 0) {
        stop_all();
        throw std::runtime_error(std::string("vivv::run: cannot create a pipe for a worker: ") +
                                 std::strerror(errno));
      }
      const pid_t pid = fork();
      if (pid == 0) {
        close(pipe_ends[0]);
        const std::string text = run_in_worker(specs[next], options)
                                     .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        std::size_t written = 0;
        while (written < text.size()) {
          const ssize_t wrote = ::write(pipe_ends[1], text.data() + written, text.size() - written);
          if (wrote <= 0 && errno != EINTR) break;
          if (wrote > 0) written += static_cast<std::size_t>(wrote);
        }
        end_map_processes();
        _exit(written == text.size() ? 0 : 1);
      }
      close(pipe_ends[1]);
      if (pid < 0) {
        close(pipe_ends[0]);
        stop_all();
        throw std::runtime_error(std::string("vivv::run: cannot start a worker process: ") +
                                 std::strerror(errno));
      }
      const Clock::time_point deadline =
          options.max_seconds ? Clock::now() + std::chrono::seconds(*options.max_seconds)
                              : Clock::time_point::max();
      running.emplace(next++, Worker{pid, pipe_ends[0], "", deadline});
      continue;
    }
    // Read what the workers write; a worker whose pipe closed has ended.
    std::vector<pollfd> ready;
    std::vector<std::size_t> order;
    for (const auto& [index, worker] : running)
      ready.push_back({worker.output, POLLIN, 0}), order.push_back(index);
    if (::poll(ready.data(), ready.size(), 100) < 0 && errno != EINTR) {
      stop_all();
      throw std::runtime_error(std::string("vivv::run: poll: ") + std::strerror(errno));
    }
    for (std::size_t k = 0; k < ready.size(); ++k) {
      Worker& worker = running.at(order[k]);
      if (Clock::now() > worker.deadline) {
        const std::string file = specs[order[k]].file;
        stop_all();
        throw std::runtime_error(file + ": the case ran past its budget of " +
                                 std::to_string(*options.max_seconds) + " s (max_seconds)");
      }
      if (!ready[k].revents) continue;
      char chunk[65536];
      const ssize_t got = ::read(worker.output, chunk, sizeof chunk);
      if (got > 0) {
        worker.received.append(chunk, static_cast<std::size_t>(got));
        continue;
      }
      if (got < 0 && errno == EINTR) continue;
      int status = 0;
      waitpid(worker.pid, &status, 0);
      close(worker.output);
      const std::size_t index = order[k];
      const std::string received = std::move(worker.received);
      running.erase(index);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || received.empty()) {
        const std::string how = WIFSIGNALED(status)
                                    ? "was ended by signal " + std::to_string(WTERMSIG(status))
                                    : "exited with status " + std::to_string(WEXITSTATUS(status));
        stop_all();
        throw std::runtime_error(specs[index].file + ": its worker process " + how +
                                 " without a result");
      }
      nlohmann::json sent = nlohmann::json::parse(received);
      if (sent.contains("exception")) {
        if (!refusal) refusal = sent;
      } else {
        cases[index] = std::move(sent["case"]);
      }
      break;  // `running` changed: poll again
    }
  }
  if (refusal) rethrow(*refusal);
  return cases;
}

}  // namespace

Run run(const std::vector<std::string>& case_files, const RunOptions& options) {
  if (options.jobs < 1 || options.jobs > 64)
    throw std::invalid_argument("vivv::run: jobs must be 1 … 64");
  if (options.max_seconds && *options.max_seconds < 1)
    throw std::invalid_argument("vivv::run: max_seconds must be at least 1");
  if (options.digits && (*options.digits < 20 || *options.digits > maximum_digits))
    throw std::invalid_argument("vivv::run: digits must be 20 … " + std::to_string(maximum_digits));
  if (!(options.process_timeout >= 0.1 && options.process_timeout <= 3600))
    throw std::invalid_argument("vivv::run: process_timeout must be 0.1 … 3600 seconds");
  Run result;
  std::set<std::string> names;
  std::vector<CaseSpec> specs;
  for (const auto& file : case_files) {
    specs.push_back(read_case_file(file));
    if (!names.insert(specs.back().name).second)
      throw CaseError(file, "name",
                      "'" + specs.back().name + "' is the name of another case of this run");
  }
  // The options against every case before any computes, as vivv run checks them.
  for (auto& spec : specs) {
    check_precision_options(spec, options.scalar, options.digits);
    if (options.scalar) spec.scalar = *options.scalar;
    permit_process(spec, options.allow_process, options.process_timeout,
                   "RunOptions::allow_process");
  }
  std::vector<nlohmann::json> cases;
  if (options.jobs == 1 && !options.max_seconds) {
    for (const auto& spec : specs) {
      result.results.push_back(run_case(spec, options.digits, options.refine, options.progress));
      cases.push_back(case_json(result.results.back()));
    }
  } else {
    cases = run_in_workers(specs, options);
  }
  for (std::size_t i = 0; i < specs.size(); ++i) cases[i]["file"] = report_name(specs[i]);
  result.report = assemble_report(cases, {"vivv::run (library)", library_versions()});
  return result;
}

std::vector<std::string> write_reports(const Run& run, const std::string& directory) {
  std::filesystem::create_directories(directory);
  return write_report_directory(directory, run.report);
}

void print_table(std::ostream& out, const Run& run) { print_claims_table(out, run.report); }

bool holds(const Run& run) { return run_succeeded(run.report["summary"]); }

std::string failures(const Run& run) {
  std::string lines;
  for (const auto& result : run.report["cases"])
    for (const auto& claim : result["claims"]) {
      const std::string verdict = claim["verdict"];
      if (verdict != "pass" && verdict != "xfail")
        lines += result["name"].get<std::string>() + " / " + claim["id"].get<std::string>() + ": " +
                 verdict + ": " + claim["explanation"].get<std::string>() + "\n";
    }
  return lines;
}

}  // namespace vivv
