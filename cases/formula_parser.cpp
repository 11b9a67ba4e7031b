#include "cases/formula_parser.hpp"

#include <boost/fusion/include/at_c.hpp>
#include <boost/spirit/home/x3.hpp>
#include <algorithm>
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

namespace vivv {

namespace {

namespace x3 = boost::spirit::x3;
using Kind = FormulaNode::Kind;

// The first character of the formula, for positions (x3::with).
struct formula_begin;

using Range = boost::iterator_range<const char*>;

// The node for the matched text `range`, at its first character.
template <class Context>
FormulaNode leaf(Kind kind, const Range& range, const Context& context) {
  FormulaNode node;
  node.kind = kind;
  node.text.assign(range.begin(), range.end());
  node.position = static_cast<int>(range.begin() - x3::get<formula_begin>(context));
  return node;
}

FormulaNode operation(Kind kind, std::string text, int position) {
  FormulaNode node;
  node.kind = kind;
  node.text = std::move(text);
  node.position = position;
  return node;
}

// Semantic actions: each builds a node from what its parser matched.
const auto take = [](auto& context) { x3::_val(context) = std::move(x3::_attr(context)); };
const auto make_number = [](auto& context) {
  x3::_val(context) = leaf(Kind::number, x3::_attr(context), context);
};
const auto make_name = [](auto& context) {
  x3::_val(context) = leaf(Kind::name, x3::_attr(context), context);
};
const auto make_call = [](auto& context) {
  auto& matched = x3::_attr(context);
  FormulaNode node = leaf(Kind::call, boost::fusion::at_c<0>(matched), context);
  node.operands = std::move(boost::fusion::at_c<1>(matched));
  x3::_val(context) = std::move(node);
};
const auto make_component = [](auto& context) {
  auto& matched = x3::_attr(context);
  FormulaNode node = leaf(Kind::component, boost::fusion::at_c<0>(matched), context);
  node.operands = std::move(boost::fusion::at_c<1>(matched));
  x3::_val(context) = std::move(node);
};
// sum(i = a..b, body): the index's name, the bounds, the body.
const auto make_sum = [](auto& context) {
  auto& matched = x3::_attr(context);
  FormulaNode node = leaf(Kind::sum, boost::fusion::at_c<0>(matched), context);
  node.operands.push_back(std::move(boost::fusion::at_c<1>(matched)));
  node.operands.push_back(std::move(boost::fusion::at_c<2>(matched)));
  node.operands.push_back(std::move(boost::fusion::at_c<3>(matched)));
  x3::_val(context) = std::move(node);
};
const auto make_negate = [](auto& context) {
  FormulaNode node = operation(Kind::negate, "-", x3::_attr(context).position);
  node.operands.push_back(std::move(x3::_attr(context)));
  x3::_val(context) = std::move(node);
};
// Folds `left op right` into the node built so far (left-associative chains and ^).
const auto fold = [](auto& context) {
  auto& matched = x3::_attr(context);
  const Range& symbol = boost::fusion::at_c<0>(matched);
  const char op = *symbol.begin();
  FormulaNode node = operation(op == '+'   ? Kind::add
                          : op == '-' ? Kind::subtract
                          : op == '*' ? Kind::multiply
                          : op == '/' ? Kind::divide
                                      : Kind::power,
                          std::string(1, op), static_cast<int>(symbol.begin() - x3::get<formula_begin>(context)));
  node.operands.push_back(std::move(x3::_val(context)));
  node.operands.push_back(std::move(boost::fusion::at_c<1>(matched)));
  x3::_val(context) = std::move(node);
};

const x3::rule<class expression_rule, FormulaNode> expression = "an expression";
const x3::rule<class term_rule, FormulaNode> term = "a term";
const x3::rule<class unary_rule, FormulaNode> unary = "a number, a name, '-' or '('";
const x3::rule<class power_rule, FormulaNode> power = "a power";
const x3::rule<class primary_rule, FormulaNode> primary = "a number, a name or '('";
const x3::rule<class number_rule, Range> number = "a number";
const x3::rule<class identifier_rule, Range> identifier = "a name";
const x3::rule<class additive_rule, Range> additive = "'+' or '-'";
const x3::rule<class multiplicative_rule, Range> multiplicative = "'*' or '/'";
const x3::rule<class caret_rule, Range> caret = "'^'";
const x3::rule<class arguments_rule, std::vector<FormulaNode>> arguments = "arguments";

const auto number_def =
    x3::lexeme[x3::raw[+x3::digit >> -('.' >> +x3::digit) >> -(x3::char_("eE") >> -x3::char_("+-") >> +x3::digit)]];
const auto identifier_def = x3::lexeme[x3::raw[x3::alpha >> *(x3::alnum | '_')]];
const auto additive_def = x3::raw[x3::char_("+-")];
const auto multiplicative_def = x3::raw[x3::char_("*/")];
const auto caret_def = x3::raw[x3::lit('^')];
const auto arguments_def = expression % ',';
const auto primary_def = number[make_number] |
                         (x3::lit("sum") >> '(' > identifier > '=' > expression > ".." > expression > ',' > expression >
                          ')')[make_sum] |
                         (identifier >> '(' > arguments > ')')[make_call] |
                         (identifier >> '[' > arguments > ']')[make_component] |
                         identifier[make_name] |
                         ('(' > expression > ')')[take];
const auto power_def = primary[take] >> -(caret > unary)[fold];
const auto unary_def = ('-' > unary)[make_negate] | power[take];
const auto term_def = unary[take] >> *(multiplicative > unary)[fold];
const auto expression_def = term[take] >> *(additive > term)[fold];

BOOST_SPIRIT_DEFINE(expression, term, unary, power, primary, number, identifier, additive, multiplicative, caret,
                    arguments)

// X3 names a literal as '\'c\''; the messages quote it as 'c'.
std::string readable(std::string which) {
  if (which.size() == 4 && which.front() == '\'' && which[1] == '\\') return "'" + which.substr(2, 1) + "'";
  if (which.find("uint_parser") != std::string::npos) return "a component index (1, 2, …)";
  return which;
}

// How deep the grammar recurses on `text`, bounded from above before X3 sees it: X3 (and the
// interpreter after it) recurse once per level, and a formula of 10⁴ nested parentheses — short
// enough for a case file — overflowed the stack. A level is an open '(' or '[', and within it
// each unary '-' or '^' whose operand has not ended yet (a binary operator, ',' or the closing
// bracket ends the chain at its level: a − b − c is flat, −(−(−x)) and a^b^c are not). Returns
// where the depth first passes `limit`, or −1.
int deeper_than(const std::string& text, int limit) {
  std::vector<int> chain{0};  // per open bracket: unary '-' and '^' pending at that level
  int depth = 0;
  char previous = 0, before = 0;  // the last two characters that are not spaces
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
    // The sign of a number's exponent, 1.5e-3, is neither operator.
    const bool exponent_sign = (c == '+' || c == '-') && (previous == 'e' || previous == 'E') &&
                               std::isdigit(static_cast<unsigned char>(before));
    if (exponent_sign) {
      before = previous, previous = c;
      continue;
    }
    const bool after_operand =
        previous != 0 && std::string("([,+-*/^").find(previous) == std::string::npos;
    if (c == '(' || c == '[') {
      chain.push_back(0);
      ++depth;
    } else if ((c == ')' || c == ']') && chain.size() > 1) {
      depth -= 1 + chain.back();
      chain.pop_back();
    } else if (c == '^' || (c == '-' && !after_operand)) {
      ++chain.back();
      ++depth;
    } else if (c == '+' || c == '-' || c == '*' || c == '/' || c == ',') {
      depth -= chain.back();
      chain.back() = 0;
    }
    if (depth > limit) return static_cast<int>(i);
    before = previous, previous = c;
  }
  return -1;
}

}  // namespace

