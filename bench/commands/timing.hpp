// Timing for the `vivv bench` commands: not timed tests, measurements reported as ratios.
#pragma once

#include <algorithm>
#include <chrono>

namespace vivv {

// Keeps the compiler from dropping a computation whose result is unused (as Google
// Benchmark's DoNotOptimize): the object must exist in memory.
template <class V>
void keep(V& value) {
  asm volatile("" : : "r"(&value) : "memory");
}

// Seconds per call of `f`: the best of three batches of at least `batch_seconds` each.
template <class F>
double seconds_per_call(F&& f, double batch_seconds) {
  using Clock = std::chrono::steady_clock;
  double best = 1e300;
  for (int batch = 0; batch < 3; ++batch) {
    long calls = 0;
    const Clock::time_point start = Clock::now();
    double elapsed = 0;
    do {
      f();
      ++calls;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    } while (elapsed < batch_seconds);
    best = std::min(best, elapsed / static_cast<double>(calls));
  }
  return best;
}

}  // namespace vivv
