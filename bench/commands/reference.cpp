// `vivv bench reference` (issue 3): wall time, steps, order and multiply-adds
// of the Taylor reference flow, and Boost.Odeint's bulirsch_stoer on the same
// problem and scalar, timed in the same run. Not a timed test: it measures
// and reports, it does not judge.
#include "bench/commands/reference.hpp"

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/odeint_mpfr.hpp"  // extract_value_type for odeint on MPFR
#include "cases/systems.hpp"
#include "references/closed_forms.hpp"
#include "references/taylor_flow.hpp"


namespace vivv {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct TaylorRun {
  double seconds = 0;  // best of the repetitions, tape recording included
  TaylorReport report;
  double error = 0;  // max-norm distance to the closed form at t = 10 (not timed)
};

// The pendulum q'' = −k sin q from (1, 0) to `end_time` by the Taylor flow at step tolerance
// `tolerance`.
template <class T>
TaylorRun time_taylor(const T& tolerance, int repetitions, const T& k = 1, const T& end_time = 10) {
  Pendulum<T> pendulum;
  pendulum.k = k;
  State<T, 1> start;
  start.q[0] = 1;
  start.w[0] = 0;
  TaylorRun run;
  run.seconds = 1e300;
  State<T, 1> end;
  for (int r = 0; r < repetitions; ++r) {
    Clock::time_point begin = Clock::now();
    TaylorFlow<Pendulum<T>> flow(pendulum, tolerance);
    end = flow.advance(start, end_time);
    run.seconds = std::min(run.seconds, seconds_since(begin));
    run.report = flow.report();
  }
  run.error =
      static_cast<double>(state_distance<T, 1>(end, pendulum_flow(pendulum, start, end_time)));
  return run;
}

// heyoka's published pendulum benchmarks, so that vivv's figures can be set beside theirs:
// x'' = −9.8 sin x from x = 1, v = 0, at the working precision's tolerance.
template <class T>
void heyoka_problem(std::ostream& out, nlohmann::json& result, const std::string& key, const std::string& label,
                    const T& tolerance, const T& end_time, int repetitions) {
  TaylorRun run = time_taylor<T>(tolerance, repetitions, from_decimal<T>("9.8"), end_time);
  out << "heyoka's pendulum, " << label << ": " << run.seconds * 1e6 << " us, " << run.report.steps
      << " steps, order " << run.report.order << ", error vs closed form " << run.error << "\n";
  result[key] = {{"seconds", run.seconds}, {"steps", run.report.steps}, {"order", run.report.order},
                 {"error", run.error}, {"bits", precision_bits<T>()}};
}

struct OdeintRun {
  double seconds = 0;  // best of the repetitions, like the Taylor runs
  double error = 0;
  long steps = 0;
};

// The same problem with odeint's bulirsch_stoer (absolute and relative tolerance `tolerance`).
OdeintRun time_odeint(const mpfr_real& tolerance, int repetitions) {
  using T = mpfr_real;
  using StateType = std::vector<T>;
  namespace odeint = boost::numeric::odeint;
  OdeintRun run;
  run.seconds = 1e300;
  StateType y;
  auto pendulum = [](const StateType& x, StateType& dxdt, const T& /*t*/) {
    using std::sin;
    dxdt[0] = x[1];
    dxdt[1] = -sin(x[0]);
  };
  for (int r = 0; r < repetitions; ++r) {
    y = {T(1), T(0)};
    Clock::time_point begin = Clock::now();
    odeint::bulirsch_stoer<StateType, T> stepper(tolerance, tolerance);
    run.steps =
        static_cast<long>(odeint::integrate_adaptive(stepper, pendulum, y, T(0), T(10), T(1) / 10));
    run.seconds = std::min(run.seconds, seconds_since(begin));
  }
  State<T, 1> start, end;
  start.q[0] = 1, start.w[0] = 0, end.q[0] = y[0], end.w[0] = y[1];
  run.error =
      static_cast<double>(state_distance<T, 1>(end, pendulum_flow(Pendulum<T>{}, start, T(10))));
  return run;
}

}  // namespace

