// Google Benchmark: a system of two coordinates at its compile-time size (FormulaSystem<T, 2>)
// and at a run-time one (any_size: Eigen-dynamic vectors, heap jets), the same formula and DEL
// step (Hénon–Heiles, midpoint, Newton to convergence from the same start), in double and in
// MPFR at 60 digits: why one and two coordinates keep their fixed sizes (issue 50). Compare the
// pairs' times from one run. Measured 2026-11-29 on 2 cores: a step at the run-time size took
// 4.9 times the fixed one's CPU time in double (7.6 against 1.6 µs), 1.8 times in MPFR (275
// against 156 µs); whole trajectories, interleaved, 3.6 and 1.6 times.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/qxq/del_evolution.hpp"

namespace {

const vivv::FormulaSystemDefinition& henon_heiles() {
  static const std::string text = "(vx^2 + vy^2)/2 - (x^2 + y^2)/2 - (x^2*y - y^3/3)";
  static const vivv::FormulaSystemDefinition definition{
      "henon-heiles", text, vivv::parse_formula(text), {"x", "y"}, {"vx", "vy"}, {}, {}, nullptr};
  return definition;
}

template <class T, int N>
void del_step(benchmark::State& state) {
  std::unique_ptr<vivv::PrecisionGuard> guard;
  if constexpr (vivv::is_mpfr_v<T>) guard = std::make_unique<vivv::PrecisionGuard>(60);
  const auto system = vivv::make_formula_system<T, N>(henon_heiles());
  vivv::QxQDiscretization<T> midpoint;
  midpoint.rule = vivv::QxQRule::midpoint;
  const auto scheme = vivv::matched_scheme(midpoint);
  vivv::Vector<T, N> q0 = vivv::zero_vector<T, N>(2), q1 = vivv::zero_vector<T, N>(2);
  q0 << T(1) / 10, T(-1) / 10;
  q1 << T(101) / 1000, T(-99) / 1000;
  const T h = T(1) / 100;
  for (auto _ : state) benchmark::DoNotOptimize(vivv::del_step(system, scheme, q0, q1, h));
}

BENCHMARK_TEMPLATE(del_step, double, 2)->Name("del_step/double/fixed_2");
BENCHMARK_TEMPLATE(del_step, double, vivv::any_size)->Name("del_step/double/run_time_2");
BENCHMARK_TEMPLATE(del_step, vivv::mpfr_real, 2)->Name("del_step/mpfr60/fixed_2");
BENCHMARK_TEMPLATE(del_step, vivv::mpfr_real, vivv::any_size)->Name("del_step/mpfr60/run_time_2");

}  // namespace

BENCHMARK_MAIN();
