// MapProcess's side of the pipes to its program (harness/process/program.hpp): writing requests
// (one at a time, or sent ahead to a program that took up "pipeline"), reading each answer line
// within the timeout while keeping the tail of the program's stderr, and checking that an answer
// is a JSON object and not an error. Starting, greeting and ending the program are in program.cpp.
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <deque>
#include <sstream>

#include "harness/process/program.hpp"
#include "harness/process/program_internals.hpp"

namespace vivv {
using program_internals::Clock, program_internals::error_text, program_internals::milliseconds_until,
    program_internals::shortened, program_internals::stderr_kept;

std::string MapProcess::line_of(const nlohmann::json& message) const {
  if (time_.empty() || !message.is_object() || !message.contains("h") || message.contains("t")) return message.dump();
  nlohmann::json timed = message;
  timed["t"] = time_;
  return timed.dump();
}

nlohmann::json MapProcess::request(const nlohmann::json& message) {
  const std::string line = line_of(message);
  last_request_ = "request " + std::to_string(requests_ + 1) + " " + shortened(line);
  send(line, last_request_);
  const std::string reply = receive(last_request_);
  ++requests_;
  return checked_answer(reply, last_request_);
}

void MapProcess::requests(const std::function<std::optional<nlohmann::json>()>& next,
                          const std::function<void(const nlohmann::json&)>& read) {
  if (!uses_extension(pipeline_extension)) {
    while (const std::optional<nlohmann::json> message = next()) read(request(*message));
    return;
  }
  std::string outgoing;            // requests made, not yet written
  std::deque<std::string> names;   // the requests sent ahead, in order, not yet answered
  bool made_all = false;
  const auto answer = [&] {
    last_request_ = names.front();
    names.pop_front();
    const std::string reply = receive(last_request_, &outgoing);
    ++requests_;
    return reply;
  };
  try {
    while (!made_all || !names.empty()) {
      while (!made_all && names.size() < pipelined_requests) {
        const std::optional<nlohmann::json> message = next();
        if (!message) {
          made_all = true;
          break;
        }
        const std::string line = line_of(*message);
        names.push_back("request " + std::to_string(requests_ + 1 + static_cast<long>(names.size())) + " " +
                        shortened(line));
        outgoing += line + "\n";
        write_ahead(outgoing);
      }
      if (names.empty()) break;
      const std::string reply = answer();
      read(checked_answer(reply, last_request_));
    }
  } catch (const MapProcessError&) {
    throw;  // the program failed: nothing more is read from it
  } catch (...) {
    while (!names.empty()) answer();  // their answers, unread: the pipe holds none for the next request
    throw;
  }
}

void MapProcess::write_ahead(std::string& outgoing) {
  while (!outgoing.empty()) {
    const ssize_t wrote = ::write(input_, outgoing.data(), outgoing.size());
    if (wrote > 0) {
      outgoing.erase(0, static_cast<std::size_t>(wrote));
      continue;
    }
    if (wrote < 0 && errno == EINTR) continue;
    return;  // a full pipe (or a closed one, which the next receive() names): written as it reads
  }
}

nlohmann::json MapProcess::checked_answer(const std::string& reply, const std::string& request_name) {
  nlohmann::json answer = parse_answer(reply, request_name);
  if (!answer.is_object()) fail(request_name, "it answered " + shortened(reply) + ", not a JSON object");
  if (answer.contains("error")) fail(request_name, "it answered with an error: " + error_text(answer["error"]));
  return answer;
}

nlohmann::json MapProcess::parse_answer(const std::string& line, const std::string& request_name) {
  // nlohmann parses iteratively, but destroying and printing a value recurse: a value nested
  // 100 000 deep would end vivv by a stack overflow. The parser's callback sees each value's
  // depth before it is built.
  struct TooDeep {};
  const auto bounded = [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > maximum_answer_depth) throw TooDeep{};
    return true;
  };
  try {
    return nlohmann::json::parse(line, bounded);
  } catch (const TooDeep&) {
    fail(request_name, "it answered JSON nested deeper than " +
                           std::to_string(maximum_answer_depth) +
                           " levels (an answer is an object of arrays of decimal strings): " +
                           shortened(line, 100));
  } catch (const nlohmann::json::exception&) {
    fail(request_name, "it answered a line that is not JSON: " + shortened(line));
  }
}

void MapProcess::drain_stderr() {
  char chunk[4096];
  ssize_t got = 0;
  while ((got = ::read(errors_, chunk, sizeof chunk)) > 0) {
    stderr_tail_.append(chunk, static_cast<std::size_t>(got));
    if (stderr_tail_.size() > stderr_kept) stderr_tail_.erase(0, stderr_tail_.size() - stderr_kept);
  }
}

