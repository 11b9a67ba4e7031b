// Case files: a system, an initial state, a step sweep, a discretization and
// the claims to check (foundation issue, "Case files").
//
// Reading a case validates every field against the catalogue; anything
// unknown or malformed is a CaseError naming the file, the field and what
// was expected. Numbers stay decimal strings here: they are parsed in the
// working precision only when the case runs.
#pragma once

#include <istream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/formulas/formula_system.hpp"

namespace vivv {

// The order tolerance when a case gives none, and the largest it may give: a
// wider tolerance would let an order-r prediction accept order r − 1.
inline constexpr const char* default_order_tolerance = "0.2";
inline constexpr const char* maximum_order_tolerance = "0.3";
// The most MPFR digits a case may ask for: what runs in minutes. Measured on the paper
// example (midpoint, T = 2, N = 16 … 512): at 1000 digits the reference flow to T takes
// 36 s and the whole case 3 min; at 2000 the reference flow alone took 11 min.
inline constexpr int maximum_digits = 1000;

struct CaseError : std::runtime_error {
  CaseError(const std::string& file, const std::string& field, const std::string& message);
  std::string file, field;
};

struct TwinSpec {
  std::vector<std::string> a;
  int power = 1;
};

struct DiscretizationSpec;

// A discretization of TQ (docs/theory.md (TQ)): {"formalism": "tq", "psi": "linear",
// "theta": "1/2", "lagrangian": "quadrature", "nodes": 4} or
// {"formalism": "tq", "psi": "linear", "theta": "0", "lagrangian": "pullback",
//  "qxq": {"kind": "midpoint"}} or {"formalism": "tq", "psi": "taylor", "r": 2, ...},
// each with an optional twin term.
struct TQSpec {
  std::string psi = "linear";  // "linear" or "taylor"
  int r = 1;                   // degree of the taylor curve segment, 1..8 (taylor only)
  std::string theta = "0";  // a decimal or a fraction "p/q" in [0, 1]
  std::string lagrangian = "quadrature";
  int nodes = 0;  // Gauss–Legendre nodes (quadrature)
  std::shared_ptr<DiscretizationSpec> qxq;  // pulled-back Q×Q discrete Lagrangian (pullback)
};

struct DiscretizationSpec {
  std::string formalism = "qxq";  // "qxq", "tq", or "map" for kinds "odeint", "map", "process"
  std::string kind;                      // a Q×Q rule name (core/qxq/discrete_lagrangian.hpp)
  std::optional<std::string> parameter;  // "alpha" or "beta", for the rules that take one
  // kind "expression": L_d as a formula in qb, qe, h, L(x, v) and the system's parameters, and
  // the order its author claims for it.
  std::string expression;
  std::shared_ptr<const FormulaNode> expression_tree;
  // kind "user" (read as an "expression"): L_d registered as C++ code instead of a formula.
  std::shared_ptr<const PerScalar<DiscreteLagrangianRecorder>> recorded;
  int declared_order = 0;
  // kind "galerkin": degree s of the curve, "gauss" or "lobatto", and the number of nodes.
  int galerkin_degree = 0, galerkin_nodes = 0;
  std::string galerkin_quadrature;
  std::string stepper;  // kind "odeint": one of odeint_steppers() (core/maps/odeint_map.hpp)
  // kind "process": a one-step map in another program, spoken to over its standard input and
  // output (protocol vivv-map/1, docs/process-protocol.md); its order is declared_order.
  std::vector<std::string> command;  // the program and its arguments, never through a shell
  // "precision": "double" — the program computes in IEEE double (a NumPy or C integrator): the
  // case runs in double, every instance of the program is greeted with 17 digits, and
  // symplecticity differentiates it at widths a double resolves. Empty: the program computes
  // with the digits each greeting asks for.
  std::string process_precision;
  // Set by the run, not the case file: whether this run may start programs named in case files
  // (vivv run --allow-process), and how long one may take to answer (--process-timeout).
  bool process_allowed = false;
  double process_timeout_seconds = 30;
  std::optional<TwinSpec> twin;
  std::optional<TQSpec> tq;              // formalism "tq"
};

// A claim a case knows to fail: why, and — for a claim that predicts an order — the range the
// failing series' fitted order must lie in. Any other failure is a failure.
struct ExpectedFailure {
  std::string reason;
  std::optional<std::pair<std::string, std::string>>
      observed_order;  // [low, high], decimal strings
};

struct CaseSpec {
  std::string file;
  nlohmann::json source;  // the case file as read, for the report
  std::string name;
  std::string system;  // a catalogue name, or the name a formula system is given
  int dimension = 1;
  // A system written as a formula (its parameters are `parameters`); empty for the catalogue's.
  std::shared_ptr<const FormulaSystemDefinition> formula;
  std::vector<std::pair<std::string, std::string>> parameters;  // every parameter, defaults filled in
  // What the case reads but nothing computes with: a formula system's parameter that neither L,
  // its symmetry nor L_d names (a misspelt "mass" beside L's "m"). Said on the console and in the
  // report; the run goes on (a process program receives every parameter in its greeting).
  std::vector<std::string> warnings;
  std::vector<std::string> q, w;
  std::string final_time;  // "T"
  std::string start_time = "0";  // "t0": the time of the initial state (it matters to an L that depends on time)
  std::vector<int> steps;
  std::string scalar = "mpfr";  // "double", "long double", "float128" or "mpfr"
  int digits = 60;              // MPFR only
  DiscretizationSpec discretization;
  std::optional<DiscretizationSpec> past_discretization;
  std::optional<DiscretizationSpec> compare_discretization;  // contact-order: the second discretization
  std::string start = "reference";  // or "momentum"
  std::vector<std::string> claims;
  // Exact orders a case declares, each >= 1 and never below the theorem's
  // bound for the claim (checked when the case runs: harness/claims/registry.hpp).
  std::map<std::string, int> expect;
  std::string order_tolerance = default_order_tolerance;  // |observed − predicted| allowed
  std::map<std::string, ExpectedFailure> xfail;  // claim id -> how and why the case knows it fails
  bool refine = false;                       // extend the sweep until the finest orders settle
  std::vector<std::string> labels;       // e.g. "paper"
  // Every decimal the case file gives, with its field: checked against the range of the scalar
  // the case runs in (check_precision_options).
  std::vector<std::pair<std::string, std::string>> decimals;
  // The numbers written as formulas ("initial.q[0]": "pi/4"), as written; their decimals, of
  // maximum_digits + 10 digits, are in q, w, final_time and parameters.
  std::vector<std::pair<std::string, std::string>> written;
};

// Reads and validates a case file; throws CaseError (also for a path that is
// not a regular file, JSON nested deeper than maximum_json_depth and a key
// that occurs twice in one object).
// Why the claim modified-energy does not apply to the case's discretization (its H₂ is derived
// for the midpoint and trapezoid rules without twin terms), or "" when it does.
std::string modified_energy_inapplicable(const CaseSpec& spec);

CaseSpec read_case_file(const std::string& path);

// What `vivv run --scalar S --digits D` would make of `spec`: the checks read_case_file makes
// of its own "scalar" and "digits" (digits only in MPFR; 3 and 4 coordinates in MPFR only;
// precision-leak in MPFR, at twice the digits; every decimal within the scalar's range) made
// again for the overrides, so that a run refuses every case it cannot compute before it
// computes any. Throws CaseError naming the case file and the option or the field.
void check_precision_options(const CaseSpec& spec, const std::optional<std::string>& scalar,
                             std::optional<int> digits);

// JSON from `in`, refusing nesting deeper than maximum_json_depth and
// duplicate keys; CaseError naming `where` otherwise.
inline constexpr int maximum_json_depth = 64;
nlohmann::json parse_json_strictly(std::istream& in, const std::string& where);
// Validates an already-parsed case; `file` names it in errors.
CaseSpec parse_case(const nlohmann::json& json, const std::string& file);

// The scalars a case may run in ("scalar", vivv run --scalar).
const std::vector<std::string>& scalar_names();

// The parameters as the case file writes them: a name for each scalar, an array for each family
// (m[1], m[2], … back into "m": [...], in index order, as the case gives them), each value
// through `value(name, text)`. The process greeting and the report carry them so: a program reads
// "m" as the case's array, and no reader meets m[10] sorted before m[2].
template <class Value>
nlohmann::json parameters_as_written(const std::vector<std::pair<std::string, std::string>>& parameters,
                                     Value&& value) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, text] : parameters) {
    const auto bracket = name.find('[');
    if (bracket == std::string::npos || name.back() != ']') {
      out[name] = value(name, text);
      continue;
    }
    nlohmann::json& members = out[name.substr(0, bracket)];
    if (!members.is_array()) members = nlohmann::json::array();
    members.push_back(value(name, text));  // the family's members come in index order (system_section.cpp)
  }
  return out;
}

// The catalogue system `name` written as a formula, with `parameters`: what runs a catalogue
// system in a scalar other than MPFR (tests/core/formulas/formula_system_test.cpp checks it against the
// compiled system).
FormulaSystemDefinition catalogue_twin(const std::string& name,
                                       const std::vector<std::pair<std::string, std::string>>& parameters);

// Names accepted in case files, for `vivv list` and error messages.
std::vector<std::string> system_names();
std::vector<std::string> claim_names();

}  // namespace vivv
