// Google Benchmark: a system of two coordinates at its compile-time size (FormulaSystem<T, 2>)
// and at a run-time one (any_size: Eigen-dynamic vectors, heap jets), the same formula and DEL
// step (Hénon–Heiles, midpoint, Newton to convergence from the same start), in double and in
// MPFR at 60 digits; and the LU a DEL step's Newton iteration factors, sparse and dense, at 2 to
// 64 unknowns (where vivv::dense_factorization_limit sits). Compare the pairs' times from one run.
// Measured 2026-12-07 on 2 cores: the run-time size's step took 4.8 times the fixed one's in double
// (5.1 against 1.06 µs) and 3.9 times in MPFR (357 against 91 µs), 86 % of the latter in the sparse
// LU's set-up; with small systems factored dense, 1.8 times in double (1.93 against 1.08 µs) and
// 0.55 times in MPFR (51 against 94 µs).
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/numerics/linear_solve.hpp"
#include "core/qxq/del_evolution.hpp"
#include "references/taylor_flow.hpp"

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

// The Taylor reference flow of the same system from (0.1, −0.1, 0.05, 0.02) to t = 50 at tolerance
// 10^-50, in MPFR at 60 digits: the reference's part of the fixed-against-run-time comparison.
template <class T, int N>
void taylor_flow(benchmark::State& state) {
  vivv::PrecisionGuard guard(60);
  const auto system = vivv::make_formula_system<T, N>(henon_heiles());
  vivv::State<T, N> start{vivv::zero_vector<T, N>(2), vivv::zero_vector<T, N>(2)};
  start.q << T(1) / 10, T(-1) / 10;
  start.w << T(1) / 20, T(1) / 50;
  using std::pow;
  const T tolerance = pow(T(10), -50);
  vivv::TaylorReport report;
  for (auto _ : state) {
    vivv::TaylorFlow<std::decay_t<decltype(system)>> flow(system, tolerance);
    benchmark::DoNotOptimize(flow.advance(start, T(50)));
    report = flow.report();
  }
  state.counters["steps"] = double(report.steps);
  state.counters["order"] = report.order;
  state.counters["fma_per_step"] = double(report.multiply_adds) / double(report.steps);
}

BENCHMARK_TEMPLATE(taylor_flow, vivv::mpfr_real, 2)->Name("taylor_flow/mpfr60/fixed_2")->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(taylor_flow, vivv::mpfr_real, vivv::any_size)
    ->Name("taylor_flow/mpfr60/run_time_2")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(del_step, double, 2)->Name("del_step/double/fixed_2");
BENCHMARK_TEMPLATE(del_step, double, vivv::any_size)->Name("del_step/double/run_time_2");
BENCHMARK_TEMPLATE(del_step, vivv::mpfr_real, 2)->Name("del_step/mpfr60/fixed_2");
BENCHMARK_TEMPLATE(del_step, vivv::mpfr_real, vivv::any_size)->Name("del_step/mpfr60/run_time_2");

// One LU of a chain's tridiagonal n × n matrix and a solve with it (what a DEL step's Newton
// iteration does), sparse (Eigen's SparseLU) or dense (FullPivLU): where
// vivv::dense_factorization_limit should sit, in double and in MPFR at 60 digits.
template <class T, bool dense>
void factor_and_solve(benchmark::State& state) {
  std::unique_ptr<vivv::PrecisionGuard> guard;
  if constexpr (vivv::is_mpfr_v<T>) guard = std::make_unique<vivv::PrecisionGuard>(60);
  const int n = static_cast<int>(state.range(0));
  std::vector<Eigen::Triplet<T>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, T(2) + T(i) / 7);
    if (i + 1 < n) entries.emplace_back(i, i + 1, T(-1)), entries.emplace_back(i + 1, i, T(-1) / 3);
  }
  Eigen::SparseMatrix<T> matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  const vivv::Vector<T, vivv::any_size> right = vivv::Vector<T, vivv::any_size>::Ones(n);
  for (auto _ : state) {
    vivv::SparseFactorization<T> lu;
    benchmark::DoNotOptimize(lu.factor(matrix, T(1e-30), dense ? n : 0));
    benchmark::DoNotOptimize(lu.solve(right));
  }
}

BENCHMARK_TEMPLATE(factor_and_solve, double, false)->Name("factor/double/sparse")->RangeMultiplier(2)->Range(2, 64);
BENCHMARK_TEMPLATE(factor_and_solve, double, true)->Name("factor/double/dense")->RangeMultiplier(2)->Range(2, 64);
BENCHMARK_TEMPLATE(factor_and_solve, vivv::mpfr_real, false)->Name("factor/mpfr60/sparse")->RangeMultiplier(2)->Range(2, 64);
BENCHMARK_TEMPLATE(factor_and_solve, vivv::mpfr_real, true)->Name("factor/mpfr60/dense")->RangeMultiplier(2)->Range(2, 64);

}  // namespace

BENCHMARK_MAIN();
