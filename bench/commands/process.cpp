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
#include <vector>

#include "cases/formula_parser.hpp"
#include "cases/systems.hpp"
#include "core/formulas/formula_system.hpp"
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

// One Jacobian of symplecticity's (ProcessMap::jacobian, the first of every eight checked as the
// claim checks it) from an echo that sends its own (extension "jacobian"), against one by central
// differences (a second instance at 2D + 10 digits; for a double program, the same instance), in
// microseconds, for a system of `n` coordinates (the echo's map is the identity: the programs'
// own work is nil, and the figure is vivv's and the protocol's).
template <class System>
nlohmann::json measure_jacobians(const char* scalar, const std::string& vivv_path,
                                 const System& system, const nlohmann::json& system_json) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  const T h = T(1) / 10;
  State<T, n> x;
  for (int i = 0; i < n; ++i) x.q[i] = T(11 + i) / 10, x.w[i] = T(1) / 4;
  MapProcess::Options options;
  options.directory = std::filesystem::current_path().string();
  auto microseconds = [&](std::vector<std::string> command, bool double_program) {
    options.command = std::move(command);
    const ProcessMap<System> map(system, options, system_json, 1, T(2), double_program);
    return 1e6 * seconds_per_call(
                     [&] {
                       auto jacobian = map.jacobian(x, h);
                       keep(jacobian);
                     },
                     0.3);
  };
  const double own_us = microseconds({vivv_path, "map-echo", "--jacobian"}, false);
  const double differences_us = microseconds({vivv_path, "map-echo"}, false);
  nlohmann::json row = {{"scalar", scalar},
                        {"dimension", n},
                        {"digits", round_trip_digits<T>()},
                        {"own_jacobian_us", own_us},
                        {"differences_us", differences_us},
                        {"speedup", differences_us / own_us}};
  if (std::string(scalar) == "double") {
    const double double_us = microseconds({vivv_path, "map-echo"}, true);
    row["double_program_differences_us"] = double_us;
    row["double_program_speedup"] = double_us / own_us;
  }
  return row;
}

// L = Σ w_i²/2 − Σ q_i²/2 in n explicit names: a system sized at run time, for the echo's rows at
// the sizes programs have (the echo's map is the identity, so L only sizes the messages).
FormulaSystemDefinition oscillators(int n) {
  std::vector<std::string> q, w;
  std::string kinetic, potential;
  for (int i = 1; i <= n; ++i) {
    q.push_back("q" + std::to_string(i)), w.push_back("w" + std::to_string(i));
    kinetic += (i > 1 ? " + " : "") + w.back() + "^2";
    potential += (i > 1 ? " + " : "") + q.back() + "^2";
  }
  const std::string text = "(" + kinetic + ")/2 - (" + potential + ")/2";
  return {"oscillators", text, parse_formula(text), q, w, {}, {}, nullptr};
}

