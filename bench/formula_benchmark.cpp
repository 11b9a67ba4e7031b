// Google Benchmark: a formula Lagrangian against its compiled catalogue twin,
// in MPFR at 256 bits (issue 12: a formula may cost at most 2x its twin).
// Per DEL step (midpoint, Newton to convergence from the same start) and per
// Taylor step (the reference flow over one period, divided by its steps), for
// the pendulum and the paper's example. After the runs it prints each ratio
// formula / compiled, both measured in this one run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "cases/formula_parser.hpp"
#include "cases/systems.hpp"
#include "core/del_evolution.hpp"
#include "core/formula_system.hpp"
#include "references/taylor_flow.hpp"

namespace {

using vivv::mpfr_real;
constexpr int digits = 77;  // 256 bits

vivv::FormulaSystemDefinition definition(const std::string& text,
                                         std::vector<std::pair<std::string, std::string>> parameters) {
  return {"formula", text,   vivv::parse_formula(text), {"q"}, {"w"}, std::move(parameters),
          {},        nullptr};
}

// One DEL step of the midpoint rule from (q0, q1) = (1, 1.01), h = 1/100.
template <class System>
void del_step(benchmark::State& state, const System& system) {
  using T = typename System::Scalar;
  const auto scheme = vivv::matched_scheme(vivv::QxQDiscretization<T>{});
  vivv::Vector<T, 1> q0, q1;
  q0[0] = 1, q1[0] = T(101) / 100;
  const T h = T(1) / 100;
  for (auto _ : state) benchmark::DoNotOptimize(vivv::del_step(system, scheme, q0, q1, h));
}

// The Taylor reference flow from (1, 1/2) to t = 10 at tolerance 1e-60; time per step.
template <class System>
void taylor_steps(benchmark::State& state, const System& system) {
  using T = typename System::Scalar;
  vivv::State<T, 1> start;
  start.q[0] = 1, start.w[0] = T(1) / 2;
  const T tolerance = pow(T(10), -60);
  long steps = 0;
  for (auto _ : state) {
    vivv::TaylorFlow<System> flow(system, tolerance);
    benchmark::DoNotOptimize(flow.advance(start, T(10)));
    steps = flow.report().steps;
  }
  state.counters["steps"] = double(steps);
  state.SetItemsProcessed(state.iterations() * steps);  // items/s: Taylor steps per second
}

// Keeps each benchmark's time per iteration (DEL) or per Taylor step, for the ratios.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& run : runs) {
      double seconds = run.GetAdjustedRealTime();
      auto steps = run.counters.find("steps");
      if (steps != run.counters.end() && steps->second.value > 0) seconds /= steps->second.value;
      per_unit[run.benchmark_name()] = seconds;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> per_unit;
};

}  // namespace

int main(int argc, char** argv) {
  vivv::PrecisionGuard guard(digits);
  const vivv::Pendulum<mpfr_real> pendulum;
  const vivv::PaperExample<mpfr_real> paper;
  const auto pendulum_twin = vivv::make_formula_system<mpfr_real, 1>(definition("w^2/2 - k*(1 - cos(q))", {{"k", "1"}}));
  const auto paper_twin = vivv::make_formula_system<mpfr_real, 1>(
      definition("(g0 + g2*q^2) * w^2 / 2 - (k*(1 - cos(q)) + m*q^2/2)",
                 {{"g0", "1"}, {"g2", "0.5"}, {"k", "1"}, {"m", "0"}}));
  benchmark::RegisterBenchmark("del_step/pendulum/compiled", [&](auto& s) { del_step(s, pendulum); });
  benchmark::RegisterBenchmark("del_step/pendulum/formula", [&](auto& s) { del_step(s, pendulum_twin); });
  benchmark::RegisterBenchmark("del_step/paper_example/compiled", [&](auto& s) { del_step(s, paper); });
  benchmark::RegisterBenchmark("del_step/paper_example/formula", [&](auto& s) { del_step(s, paper_twin); });
  benchmark::RegisterBenchmark("taylor_step/pendulum/compiled", [&](auto& s) { taylor_steps(s, pendulum); });
  benchmark::RegisterBenchmark("taylor_step/pendulum/formula", [&](auto& s) { taylor_steps(s, pendulum_twin); });
  benchmark::RegisterBenchmark("taylor_step/paper_example/compiled", [&](auto& s) { taylor_steps(s, paper); });
  benchmark::RegisterBenchmark("taylor_step/paper_example/formula", [&](auto& s) { taylor_steps(s, paper_twin); });
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\nformula / compiled, MPFR %d bits (target <= 2):\n", vivv::precision_bits<mpfr_real>());
  for (const char* what : {"del_step", "taylor_step"})
    for (const char* system : {"pendulum", "paper_example"}) {
      const std::string base = std::string(what) + "/" + system + "/";
      auto compiled = reporter.per_unit.find(base + "compiled"), formula = reporter.per_unit.find(base + "formula");
      if (compiled == reporter.per_unit.end() || formula == reporter.per_unit.end()) continue;
      std::printf("  %-28s %.2f\n", (std::string(what) + " " + system).c_str(), formula->second / compiled->second);
    }
  return 0;
}
