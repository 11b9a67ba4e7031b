// A Q×Q discrete Lagrangian written as a formula in a case file (docs/case-files.md):
//
//   "discretization": {"kind": "expression", "L_d": "h*L((qb + qe)/2, (qe - qb)/h)", "order": 2}
//
// qb and qe are the begin and end configurations (vectors of the system's
// dimension, components qb[1] … qb[n]), h the step, L(x, v) the system's own
// Lagrangian and its parameters are there by name. The formula is recorded
// once in T over (qb, qe, h), with L inlined from the system, and
// discrete_lagrangian runs it in any scalar; p_begin and p_end then come from
// automatic differentiation, as for the built-in rules.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/qxq/discrete_lagrangian.hpp"
#include "core/formulas/formula.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/formulas/recorded.hpp"
#include "core/autodiff/tape.hpp"

namespace vivv {

// L_d(qb, qe; h) of `tree` recorded in T over the inputs (qb_1 … qb_n, qe_1 … qe_n, h) and, for a
// system whose L depends on time, the segment's start time t_b after them (named `time_name` in the
// formula, which then calls L(x, v, s) with a time s of its own, such as t + h/2). Throws
// FormulaError for a formula without meaning.
template <LagrangianSystem System>
std::shared_ptr<const Tape<typename System::Scalar>> record_discrete_lagrangian(
    const System& system, const FormulaNode& tree, const std::vector<std::pair<std::string, std::string>>& parameters,
    const std::string& time_name = "t") {
  using T = typename System::Scalar;
  using V = TapeScalar<T>;
  constexpr int N = System::dimension;
  const int n = dimension_of(system);
  const bool timed = depends_on_time(system);
  TapeRecording<T> recording(2 * n + (timed ? 2 : 1));
  FormulaScope<T, V> scope;
  FormulaValue<V> qb{{}, true, false, {}}, qe{{}, true, false, {}};
  for (int i = 0; i < n; ++i)
    qb.components.push_back(recording.input(i)), qe.components.push_back(recording.input(n + i));
  scope.names["qb"] = std::move(qb);
  scope.names["qe"] = std::move(qe);
  scope.names["h"] = FormulaValue<V>::scalar(recording.input(2 * n), false);
  // An L that depends on time: the segment's start time t_b, input 2n + 1, under the time's name.
  if (timed) scope.names[time_name] = FormulaValue<V>::scalar(recording.input(2 * n + 1), false);
  scope.lagrangian_takes_time = timed;
  {
    std::vector<std::string> names;
    std::vector<V> values;
    for (const auto& [name, value] : parameters) names.push_back(name), values.push_back(V(from_decimal<T>(value)));
    bind_formula_names<T, V>(scope, names, values, true);
  }
  scope.dimension = n;
  scope.lagrangian = [&system, n](const std::vector<V>& x, const std::vector<V>& v, const V& time) {
    Coordinates<V, N> point = make_point<V, N>(n), velocity = make_point<V, N>(n);
    for (int i = 0; i < n; ++i) point[i] = x[i], velocity[i] = v[i];
    if constexpr (CarriesTime<System>) {
      if (depends_on_time(system)) return V(system.lagrangian_at(time, point, velocity));
    }
    return V(system.lagrangian(point, velocity));
  };
  const FormulaValue<V> value = interpret(tree, scope);
  if (value.is_vector) throw FormulaError(tree.position, "expected L_d to be a scalar, got a vector");
  return std::make_shared<const Tape<T>>(recording.finish({value.components[0]}));
}

// L_d(qb, qe; h) of C++ code registered for it (core/formulas/recorded.hpp), recorded in T over the
// inputs (qb_1 … qb_n, qe_1 … qe_n, h) with the system's L inlined.
template <LagrangianSystem System>
std::shared_ptr<const Tape<typename System::Scalar>> record_discrete_lagrangian(
    const System& system, const PerScalar<DiscreteLagrangianRecorder>& recorder) {
  using T = typename System::Scalar;
  using V = TapeScalar<T>;
  constexpr int N = System::dimension;
  const int n = dimension_of(system);
  if (depends_on_time(system))
    throw std::invalid_argument("an L_d registered as C++ code for an L that uses t is not supported: its L(x, v) "
                                "would hold t fixed");
  TapeRecording<T> recording(2 * n + 1);
  std::vector<V> qb, qe;
  for (int i = 0; i < n; ++i) qb.push_back(recording.input(i)), qe.push_back(recording.input(n + i));
  auto lagrangian = [&system, n](const std::vector<V>& x, const std::vector<V>& v) {
    Coordinates<V, N> point = make_point<V, N>(n), velocity = make_point<V, N>(n);
    for (int i = 0; i < n; ++i) point[i] = x[i], velocity[i] = v[i];
    return V(system.lagrangian(point, velocity));
  };
  const V value = recorder.template get<T>()(qb, qe, recording.input(2 * n), lagrangian);
  return std::make_shared<const Tape<T>>(recording.finish({value}));
}

// The expression discretization of `text` (its tree `tree`) for `system`, claiming `order`.
template <LagrangianSystem System>
QxQDiscretization<typename System::Scalar> expression_discretization(
    const System& system, const std::string& text, const FormulaNode& tree,
    const std::vector<std::pair<std::string, std::string>>& parameters, int order, const std::string& time_name = "t") {
  QxQDiscretization<typename System::Scalar> d;
  d.rule = QxQRule::expression;
  d.expression = record_discrete_lagrangian(system, tree, parameters, time_name);
  if constexpr (System::dimension == any_size)
    d.expression_derivatives = std::make_shared<const SecondDerivativeTape<typename System::Scalar>>(*d.expression);
  d.formula = text;
  d.declared_order = order;
  return d;
}

// The discretization of an L_d registered as C++ code, claiming `order`.
template <LagrangianSystem System>
QxQDiscretization<typename System::Scalar> recorded_discretization(
    const System& system, const std::string& text, const PerScalar<DiscreteLagrangianRecorder>& recorder, int order) {
  QxQDiscretization<typename System::Scalar> d;
  d.rule = QxQRule::expression;
  d.expression = record_discrete_lagrangian(system, recorder);
  if constexpr (System::dimension == any_size)
    d.expression_derivatives = std::make_shared<const SecondDerivativeTape<typename System::Scalar>>(*d.expression);
  d.formula = text;
  d.declared_order = order;
  return d;
}

}  // namespace vivv
