// Formulas written in case files — a Lagrangian L(q, w) or a discrete
// Lagrangian L_d(qb, qe; h) — as a syntax tree, and what a tree means in a
// scalar (docs/case-files.md, "Formulas").
//
// cases/formula_parser.cpp turns text into a FormulaNode tree; `interpret`
// gives a tree its value in any V that has the scalar's arithmetic: in T it
// evaluates (and checks the domain of sqrt, log, powers and quotients at that
// point), in TapeScalar<T> it records the straight-line program
// (core/autodiff/tape.hpp) that every other scalar S then runs — plain values, jets,
// the Taylor tape, power series. Decimal literals are parsed in T directly,
// never through a double.
#pragma once

#include <boost/math/constants/constants.hpp>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/numerics/scalar.hpp"
#include "core/autodiff/tape.hpp"

namespace vivv {

// A formula that cannot mean anything: what was expected at which character (0-based).
struct FormulaError : std::runtime_error {
  FormulaError(int position, const std::string& message) : std::runtime_error(message), position(position) {}
  int position;
};

// One node of a formula's syntax tree.
// component: `name[i, j, …]`, its operands the index expressions (integers, bound indices, + − *);
// sum: `sum(i = a..b, body)`, its text the index, its operands a, b and the body.
struct FormulaNode {
  enum class Kind { number, name, negate, add, subtract, multiply, divide, power, call, component, sum };
  Kind kind = Kind::number;
  std::string text;  // the literal (number), the name (name, component), the function (call), the index (sum)
  int position = 0;  // offset of the node's first character in the formula
  std::vector<FormulaNode> operands;
};

// Whether `node` refers to `name` (a name, not a function, a family's member or a sum's index).
inline bool formula_uses_name(const FormulaNode& node, const std::string& name) {
  if (node.kind == FormulaNode::Kind::name && node.text == name) return true;
  for (const FormulaNode& operand : node.operands)
    if (formula_uses_name(operand, name)) return true;
  return false;
}

// The value of a formula or of a part of it: a scalar, or a vector such as qb.
// An indexed family — x[i, k] of N bodies in d dimensions, masses m[i] — is a vector whose shape
// has as many entries as it takes indices, its components row-major.
template <class V>
struct FormulaValue {
  std::vector<V> components;  // one entry for a scalar
  bool is_vector = false;
  bool is_constant = false;  // depends on no coordinate, velocity, qb, qe or h
  std::vector<int> shape;     // a vector's extent per index: {n} for qb, {N, d} for x[i, k]
  static FormulaValue scalar(V value, bool constant) { return {{std::move(value)}, false, constant, {}}; }
};

// What a formula's names and L(x, v) mean, in V over the scalar T.
template <class T, class V>
struct FormulaScope {
  std::map<std::string, FormulaValue<V>> names;
  // L(x, v), for discrete Lagrangians; empty where a formula may not call it. For a system whose L
  // depends on time (`lagrangian_takes_time`) a formula writes L(x, v, s), s the time; otherwise
  // the time passed is 0 and ignored.
  std::function<V(const std::vector<V>&, const std::vector<V>&, const V&)> lagrangian;
  bool lagrangian_takes_time = false;
  int dimension = 0;  // length of L's arguments
  // The indices the enclosing sums bind, by name (a sum binds its index while it interprets its body).
  mutable std::map<std::string, long> indices;
  mutable long terms = 0;  // the terms every sum has expanded so far (maximum_formula_terms)
};

// The largest number of terms a formula's sums may expand to, all sums together: a bound on the
// work of reading it (a chain of 10⁵ particles is 10⁵ terms per sum).
inline constexpr long maximum_formula_terms = 10000000;

// Functions a formula may call, each of one argument (L(x, v) aside).
inline const std::vector<std::string>& formula_functions() {
  static const std::vector<std::string> names = {"sqrt", "exp", "log",  "sin",  "cos",
                                                 "tan",  "sinh", "cosh", "tanh", "atan"};
  return names;
}

// Names a formula cannot give to a coordinate, velocity or parameter.
inline bool is_reserved_formula_name(const std::string& name) {
  for (const auto& f : formula_functions())
    if (f == name) return true;
  return name == "pi" || name == "L" || name == "sum";
}

namespace formula_detail {

template <class V>
struct is_tape_scalar : std::false_type {};
template <class T>
struct is_tape_scalar<TapeScalar<T>> : std::true_type {};

// The T value of a constant V.
template <class T, class V>
T constant_value(const V& x) {
  if constexpr (is_tape_scalar<V>::value) return x.value();
  else return x;
}

// In T, `f(x)` is evaluated where it is defined and named where it is not.
template <class T, class V>
void check_domain(const std::string& function, const V& x, int position) {
  if constexpr (!is_tape_scalar<V>::value) {
    using std::isfinite;
    const bool bad = ((function == "sqrt" || function == "power") && x < 0) || (function == "log" && !(x > 0)) ||
                     (function == "divide" && x == 0) || !isfinite(x);
    if (!bad) return;
    const std::string what = function == "power" ? "a non-integer power of" : function == "divide" ? "a division by" : function + " of";
    std::ostringstream value;  // six digits say where the state is; the case file has the rest
    value.precision(6);
    value << x;
    throw FormulaError(position, what + " " + value.str() + " at the initial state: the state is outside the "
                                        "formula's domain");
  }
}

// x^k for an integer k, by repeated squaring (no pow, whose Taylor recurrence divides by x).
template <class V>
V integer_power(const V& x, long k) {
  if (k < 0) return V(1) / integer_power(x, -k);
  V result(1), square = x;
  bool first = true;
  for (; k > 0; k >>= 1) {
    if (k & 1) result = first ? square : result * square, first = false;
    if (k > 1) square = square * square;
  }
  return result;
}

template <class T, class V>
V apply_function(const std::string& f, const V& x, int position) {
  using std::atan, std::cos, std::exp, std::log, std::sin, std::sqrt;
  check_domain<T>(f, x, position);
  if (f == "sqrt") return sqrt(x);
  if (f == "exp") return exp(x);
  if (f == "log") return log(x);
  if (f == "sin") return sin(x);
  if (f == "cos") return cos(x);
  if (f == "tan") return sin(x) / cos(x);
  // sinh, cosh, tanh through one exponential; atan has a tape operation of its own.
  if (f == "sinh") { const V e = exp(x); return (e - 1 / e) / 2; }
  if (f == "cosh") { const V e = exp(x); return (e + 1 / e) / 2; }
  if (f == "tanh") return 1 - 2 / (exp(2 * x) + 1);
  if (f == "atan") return atan(x);
  throw FormulaError(position, "unknown function '" + f + "'");
}

}  // namespace formula_detail

// The integer an index expression stands for: integers, the indices enclosing sums bind, and
// + − * of them. FormulaError at the first part that is none of these, and at every operation whose
// exact result lies beyond ±2^40: checked before it can wrap (2^32 · 2^32 + 1 is not 1).
template <class T, class V>
long index_value(const FormulaNode& node, const FormulaScope<T, V>& scope) {
  using Kind = FormulaNode::Kind;
  constexpr long bound = 1L << 40;  // far beyond any family
  const auto checked = [&](bool overflowed, long value) {
    if (overflowed || value > bound || value < -bound)
      throw FormulaError(node.position, "an index or sum bound beyond ±2^40 (1099511627776)");
    return value;
  };
  const auto operands = [&] {
    return std::pair{index_value(node.operands[0], scope), index_value(node.operands[1], scope)};
  };
  long result = 0;
  switch (node.kind) {
    case Kind::number: {
      const bool integer = !node.text.empty() && node.text.size() <= 13 &&
                           node.text.find_first_not_of("0123456789") == std::string::npos;
      if (!integer) {
        if (!node.text.empty() && node.text.find_first_not_of("0123456789") == std::string::npos)
          checked(true, 0);  // an integer of more digits than any index within ±2^40
        throw FormulaError(node.position, "expected an integer index, got " + node.text);
      }
      return checked(false, std::stol(node.text));
    }
    case Kind::name: {
      const auto found = scope.indices.find(node.text);
      if (found == scope.indices.end()) {
        std::string bound_names;
        for (const auto& [name, value] : scope.indices) bound_names += (bound_names.empty() ? "" : ", ") + name;
        throw FormulaError(node.position, "'" + node.text + "' is not an index here; an index is an integer or a name "
                                              "a sum binds (" + (bound_names.empty() ? std::string("no sum encloses this") :
                                                                 "bound here: " + bound_names) + ")");
      }
      return found->second;
    }
    case Kind::negate: return checked(false, -index_value(node.operands[0], scope));
    case Kind::add: {
      const auto [a, b] = operands();
      const bool overflowed = __builtin_add_overflow(a, b, &result);  // before `result` is read
      return checked(overflowed, result);
    }
    case Kind::subtract: {
      const auto [a, b] = operands();
      const bool overflowed = __builtin_sub_overflow(a, b, &result);  // before `result` is read
      return checked(overflowed, result);
    }
    case Kind::multiply: {
      const auto [a, b] = operands();
      const bool overflowed = __builtin_mul_overflow(a, b, &result);  // before `result` is read
      return checked(overflowed, result);
    }
    default:
      throw FormulaError(node.position, "expected an index: integers, summation indices and + - * of them");
  }
}

// The value of `node` in V with the names and L of `scope`. Throws FormulaError
// at the offending node: an unknown name or function, a vector where a scalar
// is expected (or the reverse), a non-constant exponent and, in T, a point
// outside the domain.
template <class T, class V>
FormulaValue<V> interpret(const FormulaNode& node, const FormulaScope<T, V>& scope) {
  using Kind = FormulaNode::Kind;
  using Value = FormulaValue<V>;
  auto scalar_of = [&](const FormulaNode& operand, const char* role) {
    Value value = interpret(operand, scope);
    if (value.is_vector)
      throw FormulaError(operand.position, std::string("expected a scalar ") + role +
                                               ", got a vector (write a component such as qb[1])");
    return value;
  };
  switch (node.kind) {
    case Kind::number: {
      T value;
      try {
        value = from_decimal<T>(node.text);
      } catch (const std::exception&) {  // std::out_of_range from stod/stold
        throw FormulaError(node.position, "the number " + node.text + " is outside the range of " + scalar_name<T>());
      }
      using std::isfinite;
      if (!isfinite(value))
        throw FormulaError(node.position, "the number " + node.text + " is outside the range of " + scalar_name<T>());
      return Value::scalar(V(value), true);
    }
    case Kind::name: {
      if (node.text == "pi") return Value::scalar(V(boost::math::constants::pi<T>()), true);
      auto found = scope.names.find(node.text);
      if (found == scope.names.end()) {
        std::string known;
        for (const auto& [name, value] : scope.names) known += (known.empty() ? "" : ", ") + name;
        throw FormulaError(node.position, "unknown name '" + node.text + "'; expected one of: " + known + ", pi");
      }
      return found->second;
    }
    case Kind::component: {
      auto found = scope.names.find(node.text);
      if (found == scope.names.end() || !found->second.is_vector) {
        std::string vectors;
        for (const auto& [name, value] : scope.names)
          if (value.is_vector) vectors += (vectors.empty() ? "" : ", ") + name;
        throw FormulaError(node.position, "'" + node.text + "' is not a vector or an indexed family (" +
                                              (vectors.empty() ? std::string("there are none here") : "here: " + vectors) + ")");
      }
      const Value& family = found->second;
      const std::vector<int> shape =
          family.shape.empty() ? std::vector<int>{static_cast<int>(family.components.size())} : family.shape;
      if (node.operands.size() != shape.size())
        throw FormulaError(node.position, "'" + node.text + "' takes " + std::to_string(shape.size()) + " ind" +
                                              (shape.size() == 1 ? "ex" : "ices") + ", got " +
                                              std::to_string(node.operands.size()));
      long offset = 0;
      for (std::size_t k = 0; k < shape.size(); ++k) {
        const long index = index_value(node.operands[k], scope);
        if (index < 1 || index > shape[k])
          throw FormulaError(node.operands[k].position,
                             "index " + std::to_string(k + 1) + " of '" + node.text + "' is " + std::to_string(index) +
                                 ", outside its range 1.." + std::to_string(shape[k]));
        offset = offset * shape[k] + (index - 1);
      }
      return Value::scalar(family.components[static_cast<std::size_t>(offset)], family.is_constant);
    }
    case Kind::sum: {
      const long low = index_value(node.operands[0], scope), high = index_value(node.operands[1], scope);
      if (is_reserved_formula_name(node.text))
        throw FormulaError(node.position, "the summation index '" + node.text +
                                              "' is a reserved name (a function, pi, L or sum)");
      if (scope.names.count(node.text) || scope.indices.count(node.text))
        throw FormulaError(node.position, "the summation index '" + node.text +
                                              "' is already a name here (a coordinate, velocity, parameter or "
                                              "an enclosing sum's index)");
      Value total = Value::scalar(V(0), true);
      bool first = true;
      for (long index = low; index <= high; ++index) {
        if (++scope.terms > maximum_formula_terms) {
          scope.indices.erase(node.text);
          throw FormulaError(node.position, "the formula's sums expand to more than " +
                                                std::to_string(maximum_formula_terms) + " terms");
        }
        scope.indices[node.text] = index;
        Value term;
        try {
          term = interpret(node.operands[2], scope);
        } catch (...) {
          scope.indices.erase(node.text);
          throw;
        }
        if (term.is_vector) {
          scope.indices.erase(node.text);
          throw FormulaError(node.operands[2].position, "expected a scalar to sum, got a vector");
        }
        total.components[0] = first ? term.components[0] : total.components[0] + term.components[0];
        total.is_constant = total.is_constant && term.is_constant;
        first = false;
      }
      scope.indices.erase(node.text);
      return total;
    }
    case Kind::negate: {
      Value a = interpret(node.operands[0], scope);
      for (auto& x : a.components) x = -x;
      return a;
    }
    case Kind::add:
    case Kind::subtract: {
      Value a = interpret(node.operands[0], scope), b = interpret(node.operands[1], scope);
      if (a.is_vector != b.is_vector)
        throw FormulaError(node.position, std::string("cannot ") + (node.kind == Kind::add ? "add" : "subtract") +
                                              " a scalar and a vector");
      for (std::size_t i = 0; i < a.components.size(); ++i)
        a.components[i] = node.kind == Kind::add ? a.components[i] + b.components[i] : a.components[i] - b.components[i];
      a.is_constant = a.is_constant && b.is_constant;
      return a;
    }
    case Kind::multiply: {
      Value a = interpret(node.operands[0], scope), b = interpret(node.operands[1], scope);
      if (a.is_vector && b.is_vector)
        throw FormulaError(node.position, "cannot multiply two vectors (write the components)");
      if (a.is_vector) std::swap(a, b);  // scalar · vector
      Value out = b;
      for (auto& x : out.components) x = a.components[0] * x;
      out.is_constant = a.is_constant && b.is_constant;
      return out;
    }
    case Kind::divide: {
      Value a = interpret(node.operands[0], scope);
      Value b = scalar_of(node.operands[1], "divisor");
      formula_detail::check_domain<T>("divide", b.components[0], node.operands[1].position);
      for (auto& x : a.components) x = x / b.components[0];
      a.is_constant = a.is_constant && b.is_constant;
      return a;
    }
    case Kind::power: {
      Value base = scalar_of(node.operands[0], "base");
      Value exponent = scalar_of(node.operands[1], "exponent");
      if (!exponent.is_constant)
        throw FormulaError(node.operands[1].position, "expected a constant exponent (numbers, parameters, pi), "
                                                      "not one that depends on the state or on h");
      using std::abs, std::round;
      const T p = formula_detail::constant_value<T>(exponent.components[0]);
      const V& x = base.components[0];
      if (p == round(p) && abs(p) <= 64) {
        const long k = static_cast<long>(p);
        if (k < 0) formula_detail::check_domain<T>("divide", x, node.operands[0].position);
        return Value::scalar(formula_detail::integer_power(x, k), base.is_constant);
      }
      formula_detail::check_domain<T>("power", x, node.operands[0].position);
      using std::pow;
      if constexpr (formula_detail::is_tape_scalar<V>::value) return Value::scalar(pow(x, p), base.is_constant);
      else return Value::scalar(V(pow(x, p)), base.is_constant);
    }
    case Kind::call: {
      if (node.text == "L") {
        if (!scope.lagrangian)
          throw FormulaError(node.position, "L(x, v) can be called in a discrete Lagrangian's L_d only");
        const std::size_t arguments = scope.lagrangian_takes_time ? 3 : 2;
        if (node.operands.size() != arguments)
          throw FormulaError(node.position,
                             (scope.lagrangian_takes_time
                                  ? "this system's L depends on time: L takes two vectors and the time, L(x, v, s) "
                                    "(the midpoint rule is h*L((qb + qe)/2, (qe - qb)/h, t + h/2)); got "
                                  : "L takes two vectors, L(x, v); got ") +
                                 std::to_string(node.operands.size()) + " arguments");
        Value x = interpret(node.operands[0], scope), v = interpret(node.operands[1], scope);
        for (const auto* argument : {&node.operands[0], &node.operands[1]}) {
          const Value& value = argument == &node.operands[0] ? x : v;
          if (!value.is_vector && scope.dimension > 1)
            throw FormulaError(argument->position, "expected a vector of " + std::to_string(scope.dimension) +
                                                       " components as an argument of L, got a scalar");
        }
        const V time = arguments == 3 ? scalar_of(node.operands[2], "time").components[0] : V(0);
        return Value::scalar(scope.lagrangian(x.components, v.components, time), false);
      }
      // The name first: an unknown r2(i, j) is unknown, not a function of the wrong arity.
      bool known = false;
      for (const auto& f : formula_functions()) known = known || f == node.text;
      if (!known) {
        std::string names;
        for (const auto& f : formula_functions()) names += (names.empty() ? "" : ", ") + f;
        throw FormulaError(node.position, "unknown function '" + node.text + "'; expected one of: " + names +
                                              (scope.lagrangian ? ", L" : ""));
      }
      if (node.operands.size() != 1)
        throw FormulaError(node.position, node.text + " takes one argument, got " +
                                              std::to_string(node.operands.size()));
      Value x = scalar_of(node.operands[0], "argument");
      return Value::scalar(formula_detail::apply_function<T>(node.text, x.components[0], node.position),
                           x.is_constant);
    }
  }
  throw FormulaError(node.position, "unreadable formula node");
}

}  // namespace vivv
