// `vivv bench size` (issue 50): how the cost of one DEL step, one reference step and one
// symplecticity check grows with the number of coordinates, on two systems written as formulas
// (so sized at run time, with L's sparse derivatives):
//   (a) a nearest-neighbour chain with fixed ends and a quartic on-site term,
//       L = Σ w_i²/2 − Σ_{i=0..n} (q_{i+1} − q_i)²/2 − Σ q_i⁴/4,  q_0 = q_{n+1} = 0,
//       n = 2, 4, …, 1024 in double and up to 256 in MPFR (30 digits);
//   (b) all-pairs gravity of N bodies in space, L = Σ m_i |v_i|²/2 + Σ_{i<j} m_i m_j / |x_i − x_j|,
//       N = 2, 4, …, 64 in double.
// Columns: a midpoint DEL step (Newton on the sparse −∂²L_d/∂q_b∂q_e); a step of the Taylor
// reference flow at the tolerance a case of that scalar uses (1000 ε; 10^-(digits − 10)); the
// symplecticity check of one step (the dense 2n × 2n Jacobian of the DEL's (q, p) map and
// |JᵀΩJ − Ω|, core/structure/symplectic.hpp), up to the sizes given below, and beside it what the
// claim does instead above 16 coordinates (the sparse blocks, the generating form's defect, B_e's
// sparse LU and the carried probe pairs through J: core/structure/symplectic_probes.hpp), at every
// size. Log-log slopes are
// least-squares fits over the range the targets name (chain: n = 64 … 1024; gravity: N = 8 … 64).
// Not a timed test: it measures and reports; the targets are printed beside the slopes.
#include "bench/commands/size.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/commands/timing.hpp"
#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/structure/symplectic.hpp"
#include "core/structure/symplectic_probes.hpp"
#include "references/taylor_flow.hpp"

