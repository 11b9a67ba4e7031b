// `vivv bench del` (issue 15): one midpoint DEL step against the Lagrangian evaluations it
// needs, in three scalars. Not a timed test: it measures and reports, it does not judge; the
// ratio's target (at most 2, issue 27: keep the midpoint within 2x its evaluations) is printed
// beside it.
#include "bench/commands/del.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/counted_system.hpp"
#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "bench/commands/timing.hpp"

namespace vivv {
namespace {

constexpr double target_ratio = 2;

// q_{k−1} = (1, 1/2, ...), q_k = q_{k−1} + (1/100, 2/100, ...), h = 1/10.
template <class System>
nlohmann::json measure(const char* scalar) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  const Counted<System> system;
  Vector<T, n> q0, q1, w;
  for (int i = 0; i < n; ++i) {
    q0[i] = T(1) / (i + 1);
    q1[i] = q0[i] + T(i + 1) / 100;
    w[i] = (q1[i] - q0[i]) * 10;
  }
  const T h = T(1) / 10;
  QxQDiscretization<T> midpoint;
  midpoint.rule = QxQRule::midpoint;
  const DelScheme<T> scheme = matched_scheme(midpoint);

  Counted<System>::evaluations = 0;
  auto [q2, report] = del_step(system, scheme, q0, q1, h);
  if (!report.converged)
    throw std::runtime_error(std::string("bench del: the DEL step of ") + System::name + " in " +
                             scalar + " did not converge");
  const long evaluations = Counted<System>::evaluations;
  const double step_ns = 1e9 * seconds_per_call(
                                   [&] {
                                     auto step = del_step(system, scheme, q0, q1, h);
                                     keep(step);
                                   },
                                   0.1);
  const double evaluation_ns = 1e9 * seconds_per_call(
                                         [&] {
                                           auto derivatives = lagrangian_derivatives(system, q1, w);
                                           keep(derivatives);
                                         },
                                         0.1);
  const double ratio = step_ns / (static_cast<double>(evaluations) * evaluation_ns);
  return {{"system", System::name},
          {"dimension", n},
          {"scalar", scalar},
          {"bits", precision_bits<T>()},
          {"evaluations", evaluations},
          {"newton_iterations", report.iterations},
          {"step_ns", step_ns},
          {"evaluation_ns", evaluation_ns},
          {"ratio", ratio},
          {"within_target", ratio <= target_ratio}};
}

}  // namespace

int run_del_benchmark(std::ostream& out) {
  nlohmann::json rows = nlohmann::json::array();
  rows.push_back(measure<Pendulum<double>>("double"));
  rows.push_back(measure<DoublePendulum<double>>("double"));
  rows.push_back(measure<Pendulum<quad>>("float128"));
  rows.push_back(measure<DoublePendulum<quad>>("float128"));
  {
    PrecisionGuard guard(77);  // 256 bits
    rows.push_back(measure<Pendulum<mpfr_real>>("mpfr"));
    rows.push_back(measure<DoublePendulum<mpfr_real>>("mpfr"));
  }
  out << "one midpoint DEL step against the L evaluations (value, gradient, Hessian) it needs\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-16s %-9s %5s %6s %8s %12s %14s %7s\n", "system", "scalar",
                "bits", "evals", "newton", "step (ns)", "one eval (ns)", "ratio");
  out << line;
  for (const auto& row : rows) {
    std::snprintf(
        line, sizeof line, "%-16s %-9s %5d %6ld %8d %12.0f %14.0f %7.2f%s\n",
        row["system"].get<std::string>().c_str(), row["scalar"].get<std::string>().c_str(),
        row["bits"].get<int>(), row["evaluations"].get<long>(), row["newton_iterations"].get<int>(),
        row["step_ns"].get<double>(), row["evaluation_ns"].get<double>(),
        row["ratio"].get<double>(), row["within_target"].get<bool>() ? "" : "  (above the target)");
    out << line;
  }
  out << "ratio = step / (evals x one eval); target <= " << target_ratio << "\n";
  out << "one eval: L's value, gradient and full Hessian in (q, w); the step's Newton keeps only the "
         "q_b-q_e block of L_d's Hessian, which is why a ratio can fall below 1\n";
  out << nlohmann::json{{"target_ratio", target_ratio}, {"rows", rows}}.dump() << "\n";
  return 0;
}

}  // namespace vivv
