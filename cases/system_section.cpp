#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "cases/case_sections.hpp"
#include "cases/catalogue.hpp"
#include "cases/formula_parser.hpp"
#include "cases/lexical_forms.hpp"
#include "cases/systems.hpp"
#include "core/formulas/formula_system.hpp"

namespace vivv::case_reading {

// "system": {"name", "lagrangian", "coordinates", "velocities", "params"}: a system as a formula.
void read_formula_system(Reader& system, CaseSpec& spec) {
  spec.system = system.string("name");
  const auto catalogue = system_names();
  if (std::find(catalogue.begin(), catalogue.end(), spec.system) != catalogue.end())
    system.fail("name", "'" + spec.system + "' is a catalogue system; a system given by its lagrangian needs a "
                        "name of its own");
  if (!is_formula_name(spec.system) && !is_name_text(spec.system, 64, "_.-"))
    system.fail("name", "expected a name of letters, digits, '_', '-' and '.', starting with a letter, got \"" +
                            echo(spec.system) + "\"");
  auto definition = std::make_shared<FormulaSystemDefinition>();
  definition->name = spec.system;
  definition->coordinates = system.strings("coordinates");
  definition->velocities = system.strings("velocities");
  const std::size_t n = definition->coordinates.size();
  if (n < 1) system.fail("coordinates", "expected at least one coordinate name, got none");
  if (definition->velocities.size() != n)
    system.fail("velocities", "expected " + std::to_string(n) + " velocity names, one per coordinate, got " +
                                  std::to_string(definition->velocities.size()));
  // Every name once, in one role, and not one the grammar reserves.
  std::map<std::string, std::string> role;
  auto claim_name = [&](const std::string& name, const std::string& field, const std::string& what) {
    if (!is_formula_name(name))
      throw CaseError(system.file(), field, "expected a name of letters, digits and '_' starting with a letter "
                                            "(at most 32 characters), got \"" + echo(name) + "\"");
    if (is_reserved_formula_name(name) || name == "qb" || name == "qe" || name == "h")
      throw CaseError(system.file(), field, "'" + name + "' is reserved (functions, pi, L, qb, qe, h)");
    if (role.count(name))
      throw CaseError(system.file(), field, "'" + name + "' is used both as " + role[name] + " and as " + what);
    role[name] = what;
  };
  for (std::size_t i = 0; i < n; ++i)
    claim_name(definition->coordinates[i], system.field("coordinates") + "[" + std::to_string(i) + "]",
               "a coordinate");
  for (std::size_t i = 0; i < n; ++i)
    claim_name(definition->velocities[i], system.field("velocities") + "[" + std::to_string(i) + "]",
               "a velocity");
  if (system.has("params")) {
    const auto& params = system.get("params");
    if (!params.is_object()) system.fail("params", "expected an object of name: decimal string, got " + echo(params));
    Reader values = system.object("params");
    for (const auto& [name, value] : params.items()) {
      claim_name(name, system.field("params") + "." + name, "a parameter");
      spec.parameters.emplace_back(name, values.number(name));
    }
    values.finish();
  }
  definition->parameters = spec.parameters;
  std::string text;
  definition->lagrangian = *read_formula(system, "lagrangian", text);
  definition->text = text;
  spec.dimension = static_cast<int>(n);
  std::vector<std::string> symmetry_texts;
  if (system.has("symmetry")) {
    symmetry_texts = system.strings("symmetry");
    if (symmetry_texts.size() != n)
      system.fail("symmetry", "expected the generator ξ(q) as " + std::to_string(n) +
                                  " formulas, one per coordinate, got " + std::to_string(symmetry_texts.size()));
    for (std::size_t i = 0; i < n; ++i) {
      const std::string field = "symmetry[" + std::to_string(i) + "]";
      if (symmetry_texts[i].size() > longest_formula) system.fail(field, "formula too long");
      try {
        definition->symmetry.push_back(parse_formula(symmetry_texts[i]));
      } catch (const FormulaError& error) {
        system.fail(field, describe_formula_error(symmetry_texts[i], error));
      }
    }
  }
  // Each component of ξ alone, so that an error names its field: a scalar in the coordinates
  // and parameters (the velocities are unknown names there).
  for (std::size_t i = 0; i < symmetry_texts.size(); ++i) {
    using V = TapeScalar<long double>;
    TapeRecording<long double> recording(static_cast<int>(n));
    FormulaScope<long double, V> scope;
    for (std::size_t j = 0; j < n; ++j)
      scope.names[definition->coordinates[j]] = FormulaValue<V>::scalar(recording.input(static_cast<int>(j)), false);
    for (const auto& [name, value] : definition->parameters)
      scope.names[name] = FormulaValue<V>::scalar(V(from_decimal<long double>(value)), true);
    try {
      if (interpret(definition->symmetry[i], scope).is_vector)
        throw FormulaError(0, "expected a number, got a vector");
    } catch (const FormulaError& error) {
      system.fail("symmetry[" + std::to_string(i) + "]", describe_formula_error(symmetry_texts[i], error));
    }
  }
  try {
    switch (n) {
      case 1: make_formula_system<long double, 1>(*definition); break;
      case 2: make_formula_system<long double, 2>(*definition); break;
      default: make_formula_system<long double, any_size>(*definition); break;
    }
  } catch (const FormulaError& error) {
    system.fail("lagrangian", describe_formula_error(text, error));
  }
  spec.formula = std::move(definition);
}

// "system.params": a decimal for each declared parameter (name, default), the default where the
// case gives none; a parameter that is not declared is an error (params.finish).
std::vector<std::pair<std::string, std::string>> read_parameters(
    Reader& system, const std::vector<std::pair<std::string, std::string>>& declared) {
  std::vector<std::pair<std::string, std::string>> values = declared;
  if (!system.has("params")) return values;
  Reader params = system.object("params");
  for (auto& [name, value] : values)
    if (params.has(name)) value = params.number(name);
  params.finish();
  return values;
}

// The system registered under the name "system.name" gives, if one is.
const RegisteredSystem* registered_system(Reader& system) {
  if (!system.has("name") || !system.get("name").is_string()) return nullptr;
  for (const auto& registered : registered_systems())
    if (registered.name == system.get("name").get<std::string>()) return &registered;
  return nullptr;
}

namespace {

// d²L/dw² of `system` at (q, w), or a CaseError naming the field when it is singular there.
template <class System>
void check_regular(const System& system, const CaseSpec& spec, const std::string& file) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = spec.dimension;
  Vector<T, N> q(n), w(n);
  for (int i = 0; i < n; ++i) q[i] = from_decimal<T>(spec.q[i]), w[i] = from_decimal<T>(spec.w[i]);
  const auto d = lagrangian_derivatives(system, q, w);
  const std::string field = spec.formula ? "system.lagrangian" : "initial";
  using std::isfinite;
  if (!isfinite(d.value))
    throw CaseError(file, field, "L is not finite at the initial state: the state is outside the Lagrangian's domain");
  const T determinant = d.d2L_dw2.determinant();
  const T scale = d.d2L_dw2.cwiseAbs().maxCoeff();
  Eigen::FullPivLU<Matrix<T, N, N>> lu(d.d2L_dw2);
  lu.setThreshold(1024 * epsilon<T>());
  if (!isfinite(determinant) || !(scale > 0) || !lu.isInvertible())
    throw CaseError(file, field, "the Lagrangian is not regular at the initial state: det d2L/dw2 = " +
                                     to_decimal<T>(determinant) + " (d2L/dw2 is singular there, so the "
                                     "Euler–Lagrange equations do not determine the acceleration)");
}

}  // namespace