FormulaNode parse_formula(const std::string& text) {
  if (const int where = deeper_than(text, maximum_formula_depth); where >= 0)
    throw FormulaError(where,
                       "nested more than " + std::to_string(maximum_formula_depth) +
                           " levels deep (open parentheses, unary '-' and chains of '^' count): "
                           "vivv reads formulas up to that depth");
  const char* const begin = text.data();
  const char* first = begin;
  const char* const last = begin + text.size();
  FormulaNode tree;
  bool parsed = false;
  try {
    parsed = x3::phrase_parse(first, last, x3::with<formula_begin>(begin)[expression], x3::space, tree);
  } catch (const x3::expectation_failure<const char*>& failure) {
    throw FormulaError(static_cast<int>(failure.where() - begin), "expected " + readable(failure.which()));
  }
  if (!parsed) throw FormulaError(static_cast<int>(first - begin), "expected a number, a name, '-' or '('");
  if (first != last)
    throw FormulaError(static_cast<int>(first - begin),
                       "expected an operator (+ - * / ^), ')' or the end of the formula");
  return tree;
}

std::string describe_formula_error(const std::string& text, const FormulaError& error) {
  // 60 characters of the formula: its start, or (for a position further in) from 30 before it.
  constexpr std::size_t shown = 60, before = 30;
  const std::size_t position = static_cast<std::size_t>(std::max(0, error.position));
  const std::size_t start = position > before ? position - before : 0;
  std::ostringstream out;
  out << "at character " << error.position + 1 << " of \"" << (start > 0 ? "…" : "") << text.substr(start, shown)
      << (text.size() > start + shown ? "…" : "") << "\": " << error.what();
  return out.str();
}

}  // namespace vivv
