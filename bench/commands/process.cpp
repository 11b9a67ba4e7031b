// `vivv bench process` (issue 28): the process protocol's overhead per step, as a ratio against
// vivv's own DEL step. Not a timed test: it measures and reports; the target (50 µs) is printed
// beside it.
#include "bench/commands/process.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "bench/commands/timing.hpp"
#include "harness/process/process_map.hpp"

namespace vivv {
namespace {

constexpr double target_microseconds = 50;

template <class T>
nlohmann::json measure(const char* scalar, const std::string& vivv_path) {
  const Pendulum<T> system;
  const T h = T(1) / 10;
  State<T, 1> x;
  x.q[0] = T(11) / 10, x.w[0] = T(1) / 4;
  MapProcess::Options options;
  options.command = {vivv_path, "map-echo"};
  options.directory = std::filesystem::current_path().string();
  // The echo answers the state it is sent: an orbit of size |q| = 1.1.
  const ProcessMap<Pendulum<T>> map(system, options, nlohmann::json{{"name", "pendulum"}}, 1,
                                    x.q[0]);
  const double process_us = 1e6 * seconds_per_call(
                                      [&] {
                                        State<T, 1> next = map.step(x, h);
                                        keep(next);
                                      },
                                      0.2);
  // Of that, the trip itself: one request already written as JSON, through the pipes and back.
  MapProcess echo(
      options, {{"protocol", map_protocol}, {"digits", round_trip_digits<T>()}, {"dimension", 1}});
  const nlohmann::json request = {
      {"h", to_decimal<T>(h)}, {"q", {to_decimal<T>(x.q[0])}}, {"p", {to_decimal<T>(x.w[0])}}};
  const double trip_us = 1e6 * seconds_per_call(
                                   [&] {
                                     nlohmann::json answer = echo.request(request);
                                     keep(answer);
                                   },
                                   0.2);
  QxQDiscretization<T> midpoint;
  midpoint.rule = QxQRule::midpoint;
  const DelScheme<T> scheme = matched_scheme(midpoint);
  Vector<T, 1> q0, q1;
  q0[0] = x.q[0], q1[0] = x.q[0] + h * x.w[0];
  const double del_us = 1e6 * seconds_per_call(
                                  [&] {
                                    auto step = del_step(system, scheme, q0, q1, h);
                                    keep(step);
                                  },
                                  0.2);
  return {{"scalar", scalar},
          {"digits", round_trip_digits<T>()},
          {"process_step_us", process_us},
          {"pipe_trip_us", trip_us},
          {"del_step_us", del_us},
          {"ratio", process_us / del_us},
          {"within_target", process_us <= target_microseconds}};
}

}  // namespace

int run_process_benchmark(std::ostream& out, const std::string& vivv_path) {
  nlohmann::json rows = nlohmann::json::array();
  rows.push_back(measure<double>("double", vivv_path));
  {
    PrecisionGuard guard(40);
    rows.push_back(measure<mpfr_real>("mpfr", vivv_path));
  }
  out << "one step of a process map whose program echoes (q, p) (vivv map-echo), against one "
         "midpoint DEL\n"
         "step of vivv's own, pendulum\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-9s %7s %18s %16s %14s %8s\n", "scalar", "digits",
                "process step (us)", "of it, trip (us)", "DEL step (us)", "ratio");
  out << line;
  for (const auto& row : rows) {
    std::snprintf(line, sizeof line, "%-9s %7d %18.1f %16.1f %14.1f %8.2f%s\n",
                  row["scalar"].get<std::string>().c_str(), row["digits"].get<int>(),
                  row["process_step_us"].get<double>(), row["pipe_trip_us"].get<double>(),
                  row["del_step_us"].get<double>(), row["ratio"].get<double>(),
                  row["within_target"].get<bool>() ? "" : "  (above the target)");
    out << line;
  }
  out << "ratio = process step / DEL step; target: a process step <= " << target_microseconds
      << " us\n";
  out << nlohmann::json{{"target_microseconds", target_microseconds}, {"rows", rows}}.dump()
      << "\n";
  return 0;
}

int run_map_echo() {
  std::string line;
  if (!std::getline(std::cin, line)) return 0;
  std::cout << "{\"protocol\": \"" << map_protocol << "\"}" << std::endl;
  while (std::getline(std::cin, line)) {
    const nlohmann::json request = nlohmann::json::parse(line);
    std::cout << nlohmann::json{{"q", request["q"]}, {"p", request["p"]}}.dump() << std::endl;
  }
  return 0;
}

}  // namespace vivv