// The initial state in the formula's domain (sqrt, log, powers, quotients) and the Lagrangian
// regular there, checked in long double before any work.
void check_initial_state(const CaseSpec& spec, const std::string& file) {
  using T = long double;
  std::vector<T> q, w;
  for (int i = 0; i < spec.dimension; ++i) q.push_back(from_decimal<T>(spec.q[i])), w.push_back(from_decimal<T>(spec.w[i]));
  if (spec.formula) {
    try {
      if (!spec.formula->recorded) check_formula_domain<T>(*spec.formula, q, w);
    } catch (const FormulaError& error) {
      throw CaseError(file, "system.lagrangian", describe_formula_error(spec.formula->text, error));
    }
    switch (spec.dimension) {
      case 1: check_regular(make_formula_system<T, 1>(*spec.formula), spec, file); break;
      case 2: check_regular(make_formula_system<T, 2>(*spec.formula), spec, file); break;
      default: check_regular(make_formula_system<T, any_size>(*spec.formula), spec, file); break;
    }
    return;
  }
  std::vector<std::string> parameters;
  for (const auto& [name, value] : spec.parameters) parameters.push_back(value);
  visit_system<T>(spec.system, parameters, [&](const auto& system) { check_regular(system, spec, file); });
}

// The bytes of one number in `scalar` at `digits` (MPFR: the number and its limbs).
static double bytes_per_number(const std::string& scalar, int digits) {
  if (scalar == "double") return sizeof(double);
  if (scalar == "long double") return sizeof(long double);
  if (scalar == "float128") return sizeof(quad);
  const double limbs = std::ceil(digits * 3.3219280948873623 / 64) + 1;
  return static_cast<double>(sizeof(mpfr_real)) + 8 * limbs;
}

void check_memory(const CaseSpec& spec, const std::string& file, const std::string& scalar, int digits,
                  const std::string& purpose) {
  if (!spec.formula || spec.dimension <= 2) return;
  const double n = spec.dimension;
  const double operations =
      static_cast<double>(make_formula_system<long double, any_size>(*spec.formula).program->nodes.size());
  const double needed = operations * (1 + 2 * n + 4 * n * n) * bytes_per_number(scalar, digits);
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES));
  const double page = static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double available = pages > 0 && page > 0 ? pages * page : 0;
  if (available > 0 && needed > available) {
    const auto gib = [](double bytes) { return three_digits(bytes / (1024.0 * 1024 * 1024)) + " GiB"; };
    throw CaseError(file, "system.coordinates",
                    "a system of " + std::to_string(spec.dimension) + " coordinates whose L takes " +
                        std::to_string(static_cast<long>(operations)) + " operations needs about " + gib(needed) +
                        " in " + scalar + purpose +
                        " for vivv's dense second derivatives (each operation a jet of 1 + 2n + (2n)^2 numbers), "
                        "more than this machine's " + gib(available) + " of memory");
  }
}

}  // namespace vivv::case_reading
