// A Lagrangian system written as a formula in a case file (docs/case-files.md):
//
//   "system": {"name": "henon-heiles", "lagrangian": "(vx^2 + vy^2)/2 - ...",
//              "coordinates": ["x", "y"], "velocities": ["vx", "vy"], "params": {...}}
//
// The formula's tree is recorded once in T as a straight-line program over
// (q_1 … q_n, w_1 … w_n) (core/autodiff/tape.hpp; parameters and pi become constants
// in T), and L(q, w) runs that program in whatever scalar S core/ asks for:
// T, jets, the Taylor tape, power series. So a formula system is a
// LagrangianSystem like any in the catalogue.
#pragma once

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/formulas/formula.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "core/formulas/recorded.hpp"
#include "core/autodiff/sparse_hessian.hpp"
#include "core/autodiff/tape.hpp"

namespace vivv {

// The names a system formula is written in; parameter values are decimals, parsed in T.
struct FormulaSystemDefinition {
  std::string name;
  std::string text;  // the formula as written
  FormulaNode lagrangian;
  std::vector<std::string> coordinates, velocities;
  std::vector<std::pair<std::string, std::string>> parameters;
  // The generator ξ(q) of a symmetry of L, a formula per coordinate in the
  // coordinates and parameters (core/structure/noether.hpp); empty: none declared.
  std::vector<FormulaNode> symmetry;
  // A system registered as C++ code (core/formulas/recorded.hpp): L is recorded from it, not from
  // `lagrangian`, which is then empty.
  std::shared_ptr<const PerScalar<SystemRecorder>> recorded;
  // The operations of L's recorded tape, counted when the case was read (0: not yet recorded).
  std::size_t operations = 0;
  // The nodes of the Euler–Lagrange acceleration's tape (the Taylor reference flow's, from L's
  // sparse derivatives), counted when the case was read for the memory estimate (0: not counted:
  // one or two coordinates, or an L whose mass matrix is singular, which the reading refuses).
  std::size_t acceleration_operations = 0;
  // L uses the time (named `time_name` in its formula, "t" unless a coordinate, velocity or parameter
  // takes that name): its tapes take the time as one more input, after (q, w).
  bool time_dependent = false;
  std::string time_name = "t";
};

// n: the number of coordinates, fixed (1, 2) or any_size (then the definition's, at run time).
template <class T, int n>
struct FormulaSystem {
  using Scalar = T;
  static constexpr int dimension = n;
  std::shared_ptr<const Tape<T>> program;  // inputs q_1 … q_n, w_1 … w_n (and t, timed); one output, L
  // Sized at run time: L's gradient and sparse Hessian, recorded from `program` by edge pushing
  // (core/autodiff/sparse_hessian.hpp), which the Q × Q rules and the DEL step use instead of
  // dense jets (core/qxq/sparse_legendre.hpp). Null at the fixed sizes 1 and 2.
  std::shared_ptr<const SecondDerivativeTape<T>> derivatives;
  int coordinates = n;
  // An L that uses t (its tapes' input 2n), evaluated at `time` (core/lagrangian/lagrangian.hpp: at_time).
  bool timed = false;
  T time = T(0);

  int size() const { return coordinates; }

  // L(q, w) at the system's time: the recorded program run in S.
  template <class P>
  auto lagrangian(const P& q, const P& w) const {
    return lagrangian_at(time, q, w);
  }

  // L(q, w) at time t (which an L that does not use t ignores). t is a constant of S — jets over
  // (q, w) do not differentiate in it — or, on a tape recording an L_d expression, its time.
  template <class P, class U>
  auto lagrangian_at(const U& t, const P& q, const P& w) const {
    using S = typename P::value_type;
    count_lagrangian_evaluation();
    Coordinates<S, plus(twice(n), 1)> x = make_point<S, plus(twice(n), 1)>(2 * coordinates + (timed ? 1 : 0));
    for (int i = 0; i < coordinates; ++i) x[i] = q[i], x[coordinates + i] = w[i];
    if (timed) x[2 * coordinates] = S(t);
    return S(program->evaluate_first(x.data()));
  }

  std::shared_ptr<const Tape<T>> symmetry;  // inputs q_1 … q_n; outputs ξ_1 … ξ_n; null: none declared
  bool has_symmetry() const { return symmetry != nullptr; }
  Coordinates<T, n> symmetry_generator(const Coordinates<T, n>& q) const {
    const std::vector<T> xi = symmetry->evaluate(std::vector<T>(q.begin(), q.end()));
    Coordinates<T, n> generator = make_point<T, n>(coordinates);
    for (int i = 0; i < coordinates; ++i) generator[i] = xi[i];
    return generator;
  }
};

// Binds `names` to `values` in `scope`: a plain name to its value, a member of an indexed family
// ("x[2,3]", as the case reader names them, every member of a family present, row-major) to its
// place in the family x, whose shape is the largest index in each position.
template <class T, class V>
void bind_formula_names(FormulaScope<T, V>& scope, const std::vector<std::string>& names, const std::vector<V>& values,
                        bool constant) {
  struct Member {
    std::vector<int> indices;
    const V* value;
  };
  std::map<std::string, std::vector<Member>> families;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    const auto open = name.find('[');
    if (open == std::string::npos) {
      scope.names[name] = FormulaValue<V>::scalar(values[i], constant);
      continue;
    }
    Member member{{}, &values[i]};
    std::string index;
    for (std::size_t k = open + 1; k < name.size(); ++k) {
      if (name[k] == ',' || name[k] == ']') member.indices.push_back(std::stoi(index)), index.clear();
      else index += name[k];
    }
    families[name.substr(0, open)].push_back(std::move(member));
  }
  for (auto& [name, members] : families) {
    FormulaValue<V> family;
    family.is_vector = true;
    family.is_constant = constant;
    family.shape.assign(members.front().indices.size(), 0);
    for (const Member& member : members)
      for (std::size_t k = 0; k < family.shape.size(); ++k) family.shape[k] = std::max(family.shape[k], member.indices[k]);
    std::size_t size = 1;
    for (int extent : family.shape) size *= static_cast<std::size_t>(extent);
    family.components.assign(size, V(0));
    for (const Member& member : members) {
      std::size_t offset = 0;
      for (std::size_t k = 0; k < family.shape.size(); ++k)
        offset = offset * static_cast<std::size_t>(family.shape[k]) + static_cast<std::size_t>(member.indices[k] - 1);
      family.components[offset] = *member.value;
    }
    scope.names[name] = std::move(family);
  }
}

