// A one-step map in another program, spoken to over its standard input and output with one
// JSON object per line: protocol vivv-map/1 (docs/process-protocol.md). MapProcess is the
// program's side of it as vivv sees it: starting the program (never through a shell, in the
// case file's folder, in a process group of its own that a terminal's signals do not reach),
// the greeting, one request and its answer at a time within a timeout, and its end. Nothing
// outlives vivv: the destructor closes the program's input and kills what is left of its
// group; vivv ended by SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1 or SIGUSR2 kills every group
// first; the kernel kills the program itself when vivv dies by SIGKILL (PR_SET_PDEATHSIG).
#pragma once

#include <sys/types.h>

#include <algorithm>
#include <functional>
#include <optional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases/case_file.hpp"

namespace vivv {

// The protocol's name and version, in the greeting and in its answer.
inline constexpr const char* map_protocol = "vivv-map/1";

// The extension a program takes up to be sent several requests before it answers the first
// (MapProcess::requests).
inline constexpr const char* pipeline_extension = "pipeline";

// The deepest JSON an answer may hold: an object of arrays of strings is 3 levels (a Jacobian's
// array of arrays, 4); deeper answers are refused before they are built.
inline constexpr int maximum_answer_depth = 8;

// A program that cannot be started, declines, dies, hangs or breaks the protocol while its case
// runs: the case could not run (recorded in the reports, exit 4), the message naming the program
// and the request it failed.
struct MapProcessError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class MapProcess {
 public:
  struct Options {
    std::vector<std::string> command;  // the program and its arguments
    std::string directory;             // its working directory: the case file's folder
    double timeout_seconds = 30;       // for the greeting and for each answer
  };

  // Starts the program and greets it with `greeting` (which carries the protocol's name);
  // throws MapProcessError when it cannot start, declines ({"error": …}) or answers otherwise.
  MapProcess(Options options, const nlohmann::json& greeting);
  ~MapProcess();
  MapProcess(const MapProcess&) = delete;
  MapProcess& operator=(const MapProcess&) = delete;

  // Sends one request and returns the answer, a JSON object; an answer {"error": …}, no answer
  // in time, an early exit or a line that is not a JSON object throws MapProcessError naming the
  // request.
  nlohmann::json request(const nlohmann::json& message);

  // Requests next() gives, until it gives none, each answer (an object, checked as request()
  // checks it) passed to read() in order, with answering() naming its request. A program that took
  // up the extension "pipeline" (it reads its requests a line at a time and answers each in turn)
  // is sent up to `pipelined_requests` ahead: it works on one while vivv reads the last answer
  // and makes the next request, and no request waits for the pipe's round trip; the text is written
  // as its input takes it and the answers read as they come, so neither side blocks on a full
  // pipe. Where read() or next() throws, the requests already sent are answered and their answers
  // left unread before the exception goes on: the next request is answered by its own answer. Any
  // other program gets one request at a time.
  void requests(const std::function<std::optional<nlohmann::json>()>& next,
                const std::function<void(const nlohmann::json&)>& read);
  static constexpr std::size_t pipelined_requests = 8;

  // The time "t" every step's request (one with an "h") carries from now on, a decimal: the time
  // of the request's first state, for a case whose Lagrangian depends on time (empty: none is
  // sent, as for any other case). A request that names its own "t" keeps it.
  void set_time(std::string t) { time_ = std::move(t); }

  // "'python3 step.py'" for messages.
  std::string name() const;
  // Requests answered so far (the greeting not counted).
  long requests() const { return requests_; }
  // The longest answer line read, in characters (from the greeting's n and D, at least 1 MiB).
  std::size_t longest_line() const { return longest_line_; }
  // Whether the program took up `extension` (offered in the greeting's "extensions", named in
  // its answer's): "jacobian", its own Jacobian in each answer.
  bool uses_extension(const std::string& extension) const {
    return std::find(extensions_.begin(), extensions_.end(), extension) != extensions_.end();
  }
  // A MapProcessError naming the program, the request just answered (at most 300 characters of
  // it) and `what` is wrong with its answer.
  [[noreturn]] void fail_answer(const std::string& what) const;
  // "the map program 'X' (in DIR), request k {…}": who answered what, for a message.
  std::string answering() const;

