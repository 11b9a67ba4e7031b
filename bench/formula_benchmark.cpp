// Google Benchmark: a formula Lagrangian against its compiled catalogue twin,
// in MPFR at 77 digits, 257 bits (issue 12: a formula may cost at most 2x its twin).
// Per DEL step (midpoint, Newton to convergence from the same start) and per
// Taylor step (the reference flow over one period; the formula's and its twin's take the same
// steps), for the pendulum and the paper's example. After the runs it prints each ratio formula /
// compiled, both measured in this one run.
//
// Each benchmark times the formula step and its twin's in alternation (time_in_alternation).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/median_reporter.hpp"
#include "cases/formula_parser.hpp"
#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/formulas/formula_system.hpp"
#include "references/taylor_flow.hpp"

namespace {

using vivv::mpfr_real;
constexpr int digits = 77;  // 257 bits: Boost.Multiprecision's conversion of 77 digits

vivv::FormulaSystemDefinition definition(const std::string& text,
                                         std::vector<std::pair<std::string, std::string>> parameters) {
  return {"formula", text,   vivv::parse_formula(text), {"q"}, {"w"}, std::move(parameters),
          {},        nullptr};
}

// One DEL step of the midpoint rule from (q0, q1) = (1, 1.01), h = 1/100.
template <class System>
auto del_step(const System& system) {
  using T = typename System::Scalar;
  return [&system] {
    const auto scheme = vivv::matched_scheme(vivv::QxQDiscretization<T>{});
    vivv::Vector<T, 1> q0, q1;
    q0[0] = 1, q1[0] = T(101) / 100;
    const T h = T(1) / 100;
    benchmark::DoNotOptimize(vivv::del_step(system, scheme, q0, q1, h));
  };
}

// The Taylor reference flow from (1, 1/2) to t = 10 at tolerance 1e-60; the steps it took go to
// `steps` (the same for the formula and its twin: the test below checks it).
template <class System>
auto taylor_steps(const System& system, long& steps) {
  using T = typename System::Scalar;
  return [&system, &steps] {
    vivv::State<T, 1> start;
    start.q[0] = 1, start.w[0] = T(1) / 2;
    vivv::TaylorFlow<System> flow(system, pow(T(10), -60));
    benchmark::DoNotOptimize(flow.advance(start, T(10)));
    steps = flow.report().steps;
  };
}

}  // namespace

int main(int argc, char** argv) {
  vivv::PrecisionGuard guard(digits);
  const vivv::Pendulum<mpfr_real> pendulum;
  const vivv::PaperExample<mpfr_real> paper;
  const auto pendulum_twin = vivv::make_formula_system<mpfr_real, 1>(definition("w^2/2 - k*(1 - cos(q))", {{"k", "1"}}));
  const auto paper_twin = vivv::make_formula_system<mpfr_real, 1>(
      definition("(g0 + g2*q^2) * w^2 / 2 - (k*(1 - cos(q)) + m*q^2/2)",
                 {{"g0", "1"}, {"g2", "0.5"}, {"k", "1"}, {"m", "0"}}));
  benchmark::RegisterBenchmark("del_step/pendulum", [&](auto& s) {
    vivv::time_in_alternation(s, del_step(pendulum), del_step(pendulum_twin));
  })->Repetitions(vivv::benchmark_repetitions);
  benchmark::RegisterBenchmark("del_step/paper_example", [&](auto& s) {
    vivv::time_in_alternation(s, del_step(paper), del_step(paper_twin));
  })->Repetitions(vivv::benchmark_repetitions);
  // Both flows take the same steps (a formula evaluates the same Lagrangian); if they did not,
  // the ratio per flow would not be one per step, and the benchmark says so below.
  long pendulum_steps = 0, pendulum_twin_steps = 0, paper_steps = 0, paper_twin_steps = 0;
  benchmark::RegisterBenchmark("taylor_step/pendulum", [&](auto& s) {
    vivv::time_in_alternation(s, taylor_steps(pendulum, pendulum_steps),
                              taylor_steps(pendulum_twin, pendulum_twin_steps));
  })->Repetitions(vivv::benchmark_repetitions);
  benchmark::RegisterBenchmark("taylor_step/paper_example", [&](auto& s) {
    vivv::time_in_alternation(s, taylor_steps(paper, paper_steps),
                              taylor_steps(paper_twin, paper_twin_steps));
  })->Repetitions(vivv::benchmark_repetitions);
  benchmark::Initialize(&argc, argv);
  vivv::MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  // Targets: a formula DEL step within 1.2x its compiled twin (issue 27), a Taylor step within 2x.
  const std::map<std::string, double> targets = {{"del_step", 1.2}, {"taylor_step", 2.0}};
  nlohmann::json rows = nlohmann::json::array();
  std::printf("\nformula / compiled, MPFR %d bits, medians of %d repetitions:\n",
              vivv::precision_bits<mpfr_real>(), vivv::benchmark_repetitions);
  if (pendulum_steps != pendulum_twin_steps || paper_steps != paper_twin_steps) {
    std::fprintf(stderr,
                 "a formula's Taylor flow took other steps than its twin's: %ld/%ld, %ld/%ld\n",
                 pendulum_twin_steps, pendulum_steps, paper_twin_steps, paper_steps);
    return 1;
  }
  for (const auto& [what, target] : targets)
    for (const char* system : {"pendulum", "paper_example"}) {
      const std::string name = what + "/" + system;
      if (!reporter.has(name)) continue;
      const double ratio = reporter.median_counter(name, "ratio");
      std::printf("  %-28s %.2f (target <= %.1f)\n", (what + " " + system).c_str(), ratio, target);
      rows.push_back({{"step", what},
                      {"system", system},
                      {"ratio", ratio},
                      {"target", target},
                      {"within_target", ratio <= target}});
    }
  vivv::print_ratio_summary("formula / compiled", vivv::precision_bits<mpfr_real>(), rows);
  return 0;
}