// One request of a "precision": "double" program at n coordinates, through the echo: vivv's
// formatting of 2n numbers at 17 digits, the pipes, the echo's parse and reply, vivv's parse; and
// one with the program's own Jacobian (2n × 2n entries of 17 digits back). In microseconds.
nlohmann::json measure_size(const std::string& vivv_path, int n) {
  const auto system = make_formula_system<double, any_size>(oscillators(n));
  State<double, any_size> x{Vector<double, any_size>(n), Vector<double, any_size>(n)};
  for (int i = 0; i < n; ++i) x.q[i] = 1.1 + 0.01 * i, x.w[i] = 0.25 - 0.001 * i;
  const double h = 0.01;
  MapProcess::Options options;
  options.directory = std::filesystem::current_path().string();
  options.command = {vivv_path, "map-echo"};
  const ProcessMap<decltype(system)> map(system, options, nlohmann::json{{"name", "oscillators"}}, 1, 2.0, true);
  const double step_us = 1e6 * seconds_per_call(
                                   [&] {
                                     auto next = map.step(x, h);
                                     keep(next);
                                   },
                                   0.3);
  // The Jacobian's request by itself (ProcessMap::jacobian checks every eighth against
  // differences, which is not the protocol's cost): the request, the answer's 4n² strings parsed
  // and read as numbers.
  options.command = {vivv_path, "map-echo", "--jacobian"};
  MapProcess echo(options, {{"protocol", map_protocol},
                            {"digits", 17},
                            {"dimension", n},
                            {"extensions", nlohmann::json::array({"jacobian"})}});
  nlohmann::json request = {{"h", to_decimal<double>(h)}, {"q", nlohmann::json::array()},
                            {"p", nlohmann::json::array()}, {"jacobian", true}};
  for (int i = 0; i < n; ++i)
    request["q"].push_back(to_decimal<double>(x.q[i])), request["p"].push_back(to_decimal<double>(x.w[i]));
  // The step's request by itself, the answer's 2n strings read as numbers: the protocol's part of
  // step_us (the rest is vivv's Legendre transforms, p = ∂L/∂w and w from p').
  nlohmann::json plain = request;
  plain.erase("jacobian");
  options.command = {vivv_path, "map-echo"};  // the echo with --jacobian sends one with every answer
  MapProcess stepper(options, {{"protocol", map_protocol}, {"digits", 17}, {"dimension", n}});
  Vector<double, any_size> numbers(2 * n);
  const double trip_us = 1e6 * seconds_per_call(
                                   [&] {
                                     const nlohmann::json answer = stepper.request(plain);
                                     for (int i = 0; i < n; ++i)
                                       numbers[i] = from_decimal<double>(answer.at("q")[static_cast<std::size_t>(i)].get<std::string>()),
                                       numbers[n + i] = from_decimal<double>(answer.at("p")[static_cast<std::size_t>(i)].get<std::string>());
                                     keep(numbers);
                                   },
                                   0.3);
  Matrix<double, any_size, any_size> jacobian(2 * n, 2 * n);
  const double jacobian_us = 1e6 * seconds_per_call(
                                       [&] {
                                         const nlohmann::json answer = echo.request(request);
                                         const auto& rows = answer.at("jacobian");
                                         for (int i = 0; i < 2 * n; ++i)
                                           for (int j = 0; j < 2 * n; ++j)
                                             jacobian(i, j) = from_decimal<double>(
                                                 rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]
                                                     .get<std::string>());
                                         keep(jacobian);
                                       },
                                       0.3);
  return {{"dimension", n}, {"step_us", step_us}, {"trip_us", trip_us}, {"own_jacobian_us", jacobian_us}};
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
      << " us\n\n";
  // symplecticity's Jacobians: a program's own against differences of its steps.
  nlohmann::json jacobians = nlohmann::json::array();
  jacobians.push_back(measure_jacobians("double", vivv_path, Pendulum<double>(),
                                        nlohmann::json{{"name", "pendulum"}}));
  jacobians.push_back(measure_jacobians("double", vivv_path, Kepler<double>(),
                                        nlohmann::json{{"name", "kepler"}}));
  {
    PrecisionGuard guard(40);
    jacobians.push_back(measure_jacobians("mpfr", vivv_path, Pendulum<mpfr_real>(),
                                          nlohmann::json{{"name", "pendulum"}}));
    jacobians.push_back(measure_jacobians("mpfr", vivv_path, Kepler<mpfr_real>(),
                                          nlohmann::json{{"name", "kepler"}}));
  }
  out << "one Jacobian for symplecticity from a program that sends its own (extension "
         "\"jacobian\"), against\n"
         "one by central differences of its steps (a second instance at 2D + 10 digits; "
         "\"precision\": \"double\": the same\n"
         "instance), the echo program's identity map; the first of every 8 checked as the claim "
         "checks it\n";
  std::snprintf(line, sizeof line, "%-7s %3s %7s %12s %18s %8s %22s\n", "scalar", "n", "digits",
                "own (us)", "differences (us)", "speedup", "double program (us)");
  out << line;
  for (const auto& row : jacobians) {
    std::snprintf(line, sizeof line, "%-7s %3d %7d %12.1f %18.1f %8.2f", row["scalar"].get<std::string>().c_str(),
                  row["dimension"].get<int>(), row["digits"].get<int>(), row["own_jacobian_us"].get<double>(),
                  row["differences_us"].get<double>(), row["speedup"].get<double>());
    out << line;
    if (row.contains("double_program_differences_us")) {
      std::snprintf(line, sizeof line, " %14.1f (x%.2f)", row["double_program_differences_us"].get<double>(),
                    row["double_program_speedup"].get<double>());
      out << line;
    }
    out << "\n";
  }
  out << "speedup = differences / own; a real program's own work per request multiplies both\n\n";
  // The protocol at the sizes programs have: its cost per request against n.
  nlohmann::json sizes = nlohmann::json::array();
  for (int n : {2, 14, 114, 300}) sizes.push_back(measure_size(vivv_path, n));
  out << "one request to a \"precision\": \"double\" program (the echo) at n coordinates: a step "
         "(2n numbers each way), and\n"
         "a Jacobian the program sends (2n numbers out, 2n + 4n^2 back); vivv's side, the pipes and "
         "the echo's parsing\n";
  std::snprintf(line, sizeof line, "%5s %12s %18s %20s\n", "n", "step (us)", "of it, trip (us)", "own Jacobian (us)");
  out << line;
  for (const auto& row : sizes) {
    std::snprintf(line, sizeof line, "%5d %12.1f %18.1f %20.1f\n", row["dimension"].get<int>(), row["step_us"].get<double>(),
                  row["trip_us"].get<double>(), row["own_jacobian_us"].get<double>());
    out << line;
  }
  out << "a program's own step and its parsing in Python: bench/process_program.py\n";
  out << nlohmann::json{{"target_microseconds", target_microseconds},
                        {"rows", rows},
                        {"jacobians", jacobians},
                        {"sizes", sizes}}
             .dump()
      << "\n";
  return 0;
}

