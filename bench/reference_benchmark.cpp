// Google Benchmark: the Taylor reference flow on the pendulum q'' = −sin q,
// q(0) = 1, w(0) = 0, t in [0, 10] (issue 3), at 256 bits (tol 1e-70 and
// 1e-40) and in quad (1e-32), and Boost.Odeint's bulirsch_stoer on the same
// MPFR scalar at 1e-40. Counters: steps, order, multiply-adds per step.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "bench/odeint_mpfr.hpp"
#include "cases/systems.hpp"
#include "references/taylor_flow.hpp"

namespace {

using vivv::mpfr_real;

// The pendulum from (1, 0) to t = 10 by the Taylor flow at tolerance 10^−exponent.
template <class T>
void taylor_pendulum(benchmark::State& state, int digits, int exponent) {
  std::unique_ptr<vivv::PrecisionGuard> guard;
  if constexpr (vivv::is_mpfr_v<T>) guard = std::make_unique<vivv::PrecisionGuard>(digits);
  using std::pow;
  const T tolerance = pow(T(10), -exponent);
  vivv::Pendulum<T> pendulum;
  vivv::State<T, 1> start;
  start.q[0] = 1;
  start.w[0] = 0;
  vivv::TaylorReport report;
  for (auto _ : state) {
    vivv::TaylorFlow<vivv::Pendulum<T>> flow(pendulum, tolerance);
    benchmark::DoNotOptimize(flow.advance(start, T(10)));
    report = flow.report();
  }
  state.counters["steps"] = double(report.steps);
  state.counters["order"] = report.order;
  state.counters["fma_per_step"] = double(report.multiply_adds) / double(report.steps);
}

void odeint_pendulum(benchmark::State& state) {
  vivv::PrecisionGuard guard(77);
  using T = mpfr_real;
  using StateType = std::vector<T>;
  namespace odeint = boost::numeric::odeint;
  using std::pow;
  const T tolerance = pow(T(10), -40);
  auto pendulum = [](const StateType& x, StateType& dxdt, const T&) {
    using std::sin;
    dxdt[0] = x[1];
    dxdt[1] = -sin(x[0]);
  };
  std::size_t steps = 0;
  for (auto _ : state) {
    StateType y = {T(1), T(0)};
    odeint::bulirsch_stoer<StateType, T> stepper(tolerance, tolerance);
    steps = odeint::integrate_adaptive(stepper, pendulum, y, T(0), T(10), T(1) / 10);
    benchmark::DoNotOptimize(y);
  }
  state.counters["steps"] = double(steps);
}

void taylor_mpfr(benchmark::State& state, int digits, int exponent) {
  taylor_pendulum<mpfr_real>(state, digits, exponent);
}
void taylor_quad(benchmark::State& state, int exponent) {
  taylor_pendulum<vivv::quad>(state, 0, exponent);
}

// 77 decimal digits are 257 bits (Boost sets MPFR's precision from decimal digits).
BENCHMARK_CAPTURE(taylor_mpfr, bits256_tol1e70, 77, 70)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(taylor_mpfr, bits256_tol1e40, 77, 40)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(taylor_quad, tol1e32, 32)->Unit(benchmark::kMillisecond);
BENCHMARK(odeint_pendulum)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