int run_reference_benchmark(std::ostream& out) {
  using std::pow;
  nlohmann::json result;
  {
    // 257 bits (5 limbs), the least precision ≥ 256 bits that Boost 1.74 can set: it sets MPFR's
    // precision from decimal digits, and 76 digits are 254 bits, 77 digits 257 bits.
    PrecisionGuard guard(77);
    using T = mpfr_real;
    const int bits = precision_bits<T>();
    TaylorRun taylor = time_taylor<T>(pow(T(10), -70), 5);
    const double p = taylor.report.order;
    const double fma_per_step = double(taylor.report.multiply_adds) / double(taylor.report.steps);
    out << "Taylor, " << bits << " bits, tol 1e-70: " << taylor.seconds * 1e3 << " ms, "
        << taylor.report.steps << " steps, order " << taylor.report.order << ", "
        << fma_per_step << " multiply-adds per step (p² = " << p * p << "), error vs closed form "
        << taylor.error << "\n";
    result["bits_256"] = bits;
    result["seconds_256"] = taylor.seconds;
    result["steps_256"] = taylor.report.steps;
    result["order_256"] = taylor.report.order;
    result["fma_per_step_256"] = fma_per_step;
    result["fma_over_p2_256"] = fma_per_step / (p * p);
    result["tape_operations"] = taylor.report.tape_operations;
    result["error_256"] = taylor.error;

    TaylorRun taylor40 = time_taylor<T>(pow(T(10), -40), 5);
    OdeintRun odeint = time_odeint(pow(T(10), -40), 3);
    out << "Taylor, " << bits << " bits, tol 1e-40: " << taylor40.seconds * 1e3 << " ms, "
        << taylor40.report.steps << " steps, order " << taylor40.report.order
        << ", error vs closed form " << taylor40.error << "\n";
    out << "odeint bulirsch_stoer, " << bits << " bits, tol 1e-40: " << odeint.seconds * 1e3
        << " ms, " << odeint.steps << " steps, error vs closed form " << odeint.error << "\n";
    out << "odeint / Taylor at 1e-40: " << odeint.seconds / taylor40.seconds
        << "x; odeint at 1e-40 / Taylor at 1e-70: " << odeint.seconds / taylor.seconds << "x\n";
    result["seconds_256_tol40"] = taylor40.seconds;
    result["steps_256_tol40"] = taylor40.report.steps;
    result["order_256_tol40"] = taylor40.report.order;
    result["error_256_tol40"] = taylor40.error;
    result["odeint_seconds"] = odeint.seconds;
    result["odeint_steps"] = odeint.steps;
    result["odeint_error"] = odeint.error;
    result["odeint_ratio"] = odeint.seconds / taylor40.seconds;
    result["odeint_ratio_vs_tol70"] = odeint.seconds / taylor.seconds;
    heyoka_problem<T>(out, result, "heyoka_pendulum_256", std::to_string(bits) + " bits, tol 1e-77, t = 0.1",
                      pow(T(10), -77), T(1) / 10, 20);
  }
  {
    TaylorRun quad_run = time_taylor<quad>(pow(quad(10), -32), 20);
    out << "Taylor, quad, tol 1e-32: " << quad_run.seconds * 1e3 << " ms, " << quad_run.report.steps
        << " steps, order " << quad_run.report.order << ", error vs closed form " << quad_run.error
        << "\n";
    result["seconds_quad"] = quad_run.seconds;
    result["steps_quad"] = quad_run.report.steps;
    result["order_quad"] = quad_run.report.order;
    result["error_quad"] = quad_run.error;
    heyoka_problem<quad>(out, result, "heyoka_pendulum_quad", "quad, tol 1e-34, t = 1", pow(quad(10), -34),
                         quad(1), 20);
  }
  out << result.dump() << "\n";
  return 0;
}

}  // namespace vivv
