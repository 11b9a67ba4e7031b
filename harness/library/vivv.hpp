// vivv as a library: the whole public interface, for a program that links vivv::vivv
// (find_package(vivv) or add_subdirectory) and includes <vivv/vivv.hpp>.
//
// A case is what `vivv run` reads: a JSON case file (docs/case-files.md) naming the system,
// the initial state, T, the step counts, the scalar and the claims. What the library adds is
// code of your own under test, written once for any scalar S: a system (register_system), a
// Q×Q discrete Lagrangian (register_discrete_lagrangian) or a one-step map,
//
//   struct MyMethod {
//     // Advances (q, w) by h in place; a(q) = M⁻¹ F(q) = q'' as std::array<S, n>.
//     template <class S, std::size_t n, class Acceleration>
//     void step(std::array<S, n>& q, std::array<S, n>& w, const S& h, const Acceleration& a) const;
//   };
//
//   vivv::register_map<MyMethod>("my-method", 2);   // its name and the order you state
//
// and then a case with "discretization": {"kind": "map", "name": "my-method"} is checked like
// one of Boost.Odeint's steppers: global-order, symplecticity (its Jacobian by automatic
// differentiation through your own code), energy-behaviour, discrete-noether and
// precision-leak, in the case's scalar (double, long double, float128 or MPFR).
//
//   vivv::Run run = vivv::run({"cases/my-method.json"});        // every claim, as vivv run
//   vivv::write_reports(run, "vivv-report");                    // report.json, .html, junit.xml
//   vivv::print_table(std::cout, run);                          // the console table of vivv run
//   EXPECT_TRUE(vivv::check(run)) ;                             // with <vivv/gtest.hpp>
//
// Registering is idempotent: the same name registered again with the same type, order and value
// (an empty struct is always the same value) is a no-op, so registration may sit in a test
// fixture's SetUp or in each TEST; the same name for something else is refused.
//
// Bad input throws, where `vivv run` exits 2: a malformed case, a name nobody registered or a
// non-separable Lagrangian for a map as vivv::CaseError (naming the file and the field); a step
// too large for the solver as vivv::SolverError; a state where L is not regular as
// vivv::SingularLagrangianError; a computation that leaves the finite numbers as
// std::domain_error.
#pragma once

#include <array>
#include <concepts>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <typeindex>
#include <utility>
#include <vector>

#include "cases/case_file.hpp"
#include "core/maps/odeint_map.hpp"
#include "core/formulas/recorded.hpp"
#include "core/maps/user_map.hpp"
#include "harness/run/run_case.hpp"
#include "reports/report.hpp"

