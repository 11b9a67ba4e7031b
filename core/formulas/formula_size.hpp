// What a formula costs before it is expanded: the operations its recording will hold, counted
// from the syntax tree by walking its sums' bounds, not their bodies (docs/case-files.md, "Limits").
//
// A sum whose body holds no other sum costs (b − a + 1) times its body, counted once; a sum whose
// body holds sums binds each index in turn, since an inner bound may depend on it (an all-pairs
// sum(i = 1..N, sum(j = i+1..N, …)) walks N outer indices, not N² terms). The walk stops as soon
// as the count passes `stop_above`, so that reading a formula of 10¹² terms costs no more than
// refusing it. The count is an upper bound on the tape's operations, within a small factor: every
// node of the tree is one operation, a call a few, an integer power its squarings.
#pragma once

#include <algorithm>
#include <string>

#include "core/formulas/formula.hpp"

namespace vivv {

// The most operations a formula's recording may hold (an estimate by formula_operations): about
// 2 KiB each while the case is read, and a minute of recording at this size on one core.
inline constexpr double maximum_formula_operations = 5e7;

// Whether `node` or a part of it is a sum.
inline bool holds_sum(const FormulaNode& node) {
  if (node.kind == FormulaNode::Kind::sum) return true;
  for (const FormulaNode& operand : node.operands)
    if (holds_sum(operand)) return true;
  return false;
}

namespace formula_size_detail {

// The operations one node adds to a recording, its operands aside.
inline double own_operations(const FormulaNode& node) {
  using Kind = FormulaNode::Kind;
  switch (node.kind) {
    case Kind::call: return node.text == "L" ? 1 : 6;  // sinh, cosh, tanh: an exponential and a few more
    case Kind::power: {
      // An integer power k ≤ 64 by squaring: a square a bit of k past the first, a product a further
      // set bit; any other exponent (a parameter, a fraction) a pow, or at most 2 · 6 + 1 products.
      const FormulaNode& exponent = node.operands[1];
      const bool small_integer = exponent.kind == Kind::number && !exponent.text.empty() &&
                                 exponent.text.size() <= 2 &&
                                 exponent.text.find_first_not_of("0123456789") == std::string::npos;
      if (!small_integer) return 13;
      const unsigned k = static_cast<unsigned>(std::stoi(exponent.text));
      if (k > 64) return 13;
      int squares = 0;
      for (unsigned rest = k; rest > 1; rest >>= 1) ++squares;
      return std::max(1, squares + __builtin_popcount(k) - 1);
    }
    default: return 1;
  }
}

inline double operations(const FormulaNode& node, FormulaScope<double, double>& scope, double stop_above) {
  // A member x[i, k] records nothing of its index expressions.
  if (node.kind == FormulaNode::Kind::component) return 1;
  if (node.kind != FormulaNode::Kind::sum) {
    double total = own_operations(node);
    for (const FormulaNode& operand : node.operands) {
      total += operations(operand, scope, stop_above);
      if (total > stop_above) return total;
    }
    return total;
  }
  const long low = index_value(node.operands[0], scope), high = index_value(node.operands[1], scope);
  if (high < low) return 1;
  if (scope.indices.count(node.text)) return 1;  // interpret names this error; nothing is expanded
  const FormulaNode& body = node.operands[2];
  if (!holds_sum(body)) {
    scope.indices[node.text] = low;  // the body's indices are only counted, not evaluated
    const double each = operations(body, scope, stop_above) + 1;
    scope.indices.erase(node.text);
    return each * (static_cast<double>(high) - static_cast<double>(low) + 1);
  }
  double total = 1;
  for (long index = low; index <= high && total <= stop_above; ++index) {
    scope.indices[node.text] = index;
    total += operations(body, scope, stop_above - total) + 1;
  }
  scope.indices.erase(node.text);
  return total;
}

}  // namespace formula_size_detail

// The operations recording `tree` takes (an upper bound within a small factor), or a number above
// `stop_above` as soon as it passes it. FormulaError from a bound that is no index (as interpret).
inline double formula_operations(const FormulaNode& tree, double stop_above) {
  FormulaScope<double, double> scope;
  return formula_size_detail::operations(tree, scope, stop_above);
}

}  // namespace vivv