std::string MapProcess::how_it_ended() {
  // Its output is closed; it has ended or is ending: wait for it a little.
  const auto deadline = Clock::now() + std::chrono::milliseconds(500);
  while (Clock::now() < deadline) {
    siginfo_t info{};
    if (waitid(P_PID, pid_, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid_) {
      if (info.si_code == CLD_EXITED)
        return "it exited with status " + std::to_string(info.si_status);
      return "it was ended by signal " + std::to_string(info.si_status) + " (" +
             strsignal(info.si_status) + ")";
    }
    ::poll(nullptr, 0, 5);
  }
  return "it closed its standard output";
}

void MapProcess::send(const std::string& line, const std::string& request_name) {
  const std::string text = line + "\n";
  const auto deadline = Clock::now() + std::chrono::milliseconds(
                                           static_cast<long long>(options_.timeout_seconds * 1000));
  std::size_t sent = 0;
  while (sent < text.size()) {
    const ssize_t wrote = ::write(input_, text.data() + sent, text.size() - sent);
    if (wrote > 0) {
      sent += static_cast<std::size_t>(wrote);
      continue;
    }
    if (errno == EINTR) continue;
    if (errno == EPIPE) fail(request_name, "it stopped reading its input: " + how_it_ended());
    if (errno != EAGAIN)
      fail(request_name, std::string("cannot write to it: ") + std::strerror(errno));
    pollfd writable{input_, POLLOUT, 0};
    const int left = milliseconds_until(deadline);
    if (left == 0 || ::poll(&writable, 1, left) == 0)
      fail(request_name, "it did not read its input within " +
                             std::to_string(options_.timeout_seconds) + " s (--process-timeout)");
  }
}

std::string MapProcess::receive(const std::string& request_name, std::string* outgoing) {
  const auto deadline = Clock::now() + std::chrono::milliseconds(
                                           static_cast<long long>(options_.timeout_seconds * 1000));
  std::size_t end = 0;
  while ((end = buffer_.find('\n')) == std::string::npos) {
    if (buffer_.size() > longest_line_)
      fail(request_name, "it wrote a line longer than " + std::to_string(longest_line_) +
                             " characters (2 × (2n + (2n)²) numbers of D + 16 characters, at least "
                             "1 MiB)");
    const bool writing = outgoing != nullptr && !outgoing->empty();
    std::array<pollfd, 3> ready{pollfd{output_, POLLIN, 0}, pollfd{errors_, POLLIN, 0},
                                pollfd{writing ? input_ : -1, POLLOUT, 0}};  // fd −1: not polled
    const int left = milliseconds_until(deadline);
    if (left == 0) {
      std::ostringstream seconds;
      seconds << options_.timeout_seconds;
      fail(request_name,
           "no answer within " + seconds.str() + " s (--process-timeout)" +
               (buffer_.empty() ? "" : "; it wrote " + shortened(buffer_) + " without a newline"));
    }
    // In slices of 100 ms: a program that exited while a child of its own keeps its output open
    // never shows an end of file, so its exit is looked for too.
    const int ready_count = ::poll(ready.data(), ready.size(), std::min(left, 100));
    if (ready_count < 0) {
      if (errno == EINTR) continue;
      fail(request_name, std::string("poll: ") + std::strerror(errno));
    }
    if (ready[1].revents) drain_stderr();
    if (ready[2].revents) {  // its input takes more of the requests sent ahead
      const ssize_t wrote = ::write(input_, outgoing->data(), outgoing->size());
      if (wrote > 0) outgoing->erase(0, static_cast<std::size_t>(wrote));
      if (wrote < 0 && errno == EPIPE) fail(request_name, "it stopped reading its input: " + how_it_ended());
      if (wrote < 0 && errno != EAGAIN && errno != EINTR)
        fail(request_name, std::string("cannot write to it: ") + std::strerror(errno));
    }
    if (ready[0].revents) {
      char chunk[4096];
      const ssize_t got = ::read(output_, chunk, sizeof chunk);
      if (got > 0) buffer_.append(chunk, static_cast<std::size_t>(got));
      if (got == 0) fail(request_name, "no answer: " + how_it_ended());
      if (got < 0 && errno != EAGAIN && errno != EINTR)
        fail(request_name, std::string("cannot read its output: ") + std::strerror(errno));
    }
    siginfo_t info{};
    if (ready_count == 0 && waitid(P_PID, pid_, &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        info.si_pid == pid_) {
      char chunk[4096];
      ssize_t got = 0;
      while ((got = ::read(output_, chunk, sizeof chunk)) > 0)
        buffer_.append(chunk, static_cast<std::size_t>(got));
      if (buffer_.find('\n') == std::string::npos)
        fail(request_name, "no answer: " + how_it_ended());
    }
  }
  std::string line = buffer_.substr(0, end);
  buffer_.erase(0, end + 1);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

}  // namespace vivv
