// vivv as a library: the whole public interface, for a program that links vivv::vivv
// (find_package(vivv) or add_subdirectory) and includes <vivv/vivv.hpp>.
//
// A case is what `vivv run` reads: a JSON case file (docs/case-files.md) naming the system,
// the initial state, T, the step counts, the scalar and the claims. What the library adds is
// a method of your own under test: a one-step map, written once for any scalar S,
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
//   EXPECT_TRUE(vivv::check(run)) ;                             // with <vivv/gtest.hpp>
//
// Bad input (a malformed case, a name nobody registered, a non-separable Lagrangian for a map)
// throws vivv::CaseError naming the file and the field, as `vivv run` exits 2 on it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cases/case_file.hpp"
#include "core/odeint_map.hpp"
#include "core/user_map.hpp"
#include "harness/run_case.hpp"
#include "reports/report.hpp"

namespace vivv {

// Registers `method` under `name`, with the order r its authors state (|Φ_h − F_h| = O(h^{r+1})),
// for every scalar and dimension vivv runs: MPFR for 1 to 4 coordinates, double, long double
// and float128 for 1 and 2. A name registered twice, or one of odeint's, is refused.
template <class Method>
void register_map(const std::string& name, int order, Method method = {});

// The cases of one run and its report (schema reports/schema.json).
struct Run {
  std::vector<CaseResult> results;
  nlohmann::json report;
};

// Reads and runs each case file, as `vivv run FILE ...` does (the cases' own digits and sweeps).
Run run(const std::vector<std::string>& case_files);

// Writes DIR/report.json, report.html and junit.xml; the paths written.
std::vector<std::string> write_reports(const Run& run, const std::string& directory);

// Every claim of the run holds (pass, or xfail where the case expects a failure).
bool holds(const Run& run);

// One line per claim that does not hold: case, claim, verdict and why.
std::string failures(const Run& run);

// ---- definitions ----

template <class Method>
void register_map(const std::string& name, int order, Method method) {
  for (const auto& registered : registered_maps())
    if (registered.name == name) throw std::invalid_argument("register_map: '" + name + "' is registered twice");
  for (const auto& stepper : odeint_steppers())
    if (stepper.name == name) throw std::invalid_argument("register_map: '" + name + "' names an odeint stepper");
  if (order < 1) throw std::invalid_argument("register_map: '" + name + "' needs an order of at least 1");
  const RegisteredMap info{name, order};
  auto add = [&]<class T, int n>() {
    map_factories<T, n>()[name] = [info, method](const SeparableSystem<T, n>& system) {
      return std::shared_ptr<const OneStepMap<T, n>>(std::make_shared<const UserMap<Method, T, n>>(info, method, system));
    };
  };
  add.template operator()<mpfr_real, 1>();
  add.template operator()<mpfr_real, 2>();
  add.template operator()<mpfr_real, 3>();
  add.template operator()<mpfr_real, 4>();
  add.template operator()<double, 1>();
  add.template operator()<double, 2>();
  add.template operator()<long double, 1>();
  add.template operator()<long double, 2>();
  add.template operator()<quad, 1>();
  add.template operator()<quad, 2>();
  registered_maps().push_back(info);
}

}  // namespace vivv