 private:
  void greet(const nlohmann::json& greeting);
  // `message` with the time set_time gave, where it is a step's request without a "t" of its own.
  std::string line_of(const nlohmann::json& message) const;
  // The answer `line` to `request_name` as JSON, nested at most maximum_answer_depth levels;
  // fail() otherwise.
  nlohmann::json parse_answer(const std::string& line, const std::string& request_name);
  // Closes its input, waits up to a second for it to end, kills its group and reaps it.
  void stop() noexcept;
  void send(const std::string& line, const std::string& request_name);
  // The next answer line; while it waits, writes what its input takes of `outgoing` (requests
  // sent ahead, erased as they are written) where there is any.
  std::string receive(const std::string& request_name, std::string* outgoing = nullptr);
  // Writes what the program's input takes of `outgoing` now, erasing it; never waits.
  void write_ahead(std::string& outgoing);
  // `reply` to `request_name` as an answer object; fail() for an error answer or anything else.
  nlohmann::json checked_answer(const std::string& reply, const std::string& request_name);
  [[noreturn]] void fail(const std::string& request_name, const std::string& what);
  // "exited with status 1" / "was ended by signal 9 (Killed)", after it closed its output.
  std::string how_it_ended();
  void drain_stderr();

  Options options_;
  // "; python3 is /usr/bin/python3": where PATH took a program named without a '/', for messages
  // (another python3 first on PATH — pyenv, conda — is the commonest reason a program cannot start).
  std::string resolved_note_;
  pid_t pid_ = -1;
  int input_ = -1, output_ = -1, errors_ = -1;  // vivv's ends of the three pipes
  std::string buffer_;                          // what was read of the answer line so far
  std::size_t longest_line_ = 0;  // the longest answer line read: from the greeting's n and D
  std::string stderr_tail_;  // the last 2000 characters the program wrote to its stderr
  std::string last_request_;
  std::string token_;  // descendant_token=<vivv's pid>-<count>, in the program's environment
  long requests_ = 0;
  std::vector<std::string> extensions_;  // the offered extensions its greeting's answer named
  std::string time_;                     // the "t" of its step requests (set_time), or none
};

// What every run does with a case whose discretization is a process (kind "process") before
// anything computes: lets it start its program with the given timeout when `allowed`, else a
// CaseError naming the program and `how_to_allow` (the flag, or the library's option). Other
// kinds are left as they are.
void permit_process(CaseSpec& spec, bool allowed, double timeout_seconds,
                    const std::string& how_to_allow);

// The environment variable that marks every process a map program starts (inherited; its value
// names vivv's process and the program), for end_program_tree.
inline constexpr const char* descendant_token = "VIVV_MAP_PROGRAM";

// Kills the map program `leader` (a child of this process), its process group and every process
// below it, and reaps them: also the helpers that left the group by setsid, setpgid or a double
// fork, which reach this process — a child subreaper (PR_SET_CHILD_SUBREAPER) while programs
// run — with `token` ("NAME=value") in their environment, and are killed with everything below
// them, until none is left.
void end_program_tree(pid_t leader, const std::string& token) noexcept;

// Kills the process groups of every running map program (async-signal-safe: for a signal
// handler, e.g. the --max-seconds budget's, that ends vivv).
void end_map_processes() noexcept;

// The number of significant digits of a decimal number as the protocol writes it
// ("-1.2500e-3" has 5; trailing zeros count), 0 for the number zero, −1 for text that is not
// a decimal number ([+-]digits[.digits][e[+-]digits], digits on at least one side of a point).
int significant_digits(const std::string& text);

}  // namespace vivv
