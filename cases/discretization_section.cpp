#include <algorithm>
#include <memory>

#include "cases/case_sections.hpp"
#include "cases/catalogue.hpp"
#include "cases/formula_parser.hpp"
#include "core/maps/odeint_map.hpp"
#include "core/maps/user_map.hpp"
#include "core/qxq/discrete_lagrangian.hpp"

namespace vivv::case_reading {

namespace {

// What a discrete Lagrangian formula means, checked by recording it in long double: qb and qe
// are vectors of `dimension` components, h a scalar, the parameters constants, and L(x, v)
// stands for the system's Lagrangian; for one that depends on time, `time_name` is the segment's
// start time and L(x, v, s) takes a time.
void check_expression(const FormulaNode& tree, int dimension,
                      const std::vector<std::pair<std::string, std::string>>& parameters, const std::string& time_name) {
  using T = long double;
  using V = TapeScalar<T>;
  TapeRecording<T> recording(2 * dimension + 2);
  FormulaScope<T, V> scope;
  FormulaValue<V> qb{{}, true, false, {}}, qe{{}, true, false, {}};
  for (int i = 0; i < dimension; ++i)
    qb.components.push_back(recording.input(i)), qe.components.push_back(recording.input(dimension + i));
  scope.names["qb"] = qb;
  scope.names["qe"] = qe;
  scope.names["h"] = FormulaValue<V>::scalar(recording.input(2 * dimension), false);
  if (!time_name.empty()) scope.names[time_name] = FormulaValue<V>::scalar(recording.input(2 * dimension + 1), false);
  scope.lagrangian_takes_time = !time_name.empty();
  // As the run binds them (core/formulas/formula_discretization.hpp): a parameter array's members
  // m[1], m[2], … as the family m.
  std::vector<std::string> names;
  std::vector<V> values;
  for (const auto& [name, value] : parameters) names.push_back(name), values.push_back(V(from_decimal<T>(value)));
  bind_formula_names<T, V>(scope, names, values, true);
  scope.dimension = dimension;
  scope.lagrangian = [](const std::vector<V>& x, const std::vector<V>& v, const V& time) {
    V sum = time;
    for (std::size_t i = 0; i < x.size(); ++i) sum = sum + x[i] * v[i];
    return sum;
  };
  const FormulaValue<V> value = interpret(tree, scope);
  if (value.is_vector) throw FormulaError(tree.position, "expected L_d to be a scalar, got a vector");
}

}  // namespace

DiscretizationSpec read_discretization(Reader reader, int dimension,
                                       const std::vector<std::pair<std::string, std::string>>& parameters,
                                       bool allow_tq, const std::string& time_name) {
  DiscretizationSpec spec;
  if (reader.has("kind") && reader.get("kind") == "process") {
    // A one-step map in another program (protocol vivv-map/1): its command and declared order.
    spec.kind = "process";
    if (!allow_tq)
      reader.fail("kind", "a one-step map cannot be pulled back as a Q×Q discrete Lagrangian");
    if (reader.has("formalism"))
      reader.fail("formalism",
                  "a one-step map (kind \"process\") is neither a Q×Q nor a TQ discretization: "
                  "leave formalism out");
    spec.formalism = "map";
    const auto& command = reader.get("command");
    if (!command.is_array() || command.empty() || command.size() > 64)
      reader.fail(
          "command",
          "expected the program and its arguments as an array of 1 to 64 strings, such as "
          "[\"python3\", \"step.py\"] (run without a shell, in the case file's folder), got " +
              echo(command));
    for (std::size_t i = 0; i < command.size(); ++i) {
      const std::string where = "command[" + std::to_string(i) + "]";
      if (!command[i].is_string()) reader.fail(where, "expected a string, got " + echo(command[i]));
      const std::string word = command[i].get<std::string>();
      if ((i == 0 && word.empty()) || word.size() > 4096 || word.find('\0') != std::string::npos)
        reader.fail(
            where,
            i == 0 ? "expected the program to start: a name on PATH or a path relative to the case "
                     "file's folder, at most 4096 characters without NUL"
                   : "expected an argument of at most 4096 characters without NUL");
      spec.command.push_back(word);
    }
    if (reader.has("precision")) spec.process_precision = reader.one_of("precision", {"double"});
    spec.declared_order =
        reader.integer("order", 1, 64,
                       "the order its author states, |Phi_h - F_h| = O(h^(order+1)), "
                       "which global-order checks");
    if (reader.has("twin"))
      reader.fail("twin", "a one-step map has no discrete Lagrangian to add a twin term to");
    reader.finish();
    return spec;
  }
  if (reader.has("kind") && (reader.get("kind") == "odeint" || reader.get("kind") == "map")) {
    // A one-step map of another library (odeint's, or one a program linking vivv registered):
    // no formalism, no twin term, nothing but its name.
    spec.kind = reader.get("kind").get<std::string>();
    if (!allow_tq) reader.fail("kind", "a one-step map cannot be pulled back as a Q×Q discrete Lagrangian");
    if (reader.has("formalism"))
      reader.fail("formalism", "a one-step map (kind \"" + spec.kind + "\") is neither a Q×Q nor a TQ "
                               "discretization: leave formalism out");
    spec.formalism = "map";
    std::vector<std::string> names;
    if (spec.kind == "odeint") {
      for (const auto& stepper : odeint_steppers()) names.push_back(stepper.name);
      spec.stepper = reader.one_of("stepper", names);
    } else {
      for (const auto& map : registered_maps()) names.push_back(map.name);
      if (names.empty())
        reader.fail("kind", "\"map\" puts a method that a program linking vivv registered (vivv::register_map) "
                            "under test, and this program registered none; the vivv tool has odeint's steppers "
                            "(\"kind\": \"odeint\")");
      spec.stepper = reader.one_of("name", names);
    }
    if (reader.has("twin")) reader.fail("twin", "a one-step map has no discrete Lagrangian to add a twin term to");
    reader.finish();
    return spec;
  }
  if (reader.has("formalism"))
    spec.formalism = reader.one_of("formalism", allow_tq ? std::vector<std::string>{"qxq", "tq"}
                                                         : std::vector<std::string>{"qxq"});
  if (spec.formalism == "tq") {
    TQSpec tq;
    tq.psi = reader.one_of("psi", {"linear", "taylor", "exact"});
    if (tq.psi == "taylor")
      tq.r =
          reader.integer("r", 1, 8, "the degree of the Taylor psi; vivv expands it up to degree 8");
    if (tq.psi != "taylor" && reader.has("r"))
      reader.fail("r", "a degree r is taken only by psi \"taylor\", not \"" + tq.psi + "\"");
    tq.theta = reader.fraction("theta");
    tq.lagrangian = reader.one_of("lagrangian", {"quadrature", "pullback", "exact"});
    if (tq.lagrangian == "exact" && tq.psi != "exact")
      reader.fail("lagrangian", "\"exact\" is the action along the exact psi: needs psi \"exact\", not \"" +
                                    tq.psi + "\"");
    if (tq.lagrangian == "quadrature")
      tq.nodes = reader.integer("nodes", 1, 64,
                                "the Gauss nodes of the quadrature of L along psi; at most 64");
    if (tq.lagrangian == "pullback") {
      tq.qxq = std::make_shared<DiscretizationSpec>(
          read_discretization(reader.object("qxq"), dimension, parameters, false, time_name));
      if (tq.qxq->kind == "galerkin")
        reader.fail("qxq", "a Galerkin L_d is extremized by Newton in the working precision and cannot be pulled "
                           "back through psi's derivatives; use it on Q × Q");
    }
    spec.tq = tq;
  } else if (reader.has("kind") && reader.get("kind") == "user") {
    // L_d registered as C++ code by a program linking vivv: run as an "expression" L_d.
    std::vector<std::string> names;
    for (const auto& rule : registered_discrete_lagrangians()) names.push_back(rule.name);
    if (names.empty())
      reader.fail("kind", "\"user\" puts a discrete Lagrangian that a program linking vivv registered "
                          "(vivv::register_discrete_lagrangian) under test, and this program registered none; "
                          "write L_d as a formula instead (\"kind\": \"expression\")");
    const std::string name = reader.one_of("name", names);
    for (const auto& rule : registered_discrete_lagrangians())
      if (rule.name == name) spec.recorded = rule.recorder, spec.declared_order = rule.order;
    spec.kind = "expression";
    spec.expression = "registered C++ discrete Lagrangian '" + name + "'";
  } else {
    spec.kind = reader.one_of("kind", rule_names());
    QxQRule rule = *rule_from_name(spec.kind);
    if (rule == QxQRule::alpha) spec.parameter = reader.decimal("alpha");
    if (rule == QxQRule::weighted) spec.parameter = reader.decimal("beta");
    if (rule == QxQRule::galerkin) {
      spec.galerkin_degree = reader.integer(
          "degree", 1, 8, "the degree of the Galerkin curve; vivv builds curves up to degree 8");
      spec.galerkin_quadrature = reader.one_of("quadrature", {"gauss", "lobatto"});
      // Fewer nodes than the degree leave the interior values too loosely tied to L (degree 3 with 2
      // Gauss nodes measures order 2, not min(2s, 2m) = 4): vivv has no prediction there.
      spec.galerkin_nodes = reader.integer(
          "nodes", std::max(spec.galerkin_degree, spec.galerkin_quadrature == "lobatto" ? 2 : 1),
          16,
          "fewer nodes than the degree leave the curve's interior values too loosely tied to L "
          "(degree 3 with 2 Gauss nodes measures order 2, not 4), so vivv has no prediction there "
          "(and Lobatto needs 2 nodes, its end points); at most 16 nodes");
    }
    if (rule == QxQRule::expression) {
      spec.expression_tree = read_formula(reader, "L_d", spec.expression);
      try {
        check_expression(*spec.expression_tree, dimension, parameters, time_name);
      } catch (const FormulaError& error) {
        reader.fail("L_d", describe_formula_error(spec.expression, error));
      }
      spec.declared_order =
          reader.integer("order", 1, 64, "the order the rule declares, which its claims check");
    }
  }
  if (reader.has("twin")) {
    Reader twin = reader.object("twin");
    spec.twin = TwinSpec{
        twin.decimals("a", dimension),
        twin.integer("power", 1, 16, "the power s of h in the twin term h^s·a·w; at most 16")};
    twin.finish();
  }
  reader.finish();
  return spec;
}

}  // namespace vivv::case_reading