// The parameters of `definition` in V (constants in T), bound in `scope`.
template <class T, class V>
void bind_formula_parameters(FormulaScope<T, V>& scope, const FormulaSystemDefinition& definition) {
  std::vector<std::string> names;
  std::vector<V> values;
  for (const auto& [name, value] : definition.parameters) names.push_back(name), values.push_back(V(from_decimal<T>(value)));
  bind_formula_names<T, V>(scope, names, values, true);
}

// The scope of a system formula in V: coordinates and velocities from `q`, `w`, parameters in T,
// and t from `time` for an L that uses it.
template <class T, class V>
FormulaScope<T, V> system_formula_scope(const FormulaSystemDefinition& definition, const std::vector<V>& q,
                                        const std::vector<V>& w, const V& time = V(0)) {
  FormulaScope<T, V> scope;
  bind_formula_names<T, V>(scope, definition.coordinates, q, false);
  bind_formula_names<T, V>(scope, definition.velocities, w, false);
  bind_formula_parameters<T, V>(scope, definition);
  if (definition.time_dependent) scope.names[definition.time_name] = FormulaValue<V>::scalar(time, false);
  return scope;
}

// L of `definition` (n coordinates) recorded in T: its tape alone, inputs q_1 … q_n, w_1 … w_n
// and, for an L that uses t, t. Throws FormulaError for a formula that has no meaning (unknown
// names, vectors, non-constant exponents), TapeCeilingReached past a TapeCeiling.
template <class T>
Tape<T> record_lagrangian(const FormulaSystemDefinition& definition, int n) {
  TapeRecording<T> recording(2 * n + (definition.time_dependent ? 1 : 0));
  std::vector<TapeScalar<T>> q, w;
  for (int i = 0; i < n; ++i) q.push_back(recording.input(i)), w.push_back(recording.input(n + i));
  if (definition.recorded)
    return recording.finish({definition.recorded->template get<T>()(q, w, definition.parameters)});
  const auto scope = definition.time_dependent ? system_formula_scope<T>(definition, q, w, recording.input(2 * n))
                                               : system_formula_scope<T>(definition, q, w);
  return recording.finish({interpret(definition.lagrangian, scope).components[0]});
}

// Records the formula of `definition` (dimension n) in T. Throws FormulaError for
// a formula that has no meaning (unknown names, vectors, non-constant exponents).
template <class T, int N>
FormulaSystem<T, N> make_formula_system(const FormulaSystemDefinition& definition) {
  const int n = N == any_size ? static_cast<int>(definition.coordinates.size()) : N;
  FormulaSystem<T, N> system;
  system.coordinates = n;
  system.timed = definition.time_dependent;
  system.program = std::make_shared<const Tape<T>>(record_lagrangian<T>(definition, n));
  if constexpr (N == any_size) system.derivatives = std::make_shared<const SecondDerivativeTape<T>>(*system.program);
  if (definition.recorded) return system;
  if (!definition.symmetry.empty()) {
    TapeRecording<T> generator(n);
    std::vector<TapeScalar<T>> x;
    for (int i = 0; i < n; ++i) x.push_back(generator.input(i));
    FormulaScope<T, TapeScalar<T>> coordinates;  // the coordinates and parameters, no velocities
    bind_formula_names<T, TapeScalar<T>>(coordinates, definition.coordinates, x, false);
    bind_formula_parameters<T, TapeScalar<T>>(coordinates, definition);
    std::vector<TapeScalar<T>> components;
    for (const FormulaNode& component : definition.symmetry) {
      const FormulaValue<TapeScalar<T>> xi = interpret(component, coordinates);
      if (xi.components.size() != 1) throw FormulaError(0, "a component of the symmetry must be a number");
      components.push_back(xi.components[0]);
    }
    system.symmetry = std::make_shared<const Tape<T>>(generator.finish(components));
  }
  return system;
}

// L at (q, w) evaluated from the tree in T, naming the first sqrt, log, power or
// quotient whose argument is outside its domain there (FormulaError).
template <class T>
T check_formula_domain(const FormulaSystemDefinition& definition, const std::vector<T>& q, const std::vector<T>& w,
                       const T& time = T(0)) {
  return interpret(definition.lagrangian, system_formula_scope<T>(definition, q, w, time)).components[0];
}

}  // namespace vivv
