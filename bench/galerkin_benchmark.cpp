// Google Benchmark: one DEL step of the degree-4 Gauss Galerkin discrete
// Lagrangian (4 nodes) on the pendulum and the paper's example, in MPFR at 77 digits
// (257 bits), against the cost of the Lagrangian evaluations it needs (issue 13).
// A Galerkin DEL step nests Newton on the 3 interior control values inside
// Newton on q_{k+1}; every action evaluation evaluates L with its first and
// second derivatives at the 4 nodes. The step is counted (how many such
// evaluations it makes) and timed in alternation with that many evaluations,
// and the ratio step / (count × evaluation) printed: what the nested solves and
// the Schur complement cost beyond L itself, measured in this one run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/counted_system.hpp"
#include "bench/median_reporter.hpp"
#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/qxq/galerkin.hpp"

namespace {

using vivv::mpfr_real;
constexpr int digits = 77;  // 257 bits: Boost.Multiprecision's conversion of 77 digits

using vivv::Counted;

vivv::QxQDiscretization<mpfr_real> degree_four_gauss() {
  vivv::QxQDiscretization<mpfr_real> d;
  d.rule = vivv::QxQRule::galerkin;
  d.galerkin = std::make_shared<const vivv::GalerkinRule<mpfr_real>>(vivv::GalerkinSpec{4, false, 4});
  return d;
}

// One DEL step from (q0, q1) = (1, 1.01), h = 1/10, timed in alternation with as many
// evaluations of L with its gradient and Hessian (what each quadrature node costs) as the step
// makes; counters: "evaluations" per step, "ratio" the step's time over theirs.
template <class System>
void del_step(benchmark::State& state, const System& system) {
  const auto scheme = vivv::matched_scheme(degree_four_gauss());
  vivv::Vector<mpfr_real, 1> q0, q1;
  q0[0] = 1, q1[0] = mpfr_real(101) / 100;
  const mpfr_real h = mpfr_real(1) / 10;
  System::evaluations = 0;
  benchmark::DoNotOptimize(vivv::del_step(system, scheme, q0, q1, h));
  const long evaluations = System::evaluations;
  vivv::Vector<mpfr_real, 1> x, v;
  x[0] = 1, v[0] = mpfr_real(1) / 10;
  vivv::time_in_alternation(
      state,
      [&] {
        for (long i = 0; i < evaluations; ++i)
          benchmark::DoNotOptimize(vivv::lagrangian_hessian(system, x, v));
      },
      [&] { benchmark::DoNotOptimize(vivv::del_step(system, scheme, q0, q1, h)); });
  state.counters["evaluations"] = double(evaluations);
}

}  // namespace

int main(int argc, char** argv) {
  vivv::PrecisionGuard guard(digits);
  const Counted<vivv::Pendulum<mpfr_real>> pendulum;
  const Counted<vivv::PaperExample<mpfr_real>> paper;
  benchmark::RegisterBenchmark("galerkin_del_step/pendulum", [&](auto& s) {
    del_step(s, pendulum);
  })->Repetitions(vivv::benchmark_repetitions);
  benchmark::RegisterBenchmark("galerkin_del_step/paper_example", [&](auto& s) {
    del_step(s, paper);
  })->Repetitions(vivv::benchmark_repetitions);
  benchmark::Initialize(&argc, argv);
  vivv::MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  constexpr double target = 3;  // issue 27: a Galerkin DEL step within 3x its L evaluations
  nlohmann::json rows = nlohmann::json::array();
  std::printf(
      "\nGalerkin degree 4, 4 Gauss nodes, MPFR %d bits: DEL step / (L evaluations x one "
      "evaluation), "
      "medians of %d repetitions\n",
      vivv::precision_bits<mpfr_real>(), vivv::benchmark_repetitions);
  for (const char* system : {"pendulum", "paper_example"}) {
    const std::string step = std::string("galerkin_del_step/") + system;
    if (!reporter.has(step)) continue;
    const double count = reporter.counter(step, "evaluations");
    const double ratio = reporter.median_counter(step, "ratio");
    std::printf("  %-14s %.0f evaluations per step, ratio %.2f (target <= %.0f)\n", system, count,
                ratio, target);
    rows.push_back({{"system", system},
                    {"evaluations", count},
                    {"ratio", ratio},
                    {"target", target},
                    {"within_target", ratio <= target}});
  }
  vivv::print_ratio_summary("galerkin DEL step / L evaluations", vivv::precision_bits<mpfr_real>(), rows);
  return 0;
}
