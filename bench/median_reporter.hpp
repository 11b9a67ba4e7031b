// A console reporter that also keeps every repetition's time — per iteration, or per step when
// the benchmark sets a "steps" counter — and the counters, so that each figure a benchmark
// prints is a ratio of medians measured in this one run. One repetition is not enough: a DEL
// step in MPFR measured 105 µs and 200 µs in two repetitions of the same binary (the allocator's
// state), which moved a formula/compiled ratio from 0.8 to 1.4; the median of five is stable.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace vivv {

inline constexpr int benchmark_repetitions = 5;

class MedianReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& run : runs) {
      if (run.run_type != Run::RT_Iteration) continue;
      double seconds = run.GetAdjustedRealTime();
      const auto steps = run.counters.find("steps");
      if (steps != run.counters.end() && steps->second.value > 0) seconds /= steps->second.value;
      const std::string& name = run.run_name.function_name;
      times_[name].push_back(seconds);
      for (const auto& [counter, value] : run.counters) counters_[name][counter] = value.value;
    }
    ConsoleReporter::ReportRuns(runs);
  }

  bool has(const std::string& name) const { return times_.count(name) > 0; }
  // The median over the repetitions of `name`'s time per unit.
  double median(const std::string& name) const {
    std::vector<double> times = times_.at(name);
    std::sort(times.begin(), times.end());
    const std::size_t middle = times.size() / 2;
    return times.size() % 2 ? times[middle] : (times[middle - 1] + times[middle]) / 2;
  }
  double counter(const std::string& name, const std::string& counter) const {
    return counters_.at(name).at(counter);
  }

 private:
  std::map<std::string, std::vector<double>> times_;
  std::map<std::string, std::map<std::string, double>> counters_;
};

}  // namespace vivv