namespace vivv {
namespace {

// The chain of n coordinates, in explicit names (q1 … qn, w1 … wn).
FormulaSystemDefinition chain(int n) {
  std::vector<std::string> q, w;
  std::string kinetic, springs, quartic;
  for (int i = 1; i <= n; ++i) {
    q.push_back("q" + std::to_string(i)), w.push_back("w" + std::to_string(i));
    kinetic += (i > 1 ? " + " : "") + w.back() + "^2";
    quartic += (i > 1 ? " + " : "") + q.back() + "^4";
    springs += (i > 1 ? " + (" + q.back() + " - " + q[i - 2] + ")^2" : q.back() + "^2");
  }
  springs += " + " + q.back() + "^2";
  const std::string text = "(" + kinetic + ")/2 - (" + springs + ")/2 - (" + quartic + ")/4";
  return {"chain", text, parse_formula(text), q, w, {}, {}, nullptr};
}

// N bodies in space with masses m_i = 1/i, coordinates x1 y1 z1 … and velocities u1 v1 s1 ….
FormulaSystemDefinition gravity(int bodies) {
  std::vector<std::string> q, w;
  const char* axes[3] = {"x", "y", "z"};
  const char* rates[3] = {"u", "v", "s"};
  std::string text;
  for (int i = 1; i <= bodies; ++i)
    for (int k = 0; k < 3; ++k) {
      const std::string index = std::to_string(i);
      q.push_back(axes[k] + index), w.push_back(rates[k] + index);
      text += (text.empty() ? "" : " + ") + std::string("(1/") + index + ")*" + w.back() + "^2/2";
    }
  for (int i = 1; i <= bodies; ++i)
    for (int j = i + 1; j <= bodies; ++j) {
      const std::string a = std::to_string(i), b = std::to_string(j);
      text += " + (1/" + a + ")*(1/" + b + ")/sqrt((x" + a + " - x" + b + ")^2 + (y" + a + " - y" + b + ")^2 + (z" +
              a + " - z" + b + ")^2)";
    }
  return {"gravity", text, parse_formula(text), q, w, {}, {}, nullptr};
}

// A state: the chain near q_i = sin(i)/10, w_i = cos(i)/10; bodies spread on a helix.
template <class T>
State<T, any_size> chain_state(int n) {
  using std::cos, std::sin;
  State<T, any_size> y{zero_vector<T, any_size>(n), zero_vector<T, any_size>(n)};
  for (int i = 0; i < n; ++i) y.q[i] = sin(T(i + 1)) / 10, y.w[i] = cos(T(i + 1)) / 10;
  return y;
}
template <class T>
State<T, any_size> gravity_state(int bodies) {
  using std::cos, std::sin;
  State<T, any_size> y{zero_vector<T, any_size>(3 * bodies), zero_vector<T, any_size>(3 * bodies)};
  for (int i = 0; i < bodies; ++i) {
    const T angle = T(2 * i + 1);
    y.q[3 * i] = (1 + T(i) / 4) * cos(angle), y.q[3 * i + 1] = (1 + T(i) / 4) * sin(angle), y.q[3 * i + 2] = T(i) / 8;
    y.w[3 * i] = -sin(angle) / 10, y.w[3 * i + 1] = cos(angle) / 10, y.w[3 * i + 2] = T(1) / 100;
  }
  return y;
}

struct Sizes {
  std::string system, scalar;
  std::vector<int> counts;  // n or N
  int symplecticity_up_to;  // the largest n (or N) whose dense check is timed
};

template <class T>
nlohmann::json measure(const FormulaSystemDefinition& definition, const State<T, any_size>& y, int count,
                       bool symplecticity, const T& reference_tolerance) {
  const auto system = make_formula_system<T, any_size>(definition);
  const int n = system.size();
  const T h = T(1) / 100;
  QxQDiscretization<T> midpoint;
  midpoint.rule = QxQRule::midpoint;
  const DelScheme<T> scheme = matched_scheme(midpoint);
  const Vector<T, any_size> q0 = y.q, q1 = y.q + h * y.w;
  auto [q2, report] = del_step(system, scheme, q0, q1, h);
  if (!report.converged) throw std::runtime_error("bench size: the DEL step of " + definition.name + " did not converge");
  const double batch = n >= 256 ? 0.3 : 0.1;
  const double del_ns = 1e9 * seconds_per_call(
                                  [&] {
                                    auto step = del_step(system, scheme, q0, q1, h);
                                    keep(step);
                                  },
                                  batch);
  TaylorFlow<FormulaSystem<T, any_size>> flow(system, reference_tolerance);
  State<T, any_size> end = flow.advance(y, h);  // settles the step size
  const long before = flow.report().steps;
  const long long madds_before = flow.report().multiply_adds;
  double advanced = 0;
  const double reference_ns_per_call = 1e9 * seconds_per_call(
                                                 [&] {
                                                   end = flow.advance(y, 4 * h);
                                                   keep(end);
                                                   advanced += 1;
                                                 },
                                                 batch);
  const double steps_per_call = static_cast<double>(flow.report().steps - before) / advanced;
  // The Taylor recurrences' multiply-adds a step (O(p² · tape)): the reference's time divided by
  // them is its cost per operation, which says whether a slope comes from the work or the memory.
  const double madds_per_step = static_cast<double>(flow.report().multiply_adds - madds_before) /
                                static_cast<double>(flow.report().steps - before);
  nlohmann::json row{{"system", definition.name},
                     {"n", n},
                     {"count", count},
                     {"hessian_entries", system.derivatives->pattern.size()},
                     {"newton_iterations", report.iterations},
                     {"del_ns", del_ns},
                     {"reference_ns", reference_ns_per_call / steps_per_call},
                     {"reference_order", flow.order()},
                     {"reference_tape_operations", flow.report().tape_operations},
                     {"reference_multiply_adds", madds_per_step},
                     {"reference_ns_per_multiply_add", reference_ns_per_call / steps_per_call / madds_per_step}};
  // What symplecticity does per step above symplecticity_dense_limit coordinates: the sparse
  // blocks, the generating form's defect, B_e's LU and the carried pairs through J.
  Vector<T, any_size> carried = Vector<T, any_size>::Ones(2 * n);
  row["probes_ns"] = 1e9 * seconds_per_call(
                               [&] {
                                 const auto blocks = legendre_blocks(system, midpoint, q1, q2, h);
                                 GeneratingDefect<T> generating = generating_defect(blocks, blocks, {});
                                 const DelMapJacobian<T> jacobian(blocks, blocks);
                                 for (int i = 0; i < 2 * symplecticity_probe_pairs; ++i)
                                   carried = jacobian.apply(carried) / T(carried.norm());
                                 keep(generating.defect);
                                 keep(carried);
                               },
                               batch);
  if (symplecticity) {
    row["symplecticity_ns"] = 1e9 * seconds_per_call(
                                        [&] {
                                          const auto legendre = discrete_legendre(system, midpoint, q1, q2, h);
                                          const auto jacobian = del_map_jacobian<T, any_size>(legendre, legendre);
                                          T defect = symplecticity_defect<T, any_size>(jacobian);
                                          keep(defect);
                                        },
                                        0);
  }
  return row;
}

// The least-squares slope of log(column) against log(n) over rows with lo <= n <= hi.
double slope(const nlohmann::json& rows, const char* column, int lo, int hi) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int count = 0;
  for (const auto& row : rows) {
    const int n = row["count"].get<int>();
    if (n < lo || n > hi || !row.contains(column)) continue;
    const double x = std::log(static_cast<double>(n)), y = std::log(row[column].get<double>());
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++count;
  }
  if (count < 2) return std::nan("");
  return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

void print_rows(std::ostream& out, const nlohmann::json& rows, const std::string& title) {
  out << title << "\n";
  char line[240];
  std::snprintf(line, sizeof line, "%6s %6s %9s %7s %14s %16s %18s %14s %10s %12s\n", "count", "n", "entries", "newton",
                "DEL step (us)", "reference (us)", "symplecticity (us)", "generating (us)", "tape ops",
                "ns/mult-add");
  out << line;
  for (const auto& row : rows) {
    const std::string symplecticity =
        row.contains("symplecticity_ns") ? std::to_string(static_cast<long long>(row["symplecticity_ns"].get<double>() / 1e3))
                                         : "-";
    std::snprintf(line, sizeof line, "%6d %6d %9ld %7d %14.1f %16.1f %18s %14.1f %10d %12.2f\n", row["count"].get<int>(),
                  row["n"].get<int>(), row["hessian_entries"].get<long>(), row["newton_iterations"].get<int>(),
                  row["del_ns"].get<double>() / 1e3, row["reference_ns"].get<double>() / 1e3, symplecticity.c_str(),
                  row["probes_ns"].get<double>() / 1e3, row["reference_tape_operations"].get<int>(),
                  row["reference_ns_per_multiply_add"].get<double>());
    out << line;
  }
}

}  // namespace

int run_size_benchmark(std::ostream& out, const std::string& only) {
  if (!only.empty() && only != "chain_double" && only != "chain_mpfr" && only != "gravity_double")
    throw std::invalid_argument("bench size: '" + only + "' is none of chain_double, chain_mpfr, gravity_double");
  nlohmann::json summary = nlohmann::json::object();
  const auto run = [&](const std::string& key, const std::string& title, const std::vector<int>& counts,
                       int symplecticity_up_to, const std::function<nlohmann::json(int, bool)>& one, int lo, int hi,
                       double target) {
    if (!only.empty() && key != only) return;
    nlohmann::json rows = nlohmann::json::array();
    for (int count : counts) {
      rows.push_back(one(count, count <= symplecticity_up_to));
      std::fprintf(stderr, "bench size: %s %d done\n", key.c_str(), count);
    }
    print_rows(out, rows, title);
    char line[240];
    std::snprintf(line, sizeof line,
                  "slopes over %d..%d: DEL step %.2f (target <= %.1f), reference step %.2f, symplecticity %.2f (dense, "
                  "up to %d), %.2f (generating form and probes, target <= DEL step + 0.2)\n\n",
                  lo, hi, slope(rows, "del_ns", lo, hi), target, slope(rows, "reference_ns", lo, hi),
                  slope(rows, "symplecticity_ns", lo, std::min(hi, symplecticity_up_to)), std::min(hi, symplecticity_up_to),
                  slope(rows, "probes_ns", lo, hi));
    out << line;
    out.flush();
    summary[key] = {{"rows", rows},
                    {"range", {lo, hi}},
                    {"del_slope", slope(rows, "del_ns", lo, hi)},
                    {"reference_slope", slope(rows, "reference_ns", lo, hi)},
                    {"symplecticity_slope", slope(rows, "symplecticity_ns", lo, std::min(hi, symplecticity_up_to))},
                    {"probes_slope", slope(rows, "probes_ns", lo, hi)},
                    {"del_target", target}};
  };
  run("chain_double", "(a) chain, double: n coordinates", {2, 4, 8, 16, 32, 64, 128, 256, 512, 1024}, 512,
      [](int n, bool symplecticity) {
        return measure<double>(chain(n), chain_state<double>(n), n, symplecticity, 1000 * epsilon<double>());
      },
      64, 1024, 1.2);
  {
    const int digits = 30;
    PrecisionGuard guard(digits);
    run("chain_mpfr", "(a) chain, MPFR at 30 digits: n coordinates", {2, 4, 8, 16, 32, 64, 128, 256}, 128,
        [&](int n, bool symplecticity) {
          using std::pow;
          return measure<mpfr_real>(chain(n), chain_state<mpfr_real>(n), n, symplecticity,
                                    mpfr_real(pow(mpfr_real(10), -(digits - 10))));
        },
        64, 256, 1.2);
  }
  run("gravity_double", "(b) all-pairs gravity in space, double: N bodies (n = 3N)", {2, 4, 8, 16, 32, 64}, 64,
      [](int bodies, bool symplecticity) {
        return measure<double>(gravity(bodies), gravity_state<double>(bodies), bodies, symplecticity,
                               1000 * epsilon<double>());
      },
      8, 64, 2.2);
  out << summary.dump() << "\n";
  return 0;
}

}  // namespace vivv
