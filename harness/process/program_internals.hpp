// What program.cpp and program_pipes.cpp share in MapProcess's implementation: deadlines in
// milliseconds, text shortened for messages, an error answer's text and the stderr kept.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "core/platform/text.hpp"

namespace vivv::program_internals {

using Clock = std::chrono::steady_clock;

// Milliseconds from now to `deadline`, 0 once it has passed (for poll()).
inline int milliseconds_until(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::clamp<long long>(left, 0, 1 << 30));
}

// A program's text in a message: quoted, at most `at_most` characters.
inline std::string shortened(const std::string& text, std::size_t at_most = 300) {
  return quoted_text(text, at_most);
}

// An {"error": …} answer's text: a string as it is, anything else as JSON (its depth bounded by
// parse_answer, its length by the line's).
inline std::string error_text(const nlohmann::json& error) {
  return shortened(error.is_string() ? error.get<std::string>() : error.dump());
}

// The characters of a program's stderr kept for messages: its last ones.
inline constexpr std::size_t stderr_kept = 2000;

}  // namespace vivv::program_internals