namespace vivv {

// Registers `method` under `name`, with the order r its authors state (|Φ_h − F_h| = O(h^{r+1})),
// for every scalar and any number of coordinates. A method written for std::array<S, n> runs on
// systems of 1 to 4 coordinates; one written for any container with size() and [] (it is given
// std::vector<S> beyond 2) runs on any. The same method again under its name is a no-op; another under a
// taken name, or one of odeint's, is refused.
template <class Method>
void register_map(const std::string& name, int order, Method method = {});

// Registers a Lagrangian system written as C++ code, for any scalar S:
//   struct MySystem {
//     static constexpr int dimension = 1;                 // any number of coordinates
//     static std::vector<std::pair<std::string, std::string>> parameters();  // name, default
//     template <class S, class Parameter>                 // parameter("k") is k in S
//     S lagrangian(const std::array<S, dimension>& q, const std::array<S, dimension>& w,
//                  const Parameter& parameter) const;
//   };
// A case names it {"name": name, "params": {...}} under "system". vivv records L on a tape in
// the case's scalar (core/formulas/recorded.hpp): +, −, ×, ÷, sin, cos, exp, log, sqrt and pow by a
// constant are recorded; a branch on a value is taken once, where the recording runs.
template <class System>
void register_system(const std::string& name, System system = {});

// Registers a Q×Q discrete Lagrangian written as C++ code, with the order r its authors state
// (L_d = L_d^E + O(h^{r+1})), for any scalar S and any dimension n:
//   struct MyRule {
//     template <class S, std::size_t n, class Lagrangian>  // lagrangian(x, v): the system's L
//     S discrete_lagrangian(const std::array<S, n>& qb, const std::array<S, n>& qe, const S& h,
//                           const Lagrangian& lagrangian) const;
//   };
// A case names it {"kind": "user", "name": name} as its discretization; it takes every Q×Q
// claim an "expression" L_d takes, recorded on a tape as for register_system.
template <class Rule>
void register_discrete_lagrangian(const std::string& name, int order, Rule rule = {});

// The cases of one run and its report (schema reports/schema.json).
struct Run {
  std::vector<CaseResult> results;
  nlohmann::json report;
};

// The options of `vivv run` a program can give vivv::run (`vivv run --help`, harness/command_line/options.cpp, says more).
struct RunOptions {
  std::optional<int> digits;          // --digits: MPFR digits for every case (20 … 1000)
  std::optional<std::string> scalar;  // --scalar: double, "long double", float128 or mpfr
  bool refine = false;                // --refine: halve h until every fitted order settles
  // --jobs: cases at once, each in a worker process forked from this one (MPFR's precision is
  // process-wide); Run::results then stays empty and Run::report holds every case.
  int jobs = 1;
  // --max-seconds: each case's budget of wall time; a case past it is killed in its worker
  // process and vivv::run throws std::runtime_error naming it (a budget implies workers).
  std::optional<int> max_seconds;
  bool allow_process = false;   // --allow-process: cases may start the programs they name
  double process_timeout = 30;  // --process-timeout: seconds for each answer of such a program
  std::function<void(const std::string&)> progress;  // progress lines, as --progress prints them
};

// Reads and runs each case file, as `vivv run FILE ... [options]` does.
Run run(const std::vector<std::string>& case_files, const RunOptions& options = {});

// The console table `vivv run` prints: one row per claim, the explanations of those that do not
// pass, the summary line.
void print_table(std::ostream& out, const Run& run);

// Writes DIR/report.json, report.html and junit.xml; the paths written.
std::vector<std::string> write_reports(const Run& run, const std::string& directory);

// Every claim of the run holds (pass, or xfail where the case expects a failure).
bool holds(const Run& run);

// One line per claim that does not hold: case, claim, verdict and why (from the report, so also
// for a run in workers).
std::string failures(const Run& run);

// ---- definitions ----


namespace detail {

// What was registered under each name, so that registering the same thing again is a no-op.
struct Registration {
  std::string kind, name;
  std::type_index type;
  int order;
  std::shared_ptr<const void> value;
};

inline std::vector<Registration>& registrations() {
  static std::vector<Registration> all;
  return all;
}

// Whether `name` was registered as `kind` before with the same type, order and value (then the
// registration is a no-op); throws when the name was registered as something else.
template <class X>
bool registered_before(const std::string& kind, const std::string& name, const X& value,
                       int order) {
  for (const auto& earlier : registrations()) {
    if (earlier.kind != kind || earlier.name != name) continue;
    std::string differs;
    if (earlier.type != std::type_index(typeid(X)))
      differs = "as another type";
    else if (earlier.order != order)
      differs = "with order " + std::to_string(earlier.order);
    else if constexpr (std::is_empty_v<X>)
      return true;
    else if constexpr (std::equality_comparable<X>) {
      if (*static_cast<const X*>(earlier.value.get()) == value) return true;
      differs = "with another value of its type";
    } else {
      differs =
          "with a value of a type without operator==, which vivv cannot compare with this one";
    }
    throw std::invalid_argument(kind + ": '" + name + "' is already registered " + differs +
                                "; give this one a name of its own");
  }
  return false;
}

template <class X>
void remember_registration(const std::string& kind, const std::string& name, const X& value,
                           int order) {
  registrations().push_back(
      {kind, name, std::type_index(typeid(X)), order, std::make_shared<const X>(value)});
}

// A name not yet taken by a catalogue system, a registered one or a map.
inline void check_new_name(const std::string& what, const std::string& name, const std::vector<std::string>& taken) {
  if (name.empty()) throw std::invalid_argument(what + ": an empty name");
  for (const auto& other : taken)
    if (other == name) throw std::invalid_argument(what + ": '" + name + "' is already taken");
}

// One recorder for each scalar, from make.template operator()<T>().
template <template <class> class F, class Make>
std::shared_ptr<const PerScalar<F>> per_scalar(const Make& make) {
  auto functions = std::make_shared<PerScalar<F>>();
  functions->in_double = make.template operator()<double>();
  functions->in_long_double = make.template operator()<long double>();
  functions->in_quad = make.template operator()<quad>();
  functions->in_mpfr = make.template operator()<mpfr_real>();
  return functions;
}

template <int n, class V>
std::array<V, n> as_array(const std::vector<V>& x) {
  std::array<V, n> a;
  for (int i = 0; i < n; ++i) a[i] = x[i];
  return a;
}

// The user's rule in dimension n on the recorded inputs.
template <int n, class Rule, class V, class Lagrangian>
V record_rule(const Rule& rule, const std::vector<V>& qb, const std::vector<V>& qe, const V& h,
              const Lagrangian& lagrangian) {
  auto lagrangian_n = [&](const std::array<V, n>& x, const std::array<V, n>& v) {
    return lagrangian(std::vector<V>(x.begin(), x.end()), std::vector<V>(v.begin(), v.end()));
  };
  return V(rule.discrete_lagrangian(as_array<n>(qb), as_array<n>(qe), h, lagrangian_n));
}

}  // namespace detail

template <class Method>
void register_map(const std::string& name, int order, Method method) {
  if (detail::registered_before("register_map", name, method, order)) return;
  std::vector<std::string> taken;
  for (const auto& registered : registered_maps()) taken.push_back(registered.name);
  for (const auto& stepper : odeint_steppers()) taken.push_back(stepper.name);
  detail::check_new_name("register_map", name, taken);
  if (order < 1) throw std::invalid_argument("register_map: '" + name + "' needs an order of at least 1");
  const RegisteredMap info{name, order};
  auto add = [&]<class T, int n>() {
    map_factories<T, n>()[name] = [info, method](const SeparableSystem<T, n>& system) {
      return std::shared_ptr<const OneStepMap<T, n>>(std::make_shared<const UserMap<Method, T, n>>(info, method, system));
    };
  };
  // Every scalar sizes every system at run time (harness/run/run_case.cpp).
  add.template operator()<double, any_size>();
  add.template operator()<long double, any_size>();
  add.template operator()<quad, any_size>();
  add.template operator()<mpfr_real, any_size>();
  registered_maps().push_back(info);
  detail::remember_registration("register_map", name, method, order);
}

template <class System>
void register_system(const std::string& name, System system) {
  constexpr int n = System::dimension;
  static_assert(n >= 1, "a system has at least one coordinate");
  if (detail::registered_before("register_system", name, system, 0)) return;
  detail::check_new_name("register_system", name, system_names());
  auto recorder = detail::per_scalar<SystemRecorder>([&]<class T>() -> SystemRecorder<T> {
    return [system](const TapeVector<T>& q, const TapeVector<T>& w,
                    const std::vector<std::pair<std::string, std::string>>& parameters) {
      auto parameter = [&](const std::string& key) {
        for (const auto& [parameter_name, value] : parameters)
          if (parameter_name == key) return TapeScalar<T>(from_decimal<T>(value));
        throw std::invalid_argument("the system asks for a parameter '" + key + "' it does not declare");
      };
      return TapeScalar<T>(system.lagrangian(detail::as_array<n>(q), detail::as_array<n>(w), parameter));
    };
  });
  registered_systems().push_back({name, n, System::parameters(), recorder});
  detail::remember_registration("register_system", name, system, 0);
}

template <class Rule>
void register_discrete_lagrangian(const std::string& name, int order, Rule rule) {
  if (detail::registered_before("register_discrete_lagrangian", name, rule, order)) return;
  std::vector<std::string> taken;
  for (const auto& registered : registered_discrete_lagrangians()) taken.push_back(registered.name);
  detail::check_new_name("register_discrete_lagrangian", name, taken);
  if (order < 1) throw std::invalid_argument("register_discrete_lagrangian: '" + name + "' needs an order of at least 1");
  auto recorder = detail::per_scalar<DiscreteLagrangianRecorder>([&]<class T>() -> DiscreteLagrangianRecorder<T> {
    return [rule, name](const TapeVector<T>& qb, const TapeVector<T>& qe, const TapeScalar<T>& h,
                  const std::function<TapeScalar<T>(const TapeVector<T>&, const TapeVector<T>&)>& lagrangian) {
      using V = TapeScalar<T>;
      // A rule written for any container gets std::vector; one written for std::array<S, n> gets
      // arrays of 1 to 4 coordinates.
      if constexpr (requires { V(rule.discrete_lagrangian(qb, qe, h, lagrangian)); })
        return V(rule.discrete_lagrangian(qb, qe, h, lagrangian));
      switch (qb.size()) {
        case 1: return detail::record_rule<1>(rule, qb, qe, h, lagrangian);
        case 2: return detail::record_rule<2>(rule, qb, qe, h, lagrangian);
        case 3: return detail::record_rule<3>(rule, qb, qe, h, lagrangian);
        case 4: return detail::record_rule<4>(rule, qb, qe, h, lagrangian);
        default:
          throw std::invalid_argument("the discrete Lagrangian '" + name + "' is written for std::array<S, n>: a system of " +
                                      std::to_string(qb.size()) +
                                      " coordinates passes std::vector<S> (write discrete_lagrangian for any container)");
      }
    };
  });
  registered_discrete_lagrangians().push_back({name, order, recorder});
  detail::remember_registration("register_discrete_lagrangian", name, rule, order);
}

}  // namespace vivv
