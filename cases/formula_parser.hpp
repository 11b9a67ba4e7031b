// Reading a formula's text into its syntax tree (core/formulas/formula.hpp), with
// Boost.Spirit X3. The grammar, loosest binding first:
//
//   expression = term (("+" | "-") term)*
//   term       = unary (("*" | "/") unary)*
//   unary      = "-" unary | power
//   power      = primary ("^" unary)?          (right-associative: 2^3^2 = 2^9)
//   primary    = number | "sum" "(" name "=" expression ".." expression "," expression ")"
//              | name "(" expression ("," expression)* ")"
//              | name "[" expression ("," expression)* "]" | name | "(" expression ")"
//
// An index in brackets, and a sum's bounds, are integer expressions: integers, the names of
// enclosing sums' indices and + − * of them (checked when the formula is interpreted,
// core/formulas/formula.hpp).
//
// Numbers are decimals ("0.1", "2", "1.5e-3") kept as text; names are
// letters, digits and "_", starting with a letter. Spaces are ignored.
#pragma once

#include <string>

#include "core/formulas/formula.hpp"

namespace vivv {

// How deep a formula may nest (parentheses, unary '-' and chains of '^' together): the parser
// and the interpreter recurse once per level, and a bound keeps any text within the stack.
inline constexpr int maximum_formula_depth = 500;

// The syntax tree of `text`; FormulaError at the first character that does
// not fit the grammar, saying what was expected there, or where it nests deeper than
// maximum_formula_depth.
FormulaNode parse_formula(const std::string& text);

// "at character 13 of \"(x + y\": expected ')'" — for error messages (positions count from 1).
std::string describe_formula_error(const std::string& text, const FormulaError& error);

}  // namespace vivv
