#include "harness/process/program.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "core/platform/signals.hpp"
#include "core/platform/text.hpp"
#include "harness/process/program_internals.hpp"

namespace fs = std::filesystem;

namespace vivv {
using program_internals::Clock, program_internals::error_text, program_internals::shortened;

namespace {

// The longest line vivv reads from a program: an answer is 2n decimal strings, and with the
// extension "jacobian" (2n)² more, each of the greeting's D digits with its sign, point, exponent,
// quotes and comma. Twice that for spaces a program may add, and never less than 1 MiB: a
// 38-atom cluster in space (n = 114) sends a Jacobian of 1.3 MB at D = 17, which a fixed 1 MiB
// refused as "a line longer than 1048576 characters".
std::size_t longest_line_for(const nlohmann::json& greeting) {
  const double n = greeting.value("dimension", 1.0), digits = greeting.value("digits", 17.0);
  const double numbers = 2 * n + 4 * n * n;
  const double characters = 2 * numbers * (digits + 16) + 4096;
  return static_cast<std::size_t>(std::max(characters, double(1 << 20)));
}

// The process groups of the running programs, for the signal handler: 0 is a free slot.
constexpr int group_slots = 64;
volatile sig_atomic_t running_groups[group_slots] = {};

void register_group(pid_t group) {
  for (auto& slot : running_groups)
    if (slot == 0) {
      slot = group;
      return;
    }
  throw MapProcessError("more than " + std::to_string(group_slots) + " map programs at once");
}

void unregister_group(pid_t group) {
  for (auto& slot : running_groups)
    if (slot == group) slot = 0;
}

constexpr std::array<int, 6> ending_signals{SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2};

extern "C" void end_map_processes_and_reraise(int signal) {
  end_map_processes();
  ::signal(signal, SIG_DFL);
  raise(signal);
}

// Once per process, before the first program starts: the signals that end vivv kill the
// programs first (where vivv has its default action for them), and a program that closed its
// input makes a write fail with EPIPE instead of ending vivv by SIGPIPE.
void prepare_signals() {
  static bool prepared = false;
  if (prepared) return;
  prepared = true;
  for (int signal : ending_signals) {
    struct sigaction current {};
    sigaction(signal, nullptr, &current);
    if (current.sa_handler != SIG_DFL) continue;  // ignored, or a handler of vivv's own
    struct sigaction action {};
    action.sa_handler = end_map_processes_and_reraise;
    sigemptyset(&action.sa_mask);
    sigaction(signal, &action, nullptr);
  }
  ::signal(SIGPIPE, SIG_IGN);
}

// The program to exec, as an absolute path: a name without '/' is looked up on PATH (a relative
// entry, or an empty one meaning ".", relative to vivv's working directory, where the lookup
// found it), a path is relative to the case file's folder. The program starts in that folder, so
// a relative path here would name another file there: the program found is the program run.
std::string resolve_program(const std::string& program, const std::string& directory) {
  auto runnable = [](const fs::path& path) {
    std::error_code error;
    return fs::is_regular_file(path, error) && ::access(path.c_str(), X_OK) == 0;
  };
  if (program.find('/') != std::string::npos) {
    fs::path path =
        fs::path(program).is_absolute() ? fs::path(program) : fs::path(directory) / program;
    if (!runnable(path))
      throw MapProcessError("the map program '" + quoted_text(program, 200) +
                            "' is not an executable file (looked for " +
                            quoted_text(path.string(), 400) + ")");
    return fs::absolute(path).lexically_normal().string();
  }
  const char* path_variable = std::getenv("PATH");
  std::stringstream entries(path_variable ? path_variable : "/usr/local/bin:/usr/bin:/bin");
  std::string entry;
  while (std::getline(entries, entry, ':')) {
    const fs::path candidate = (entry.empty() ? fs::path(".") : fs::path(entry)) / program;
    if (runnable(candidate)) return fs::absolute(candidate).lexically_normal().string();
  }
  throw MapProcessError("the map program '" + quoted_text(program, 200) + "' is not on PATH (" +
                        quoted_text(path_variable ? path_variable : "unset", 400) + ")");
}

// The processes of the machine as (pid, parent pid), from /proc/<pid>/stat ("pid (comm) state
// ppid …"; comm may hold spaces and parentheses, so the fields are read after the last ')').
std::vector<std::pair<pid_t, pid_t>> process_parents() {
  std::vector<std::pair<pid_t, pid_t>> parents;
  std::error_code error;
  for (fs::directory_iterator entry("/proc", error), end; !error && entry != end;
       entry.increment(error)) {
    const std::string name = entry->path().filename().string();
    if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
    std::ifstream in(entry->path() / "stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;  // gone meanwhile
    std::istringstream fields(stat.substr(close + 1));
    char state = 0;
    long ppid = 0;
    if (fields >> state >> ppid) parents.emplace_back(std::stoi(name), static_cast<pid_t>(ppid));
  }
  return parents;
}

// Whether process `pid` has `token` ("NAME=value") in the environment it was started with.
bool carries(pid_t pid, const std::string& token) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/environ", std::ios::binary);
  std::string environment((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t at = 0; at < environment.size();) {
    const std::size_t end = std::min(environment.find('\0', at), environment.size());
    if (environment.compare(at, end - at, token) == 0) return true;
    at = end + 1;
  }
  return false;
}

}  // namespace

void permit_process(CaseSpec& spec, bool allowed, double timeout_seconds,
                    const std::string& how_to_allow) {
  if (spec.discretization.kind != "process") return;
  if (!allowed) {
    std::string command;
    for (const auto& word : spec.discretization.command)
      command += (command.empty() ? "" : " ") + word;
    throw CaseError(
        spec.file, "discretization.command",
        "this case runs the program '" + command.substr(0, 200) +
            "' that it names; vivv starts programs named in case files only when asked to: " +
            how_to_allow);
  }
  // A program that is not there is bad input found before anything computes (exit 2, no
  // report), not a case that could not run; it is looked up again when it starts.
  if (!spec.discretization.command.empty()) {
    try {
      resolve_program(spec.discretization.command.front(),
                      fs::absolute(spec.file).parent_path().string());
    } catch (const MapProcessError& error) {
      throw CaseError(spec.file, "discretization.command", error.what());
    }
  }
  spec.discretization.process_allowed = true;
  spec.discretization.process_timeout_seconds = timeout_seconds;
}

void end_map_processes() noexcept {
  for (auto& slot : running_groups)
    if (slot != 0) kill(-static_cast<pid_t>(slot), SIGKILL);
}

void end_program_tree(pid_t leader, const std::string& token) noexcept {
  // Its group first (what a signal handler can do too), then the tree: the leader, every process
  // below it by parent, and every child of vivv carrying the token — a process that left the
  // group is reparented, when its parent ends, to vivv (the subreaper), with the token inherited.
  // Each round kills what it finds and reaps the ones that are vivv's children; those below come
  // to vivv in turn (dead, or killed next round), until a look finds none. A process that dropped
  // the token and left the group while its parent lived is the one that escapes.
  kill(-leader, SIGKILL);
  try {
    const pid_t self = getpid();
    std::set<pid_t> killed{leader};
    for (int round = 0; round < 1000; ++round) {
      const auto parents = process_parents();
      std::vector<pid_t> doomed;
      for (const auto& [pid, parent] : parents)
        if (parent == self && (killed.count(pid) || carries(pid, token))) doomed.push_back(pid);
      if (doomed.empty()) return;
      const std::size_t children = doomed.size();
      for (std::size_t k = 0; k < doomed.size(); ++k)  // and the subtree below each
        for (const auto& [pid, parent] : parents)
          if (parent == doomed[k] && std::find(doomed.begin(), doomed.end(), pid) == doomed.end())
            doomed.push_back(pid);
      for (pid_t pid : doomed)
        if (killed.insert(pid).second || pid == leader) kill(pid, SIGKILL);
      for (std::size_t k = 0; k < children; ++k)
        while (waitpid(doomed[k], nullptr, 0) < 0 && errno == EINTR) {
        }
    }
  } catch (...) {  // out of memory while reading /proc: the group is ended at least
  }
  while (waitpid(leader, nullptr, 0) < 0 && errno == EINTR) {  // ECHILD once reaped above
  }
}

MapProcess::MapProcess(Options options, const nlohmann::json& greeting)
    : options_(std::move(options)), longest_line_(longest_line_for(greeting)) {
  const std::string program = resolve_program(options_.command.front(), options_.directory);
  if (options_.command.front().find('/') == std::string::npos)
    resolved_note_ = "; " + repaired_utf8(quoted_text(options_.command.front(), 100)) + " is " + repaired_utf8(program);
  std::vector<std::string> words = options_.command;
  std::vector<char*> argv;
  for (auto& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  // Its environment: vivv's, with a token of this program that every descendant inherits, by
  // which end_program_tree knows the ones that left its process group.
  static std::atomic<long> started{0};  // programs started by this process (a library's threads)
  token_ = std::string(descendant_token) + "=" + std::to_string(getpid()) + "-" +
           std::to_string(++started);
  std::vector<std::string> environment{token_};
  for (char** entry = environ; *entry; ++entry)
    if (std::strncmp(*entry, descendant_token, std::strlen(descendant_token)) != 0 ||
        (*entry)[std::strlen(descendant_token)] != '=')
      environment.emplace_back(*entry);
  std::vector<char*> envp;
  for (auto& entry : environment) envp.push_back(entry.data());
  envp.push_back(nullptr);
  // The program's input, its output, its stderr and the exec status; a pipe that cannot be made
  // (out of descriptors) closes the ones made before it.
  int pipes[4][2];
  for (int made = 0; made < 4; ++made)
    if (pipe2(pipes[made], O_CLOEXEC) != 0) {
      const int error = errno;
      for (int k = 0; k < made; ++k) close(pipes[k][0]), close(pipes[k][1]);
      throw MapProcessError("cannot create the pipes to start " + name() + ": " +
                            std::strerror(error));
    }
  int(&to_child)[2] = pipes[0];
  int(&from_child)[2] = pipes[1];
  int(&child_errors)[2] = pipes[2];
  int(&exec_status)[2] = pipes[3];
  prepare_signals();
  // A process of the program that leaves its group (setsid, setpgid, a double fork) is
  // reparented, once its parent ends, to vivv rather than to init: end_program_tree then
  // finds it among vivv's children.
  prctl(PR_SET_CHILD_SUBREAPER, 1);
  const pid_t parent = getpid();
  {
    // No signal between the fork and the group's registration: it would leave the program behind.
    DeferInterrupts defer;
    pid_ = fork();
    if (pid_ == 0) {
      // Only async-signal-safe calls until exec: vivv may have threads (its progress printer).
      setpgid(0, 0);
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) _exit(127);
      dup2(to_child[0], STDIN_FILENO);
      dup2(from_child[1], STDOUT_FILENO);
      dup2(child_errors[1], STDERR_FILENO);
      for (int signal : ending_signals) ::signal(signal, SIG_DFL);
      ::signal(SIGPIPE, SIG_DFL);
      ::signal(SIGALRM, SIG_DFL);
      sigset_t none;
      sigemptyset(&none);
      sigprocmask(SIG_SETMASK, &none, nullptr);
      int error = 0;
      if (chdir(options_.directory.c_str()) == 0) {
        execve(program.c_str(), argv.data(), envp.data());
      }
      error = errno;
      [[maybe_unused]] auto written = ::write(exec_status[1], &error, sizeof error);
      _exit(127);
    }
    if (pid_ > 0) {
      setpgid(pid_, pid_);  // also here: whichever of the two runs first
      register_group(pid_);
    }
  }
  const int fork_error = errno;
  close(to_child[0]);
  close(from_child[1]);
  close(child_errors[1]);
  close(exec_status[1]);
  input_ = to_child[1], output_ = from_child[0], errors_ = child_errors[0];
  if (pid_ < 0) {
    for (int fd : {exec_status[0], input_, output_, errors_}) close(fd);
    throw MapProcessError("cannot start " + name() + ": " + std::strerror(fork_error));
  }
  int exec_error = 0;
  ssize_t got = 0;
  while ((got = ::read(exec_status[0], &exec_error, sizeof exec_error)) < 0 && errno == EINTR) {
  }
  close(exec_status[0]);
  for (int fd : {input_, output_, errors_}) fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
  try {
    if (got > 0)
      throw MapProcessError("cannot start " + name() + " in " + repaired_utf8(options_.directory) + ": " +
                            std::strerror(exec_error));
    greet(greeting);
  } catch (...) {
    stop();  // no destructor runs for an object whose constructor threw
    throw;
  }
}

void MapProcess::greet(const nlohmann::json& greeting) {
  const std::string what = "the greeting " + shortened(greeting.dump());
  send(greeting.dump(), what);
  const std::string line = receive(what);
  const nlohmann::json answer = parse_answer(line, what);
  if (answer.is_object() && answer.contains("error"))
    fail(what, "it declined: " + error_text(answer["error"]));
  if (!answer.is_object() || !answer.contains("protocol") || answer["protocol"] != map_protocol)
    fail(what, std::string("it answered ") + shortened(line) + ", not {\"protocol\": \"" +
                   map_protocol + "\"} (or {\"error\": …} to decline)");
  // The extensions it takes up: a subset of those offered, named in an array of strings.
  if (answer.contains("extensions")) {
    const nlohmann::json offered = greeting.value("extensions", nlohmann::json::array());
    const nlohmann::json& named = answer["extensions"];
    if (!named.is_array())
      fail(what, "its \"extensions\" is " + shortened(named.dump()) +
                     ", not an array of the extensions offered: " + offered.dump());
    for (const auto& extension : named) {
      if (!extension.is_string() || std::find(offered.begin(), offered.end(), extension) == offered.end())
        fail(what, "it took up the extension " + shortened(extension.dump()) +
                       ", which the greeting did not offer (offered: " + offered.dump() + ")");
      extensions_.push_back(extension.get<std::string>());
    }
  }
}

MapProcess::~MapProcess() { stop(); }

void MapProcess::stop() noexcept {
  if (pid_ <= 0) return;
  // Its input closed, the program ends; what has not within a second is killed, with its group.
  close(input_);
  const auto deadline = Clock::now() + std::chrono::seconds(1);
  while (Clock::now() < deadline) {
    siginfo_t info{};
    const int waited = waitid(P_PID, pid_, &info, WEXITED | WNOHANG | WNOWAIT);
    if ((waited == 0 && info.si_pid == pid_) || (waited < 0 && errno == ECHILD)) break;
    // What it still writes is read and dropped, so that a full pipe does not hold it.
    pollfd wait_for{output_, POLLIN, 0};
    char discard[4096];
    if (::poll(&wait_for, 1, 5) <= 0 || ::read(output_, discard, sizeof discard) <= 0)
      ::poll(nullptr, 0, 5);
  }
  // The group (the leader is not reaped yet, so the id is still its own) and every process
  // below the program, in the group or not; the leader reaped.
  end_program_tree(pid_, token_);
  unregister_group(pid_);
  // No program left: orphans of other processes of this one go to init again, as before.
  if (std::all_of(std::begin(running_groups), std::end(running_groups),
                  [](sig_atomic_t slot) { return slot == 0; }))
    prctl(PR_SET_CHILD_SUBREAPER, 0);
  close(output_);
  close(errors_);
  pid_ = -1;
}

std::string MapProcess::name() const {
  std::string joined;
  for (const auto& word : options_.command) joined += (joined.empty() ? "" : " ") + word;
  return "'" + shortened(joined, 200) + "'";
}

std::string MapProcess::answering() const {
  return "the map program " + name() + " (in " + repaired_utf8(options_.directory) + resolved_note_ + "), " +
         last_request_;
}

void MapProcess::fail_answer(const std::string& what) const {
  throw MapProcessError(answering() + ": " + what);
}

void MapProcess::fail(const std::string& request_name, const std::string& what) {
  drain_stderr();
  std::string message = "the map program " + name() + " (in " + repaired_utf8(options_.directory) + resolved_note_ +
                        "), " + request_name + ": " + what;
  if (!stderr_tail_.empty()) {
    // The kept tail may begin inside a character, and a program may write any bytes at all.
    std::string tail = repaired_utf8(stderr_tail_);
    while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back()))) tail.pop_back();
    message += "; its standard error ended with: " + tail;
  }
  throw MapProcessError(message);
}

int significant_digits(const std::string& text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  int digits = 0, mantissa_digits = 0;
  bool nonzero_seen = false, point = false;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '.' && !point) {
      point = true;
      continue;
    }
    if (!std::isdigit(static_cast<unsigned char>(c))) break;
    ++mantissa_digits;
    if (c != '0') nonzero_seen = true;
    if (nonzero_seen) ++digits;
  }
  if (mantissa_digits == 0) return -1;
  if (i < text.size()) {
    if (text[i] != 'e' && text[i] != 'E') return -1;
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    const std::size_t exponent = i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
    if (i == exponent || i != text.size() || i - exponent > 9) return -1;
  }
  return digits;
}

}  // namespace vivv