namespace {

// `text` with at least `digits` significant digits: zeros appended to its mantissa (exact).
std::string padded(const std::string& text, int digits) {
  const std::size_t exponent = std::min(text.find_first_of("eE"), text.size());
  std::string mantissa = text.substr(0, exponent);
  int significant = 0;
  bool leading = true;
  for (char c : mantissa)
    if (c >= '0' && c <= '9' && !(leading && c == '0')) ++significant, leading = false;
  if (significant == 0) return text;  // zero
  if (mantissa.find('.') == std::string::npos) mantissa += '.';
  return mantissa + std::string(static_cast<std::size_t>(std::max(0, digits - significant)), '0') +
         text.substr(exponent);
}

}  // namespace

int run_map_echo(bool send_jacobian) {
  std::string line;
  if (!std::getline(std::cin, line)) return 0;
  const nlohmann::json greeting = nlohmann::json::parse(line);
  const int digits = greeting.value("digits", 17), n = greeting.value("dimension", 1);
  const bool offered = greeting.contains("extensions") && greeting["extensions"].is_array() &&
                       std::find(greeting["extensions"].begin(), greeting["extensions"].end(),
                                 "jacobian") != greeting["extensions"].end();
  send_jacobian = send_jacobian && offered;
  nlohmann::json answer = {{"protocol", map_protocol}};
  if (send_jacobian) answer["extensions"] = {"jacobian"};
  std::cout << answer.dump() << std::endl;
  // The identity's Jacobian, written with the digits asked for.
  nlohmann::json identity = nlohmann::json::array();
  for (int i = 0; i < 2 * n; ++i) {
    nlohmann::json row = nlohmann::json::array();
    // Off the diagonal "0.000…" with the digits a real entry has, so that a line is as long as
    // a program's (the protocol's cost at large n is mostly these characters).
    for (int j = 0; j < 2 * n; ++j) row.push_back(i == j ? padded("1", digits) : "0." + std::string(static_cast<std::size_t>(std::max(1, digits - 1)), '0'));
    identity.push_back(row);
  }
  while (std::getline(std::cin, line)) {
    const nlohmann::json request = nlohmann::json::parse(line);
    nlohmann::json reply = {{"q", nlohmann::json::array()}, {"p", nlohmann::json::array()}};
    for (const char* key : {"q", "p"})
      for (const auto& value : request[key]) reply[key].push_back(padded(value.get<std::string>(), digits));
    if (send_jacobian) reply["jacobian"] = identity;
    std::cout << reply.dump() << std::endl;
  }
  return 0;
}

}  // namespace vivv
