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
#include "core/formulas/formula_size.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/lagrangian/euler_lagrange_tape.hpp"
#include "core/platform/memory_limit.hpp"
#include "cases/memory_estimate.hpp"
#include "core/structure/dense_limit.hpp"

namespace vivv::case_reading {

namespace {

std::string gib(double bytes) { return three_digits(bytes / (1024.0 * 1024 * 1024)) + " GiB"; }

// L recorded within what reading may spend, before the rest of the system is built from it: the
// operations its sums expand to as written (core/formulas/formula_size.hpp: its sums' bounds
// walked, no term expanded) within maximum_formula_operations, a bound on the work of reading;
// then its tape recorded under a ceiling of operations that the memory this process may take
// holds — the recording and the edge-pushing record of its sparse second derivatives,
// recording_bytes_per_operation an operation whatever the number of coordinates (measured: 904 MB
// reading 645 866 operations of all-pairs gravity in 1026 coordinates, 1.4 KiB an operation; the
// first-order jets of 1 + 2n numbers this once also counted are not formed at run-time sizes, and
// counting them refused a 342-atom cluster at 35 KiB an operation). Refused naming the estimate, the
// limit and the field before the memory is spent. Returns the tape's operations.
std::size_t record_within_limits(const FormulaSystemDefinition& definition, Reader& system) {
  const std::size_t n = definition.coordinates.size();
  double written = 0;
  if (!definition.recorded) {
    written = formula_operations(definition.lagrangian, maximum_formula_operations);
    if (written > maximum_formula_operations)
      system.fail("lagrangian", "the formula's sums expand to more than " +
                                    std::to_string(static_cast<long>(maximum_formula_operations)) +
                                    " operations as written (counted from its sums' bounds, before expanding "
                                    "them): vivv reads formulas up to that size");
  }
  const double per_operation = recording_bytes_per_operation;
  const MemoryLimit limit = memory_limit();
  const double ceiling = std::max(64.0, std::floor(limit.bytes / per_operation));
  try {
    const TapeCeiling guard(ceiling < 1e15 ? static_cast<std::size_t>(ceiling) : 0);
    return record_lagrangian<long double>(definition, static_cast<int>(n)).nodes.size();
  } catch (const TapeCeilingReached& reached) {
    system.fail("lagrangian", "reading this system needs more than the " + gib(limit.bytes) +
                                  " this process may take (" + limit.what + "): its L records more than " +
                                  std::to_string(reached.nodes) + " operations" +
                                  (written > 0 ? " (about " + std::to_string(static_cast<long>(written)) +
                                                     " as written, before equal terms are shared)"
                                               : std::string()) +
                                  ", each about " + std::to_string(static_cast<long>(per_operation)) +
                                  " bytes in " + std::to_string(n) +
                                  " coordinates (its tape and the record of its sparse second derivatives): "
                                  "stopped there, before the memory was spent");
  }
  return 0;
}

}  // namespace

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
  // "coordinates" and "velocities": names, or indexed families {"x": [N, d]} whose members x[i, k]
  // are coordinates in row-major order, entry by entry with the same shapes.
  std::vector<std::vector<int>> coordinate_shapes;
  const auto read_names = [&](const std::string& key, const std::string& what, std::vector<std::string>& names,
                              std::vector<std::vector<int>>& shapes) {
    const auto& value = system.get(key);
    if (!value.is_array() || value.size() > 100000)
      system.fail(key, "expected an array of names and indexed families such as {\"x\": [6, 3]}, got " + echo(value));
    for (std::size_t e = 0; e < value.size(); ++e) {
      const auto& entry = value[e];
      const std::string field = system.field(key) + "[" + std::to_string(e) + "]";
      if (entry.is_string()) {
        claim_name(entry.get<std::string>(), field, what);
        names.push_back(entry.get<std::string>());
        shapes.push_back({});
        continue;
      }
      if (!entry.is_object() || entry.size() != 1)
        throw CaseError(system.file(), field, "expected a name or one indexed family such as {\"x\": [6, 3]}, got " +
                                                  echo(entry));
      const std::string family = entry.begin().key();
      const auto& shape_json = entry.begin().value();
      claim_name(family, field, what + " family");
      std::vector<int> shape;
      long members = 1;
      if (shape_json.is_array() && !shape_json.empty() && shape_json.size() <= 3)
        for (const auto& extent : shape_json) {
          if (!extent.is_number_integer() || extent.get<long long>() < 1 || extent.get<long long>() > 1000000) {
            shape.clear();
            break;
          }
          shape.push_back(extent.get<int>());
          members *= shape.back();
        }
      if (shape.empty() || members > 1000000)
        throw CaseError(system.file(), field + "." + family,
                        "expected the family's extents, one to three positive integers such as [6, 3] (at most "
                        "10^6 members), got " + echo(shape_json));
      std::vector<int> index(shape.size(), 1);
      for (long m = 0; m < members; ++m) {
        std::string name = family + "[";
        for (std::size_t k = 0; k < index.size(); ++k) name += (k ? "," : "") + std::to_string(index[k]);
        names.push_back(name + "]");
        for (int k = static_cast<int>(index.size()) - 1; k >= 0 && ++index[k] > shape[k]; --k) index[k] = 1;
      }
      shapes.push_back(shape);
    }
  };
  std::vector<std::vector<int>> velocity_shapes;
  read_names("coordinates", "a coordinate", definition->coordinates, coordinate_shapes);
  read_names("velocities", "a velocity", definition->velocities, velocity_shapes);
  const std::size_t n = definition->coordinates.size();
  if (n < 1) system.fail("coordinates", "expected at least one coordinate name, got none");
  if (definition->velocities.size() != n || velocity_shapes != coordinate_shapes)
    system.fail("velocities", "expected a velocity for each coordinate, entry by entry (a name for a name, a family "
                              "of the same extents for a family): " + std::to_string(n) + " coordinates, got " +
                                  std::to_string(definition->velocities.size()) + " velocities");
  // "params": a decimal string per name, or an array of them (a family m[1], m[2], …).
  if (system.has("params")) {
    const auto& params = system.get("params");
    if (!params.is_object()) system.fail("params", "expected an object of name: decimal string, got " + echo(params));
    Reader values = system.object("params");
    for (const auto& [name, value] : params.items()) {
      if (value.is_array()) {
        claim_name(name, system.field("params") + "." + name, "a parameter family");
        if (value.empty() || value.size() > 1000000)
          values.fail(name, "expected an array of 1 to 10^6 decimal strings, got " + echo(value));
        const std::vector<std::string> members = values.numbers(name, value.size());
        for (std::size_t i = 0; i < members.size(); ++i)
          spec.parameters.emplace_back(name + "[" + std::to_string(i + 1) + "]", members[i]);
        continue;
      }
      claim_name(name, system.field("params") + "." + name, "a parameter");
      // A coefficient that moves with the time ("0.5*cos(2*t)") is not a parameter: say where it goes.
      const std::string time_name = system.has("time") && system.get("time").is_string()
                                        ? system.get("time").get<std::string>()
                                        : std::string("t");
      if (value.is_string() && !is_numeral_text(value.get<std::string>()) &&
          value.get<std::string>().size() <= longest_formula) {
        try {
          if (formula_uses_name(parse_formula(value.get<std::string>()), time_name))
            values.fail(name, "uses the time '" + time_name +
                                  "': a parameter is a number, the same at every t; a coefficient that moves with the "
                                  "time belongs in the lagrangian — write its formula there in place of '" + name + "'");
        } catch (const FormulaError&) {
        }
      }
      spec.parameters.emplace_back(name, values.number(name));
    }
    values.finish();
  }
  definition->parameters = spec.parameters;
  std::string text;
  definition->lagrangian = *read_formula(system, "lagrangian", text);
  definition->text = text;
  // The time: "t" in the formula, unless a coordinate, velocity or parameter is named t, and
  // whatever "time" names (then the formula must use it). An L that uses it depends on time.
  if (system.has("time")) {
    const std::string name = system.string("time");
    claim_name(name, system.field("time"), "the time");
    definition->time_name = name;
    if (!formula_uses_name(definition->lagrangian, name))
      system.fail("time", "names the time '" + name + "', which the lagrangian does not use: leave \"time\" out "
                          "for a Lagrangian that does not depend on time");
  } else if (role.count("t")) {
    definition->time_name.clear();  // t is the case's own name for something else; the time has none
  }
  definition->time_dependent =
      !definition->time_name.empty() && formula_uses_name(definition->lagrangian, definition->time_name);
  spec.dimension = static_cast<int>(n);
  std::vector<std::string> symmetry_texts, symmetry_fields;
  const auto parse_component = [&](const std::string& formula, const std::string& field) {
    if (formula.size() > longest_formula) system.fail(field, "formula too long");
    try {
      return parse_formula(formula);
    } catch (const FormulaError& error) {
      throw CaseError(system.file(), system.field(field), describe_formula_error(formula, error));
    }
  };
  if (system.has("symmetry") && system.get("symmetry").is_object()) {
    // {"x[i]": ["-x[i,2]", "x[i,1]", "0"], "y": "1"}: per family, the generator of member i
    // (one formula, or one per last index), and per name its formula; what is not named is 0.
    const auto& object = system.get("symmetry");
    std::map<std::string, std::pair<std::string, nlohmann::json>> given;  // family or name: (index, formulas)
    for (const auto& [key, value] : object.items()) {
      const auto open = key.find('[');
      const std::string base = key.substr(0, open);
      std::string index;
      if (open != std::string::npos) {
        if (key.back() != ']' || !is_formula_name(key.substr(open + 1, key.size() - open - 2)))
          system.fail("symmetry", "expected a key such as \"x[i]\" (a family and the name of its first index) or a "
                                  "coordinate's name, got \"" + echo(key) + "\"");
        index = key.substr(open + 1, key.size() - open - 2);
        if (is_reserved_formula_name(index))
          system.fail("symmetry", "the index '" + echo(index) + "' of the key \"" + echo(key) +
                                      "\" is a reserved name (a function, pi, L or sum): name the index i, j, …");
      }
      given[base] = {index, value};
    }
    std::size_t member = 0;
    for (std::size_t e = 0; e < coordinate_shapes.size(); ++e) {
      const std::vector<int>& shape = coordinate_shapes[e];
      const std::string name = definition->coordinates[member].substr(0, definition->coordinates[member].find('['));
      const auto found = given.find(name);
      long members = 1;
      for (int extent : shape) members *= extent;
      for (long m = 0; m < members; ++m, ++member) {
        const std::string field = "symmetry." + name;
        if (found == given.end()) {
          symmetry_texts.push_back("0"), symmetry_fields.push_back(field);
          definition->symmetry.push_back(parse_formula("0"));
          continue;
        }
        const auto& [index, formulas] = found->second;
        if (shape.empty() != index.empty())
          system.fail("symmetry", shape.empty() ? "'" + name + "' is a coordinate, not a family: write its key as \"" +
                                                      name + "\""
                                                : "'" + name + "' is a family: write its key with the name of its first "
                                                               "index, \"" + name + "[i]\"");
        const int last = shape.size() == 2 ? static_cast<int>(m % shape[1]) : 0;
        std::string formula;
        if (shape.size() <= 1 && formulas.is_string()) {
          formula = formulas.get<std::string>();
        } else if (shape.size() == 2 && formulas.is_array() && formulas.size() == static_cast<std::size_t>(shape[1]) &&
                   formulas[static_cast<std::size_t>(last)].is_string()) {
          formula = formulas[static_cast<std::size_t>(last)].get<std::string>();
        } else {
          system.fail("symmetry", "expected for '" + name + "' " +
                                      (shape.size() <= 1 ? std::string("one formula")
                                                         : shape.size() == 2 ? "an array of " + std::to_string(shape[1]) +
                                                                                   " formulas, one per last index"
                                                                             : std::string("nothing: a family of three "
                                                                                           "indices takes no symmetry")) +
                                      ", got " + echo(formulas));
        }
        FormulaNode node = parse_component(formula, field);
        if (!shape.empty()) {  // the family's first index bound to this member's: sum(i = c..c, ξ)
          FormulaNode bound;
          bound.kind = FormulaNode::Kind::number;
          bound.text = std::to_string(m / (shape.size() == 2 ? shape[1] : 1) + 1);
          FormulaNode wrapped;
          wrapped.kind = FormulaNode::Kind::sum;
          wrapped.text = index;
          wrapped.operands = {bound, bound, std::move(node)};
          node = std::move(wrapped);
        }
        symmetry_texts.push_back(formula), symmetry_fields.push_back(field);
        definition->symmetry.push_back(std::move(node));
      }
      given.erase(name);
    }
    if (!given.empty())
      system.fail("symmetry", "'" + echo(given.begin()->first) + "' is not a coordinate or a coordinate family");
  } else if (system.has("symmetry")) {
    symmetry_texts = system.strings("symmetry");
    if (symmetry_texts.size() != n)
      system.fail("symmetry", "expected the generator ξ(q) as " + std::to_string(n) +
                                  " formulas, one per coordinate, got " + std::to_string(symmetry_texts.size()));
    for (std::size_t i = 0; i < n; ++i) {
      const std::string field = "symmetry[" + std::to_string(i) + "]";
      symmetry_fields.push_back(field);
      definition->symmetry.push_back(parse_component(symmetry_texts[i], field));
    }
  }
  // Each component of ξ alone, so that an error names its field: a scalar in the coordinates
  // and parameters (the velocities are unknown names there).
  for (std::size_t i = 0; i < symmetry_texts.size(); ++i) {
    try {
      if (formula_operations(definition->symmetry[i], maximum_formula_operations) > maximum_formula_operations)
        system.fail(symmetry_fields[i], "the formula expands to more than " +
                                            std::to_string(maximum_formula_operations) + " operations");
    } catch (const FormulaError& error) {
      system.fail(symmetry_fields[i], describe_formula_error(symmetry_texts[i], error));
    }
  }
  if (!symmetry_texts.empty()) {
    using V = TapeScalar<long double>;
    TapeRecording<long double> recording(static_cast<int>(n));
    FormulaScope<long double, V> scope;
    std::vector<V> inputs;
    for (std::size_t j = 0; j < n; ++j) inputs.push_back(recording.input(static_cast<int>(j)));
    bind_formula_names<long double, V>(scope, definition->coordinates, inputs, false);
    bind_formula_parameters<long double, V>(scope, *definition);
    for (std::size_t i = 0; i < symmetry_texts.size(); ++i) {
      // A generator that moves with the time is not one discrete-noether measures: say so, not
      // only that the time's name is unknown there.
      if (definition->time_dependent && formula_uses_name(definition->symmetry[i], definition->time_name))
        system.fail(symmetry_fields[i],
                    "the generator ξ(q) uses the time '" + definition->time_name +
                        "': discrete-noether measures a symmetry of L at every t whose generator does not move "
                        "with the time (a rotation of a charge in a field that pulses, docs/case-files.md \"Time\"); "
                        "its conserved quantity p·ξ(q) is then conserved to rounding by a variational integrator");
      try {
        if (interpret(definition->symmetry[i], scope).is_vector)
          throw FormulaError(0, "expected a number, got a vector");
      } catch (const FormulaError& error) {
        system.fail(symmetry_fields[i], describe_formula_error(symmetry_texts[i], error));
      }
    }
  }
  try {
    record_within_limits(*definition, system);
    const auto made = make_formula_system<long double, any_size>(*definition);
    definition->operations = made.program->nodes.size();
    // The acceleration's tape, for the memory estimate of a system of more than two coordinates
    // (check_memory); a singular mass matrix is refused with its reason by check_initial_state.
    if (n > 2) {
      try {
        definition->acceleration_operations = sparse_euler_lagrange_tape(*made.derivatives).nodes.size();
      } catch (const SingularLagrangianError&) {
      }
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

// d²L/dw² of `system` at (q, w) dense, or a CaseError naming `field` with its determinant.
template <class System, class V>
void check_regular_dense(const System& system, const V& q, const V& w, const std::string& field,
                         const std::string& file) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  using std::isfinite;
  const auto d = lagrangian_derivatives(system, q, w);
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

// d²L/dw² of `system` at (q, w), or a CaseError naming the field when it is singular there.
template <class System>
void check_regular(const System& system, const CaseSpec& spec, const std::string& file) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  const int n = spec.dimension;
  Vector<T, N> q(n), w(n);
  for (int i = 0; i < n; ++i) q[i] = from_decimal<T>(spec.q[i]), w[i] = from_decimal<T>(spec.w[i]);
  const std::string field = spec.formula ? "system.lagrangian" : "initial";
  if constexpr (SparselyDifferentiated<System>) {
    // Beyond two coordinates d²L/dw² sparse, factored sparse; no determinant, which over- or
    // underflows for many coordinates although the matrix is well conditioned. One or two
    // coordinates: dense, and the message gives the determinant.
    if (n <= 2) return check_regular_dense(system, q, w, field, file);
    try {
      (void)sparse_euler_lagrange_acceleration(system, q, w);
    } catch (const SingularLagrangianError& error) {
      const std::string what = error.what();
      if (what.find("not finite") != std::string::npos)
        throw CaseError(file, field, "L is not finite at the initial state: the state is outside the Lagrangian's domain");
      throw CaseError(file, field, "the Lagrangian is not regular at the initial state: d2L/dw2 is singular there (a "
                                   "pivot of its LU at most 1024 epsilon times the largest), so the Euler–Lagrange "
                                   "equations do not determine the acceleration");
    }
    return;
  }
  check_regular_dense(system, q, w, field, file);
}

}  // namespace

// The initial state in the formula's domain (sqrt, log, powers, quotients) and the Lagrangian
// regular there, checked in long double before any work, at the run-time size.
void check_initial_state(const CaseSpec& spec, const std::string& file) {
  using T = long double;
  std::vector<T> q, w;
  for (int i = 0; i < spec.dimension; ++i) q.push_back(from_decimal<T>(spec.q[i])), w.push_back(from_decimal<T>(spec.w[i]));
  const T t0 = from_decimal<T>(spec.start_time);
  if (spec.formula) {
    try {
      if (!spec.formula->recorded) check_formula_domain<T>(*spec.formula, q, w, t0);
    } catch (const FormulaError& error) {
      throw CaseError(file, "system.lagrangian", describe_formula_error(spec.formula->text, error));
    }
  }
  // A catalogue system through its formula twin, as it runs (harness/run/run_case.cpp).
  check_regular(at_time(make_formula_system<T, any_size>(spec.formula ? *spec.formula
                                                                      : catalogue_twin(spec.system, spec.parameters)),
                        t0),
                spec, file);
}

void check_memory(const CaseSpec& spec, const std::string& file, const std::string& scalar, int digits) {
  if (!spec.formula || spec.dimension <= 2) return;
  const MemoryEstimate estimate = estimate_memory(spec, scalar, digits);
  const MemoryLimit limit = memory_limit();
  const double needed = estimate.total();
  if (needed <= limit.bytes) return;
  // The largest part (the process itself comes first and is never the largest here), and what
  // the case could drop to fit, said with it.
  const MemoryPart& largest = *std::max_element(estimate.parts.begin(), estimate.parts.end(),
                                                [](const MemoryPart& a, const MemoryPart& b) { return a.bytes < b.bytes; });
  const double without = needed - largest.bytes;
  std::string instead;
  if (largest.name == "symplecticity's Jacobians") {
    instead = "; without symplecticity the case needs about " + in_bytes(without);
    const double per_step = largest.bytes / spec.steps.back();
    const double fitting = std::floor((limit.bytes - without) / per_step);
    if (fitting >= 1) instead += ", and with it step counts up to " + std::to_string(static_cast<long>(fitting)) + " fit";
  } else if (largest.name == "dense second derivatives") {
    instead = "; only the Galerkin and TQ discretizations need them: a Q x Q rule or a map on the same L needs about " +
              in_bytes(without);
  } else if (largest.name == "sweep") {
    instead = "; fewer or shorter runs in \"steps\" would fit: without the sweep the case needs about " + in_bytes(without);
  } else {
    instead = "; a system of fewer coordinates, an L of fewer operations";
    if (largest.name == "reference flow") instead += " or a scalar of fewer digits";
    instead += " is what would fit";
  }
  throw CaseError(file, "system.coordinates",
                  "a system of " + std::to_string(spec.dimension) + " coordinates whose L takes " +
                      std::to_string(spec.formula->operations) + " operations needs about " + in_bytes(needed) +
                      " in " + scalar + ", " + in_bytes(largest.bytes) + " of it for " + largest.name +
                      " (" + largest.what + "), more than the " + in_bytes(limit.bytes) + " this process may take (" +
                      limit.what + ")" + instead);
}

}  // namespace vivv::case_reading
