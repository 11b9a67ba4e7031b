// How far a recording may grow: a ceiling of nodes that TapeRecording::record() checks, set for
// a scope by TapeCeiling, so that a formula is expanded at most as far as memory allows
// (cases/system_section.cpp sets it from core/platform/memory_limit.hpp while a case is read).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace vivv {

// A recording that passed the ceiling a TapeCeiling set: what is recorded would not fit in memory.
struct TapeCeilingReached : std::length_error {
  explicit TapeCeilingReached(std::size_t nodes)
      : std::length_error("a recording passed its ceiling of " + std::to_string(nodes) + " operations"),
        nodes(nodes) {}
  std::size_t nodes;
};

namespace tape_detail {
inline thread_local std::size_t node_ceiling = 0;  // 0: none
}  // namespace tape_detail

// While alive, every recording on this thread holds at most `nodes` nodes (0: no ceiling) and
// throws TapeCeilingReached instead: a formula is expanded at most as far as memory allows.
class TapeCeiling {
 public:
  explicit TapeCeiling(std::size_t nodes) : previous_(tape_detail::node_ceiling) { tape_detail::node_ceiling = nodes; }
  ~TapeCeiling() { tape_detail::node_ceiling = previous_; }
  TapeCeiling(const TapeCeiling&) = delete;
  TapeCeiling& operator=(const TapeCeiling&) = delete;

 private:
  std::size_t previous_;
};

}  // namespace vivv
