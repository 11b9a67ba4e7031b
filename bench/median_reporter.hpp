// A console reporter that also keeps every repetition's counters, so that each figure a
// benchmark prints is a median over repetitions of a ratio measured in this one run (by
// time_in_alternation below). One repetition is not enough: a DEL step in MPFR measured 105 µs
// and 200 µs in two repetitions of the same binary (the allocator's state).
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace vivv {

inline constexpr int benchmark_repetitions = 5;

class MedianReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& run : runs) {
      if (run.run_type != Run::RT_Iteration) continue;
      for (const auto& [counter, value] : run.counters)
        counters_[run.run_name.function_name][counter].push_back(value.value);
    }
    ConsoleReporter::ReportRuns(runs);
  }

  bool has(const std::string& name) const { return counters_.count(name) > 0; }
  // A counter's value in the last repetition, and its median over the repetitions.
  double counter(const std::string& name, const std::string& counter) const {
    return counters_.at(name).at(counter).back();
  }
  double median_counter(const std::string& name, const std::string& counter) const {
    std::vector<double> values = counters_.at(name).at(counter);
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 ? values[middle] : (values[middle - 1] + values[middle]) / 2;
  }

 private:
  std::map<std::string, std::map<std::string, std::vector<double>>> counters_;
};

// Times `base()` and `other()` in alternation, the order swapped every iteration, and sets the
// counter "ratio" to other's time over base's. Timed as two benchmarks one after the other, a
// formula DEL step and its compiled twin gave ratios from 0.75 to 1.7 in one binary on a shared
// 2-core machine whose speed changed within seconds, and the medians of five repetitions did not
// steady it; in alternation the five repetitions agree to within 1 %.
template <class Base, class Other>
void time_in_alternation(benchmark::State& state, const Base& base, const Other& other) {
  using clock = std::chrono::steady_clock;
  clock::duration base_time{}, other_time{};
  bool other_first = false;
  for (auto _ : state) {
    const auto t0 = clock::now();
    other_first ? other() : base();
    const auto t1 = clock::now();
    other_first ? base() : other();
    const auto t2 = clock::now();
    (other_first ? other_time : base_time) += t1 - t0;
    (other_first ? base_time : other_time) += t2 - t1;
    other_first = !other_first;
  }
  state.counters["ratio"] = std::chrono::duration<double>(other_time).count() /
                            std::chrono::duration<double>(base_time).count();
}

// The last line a ratio benchmark prints: one JSON object, comparable across machines (every
// figure a ratio), with the precision and the repetitions it was measured at.
inline void print_ratio_summary(const std::string& benchmark, int bits, const nlohmann::json& rows) {
  std::printf("%s\n", nlohmann::json{{"benchmark", benchmark},
                                     {"bits", bits},
                                     {"repetitions", benchmark_repetitions},
                                     {"rows", rows}}
                          .dump()
                          .c_str());
}

}  // namespace vivv
