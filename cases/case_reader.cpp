#include "cases/case_reader.hpp"

#include <cctype>

#include "cases/formula_parser.hpp"
#include "core/numerics/scalar.hpp"

namespace vivv::case_reading {

// At most `limit` characters of `text`, and how many more there were: a hostile input's
// 100 000-character key or value must not become a message of that size.
// Control characters (a NUL byte once cut a message short) are shown as \xNN.
std::string excerpt(const std::string& text, std::size_t limit) {
  std::string out;
  for (std::size_t i = 0; i < std::min(text.size(), limit); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      static const char* const digits = "0123456789abcdef";
      out += "\\x";
      out += digits[c >> 4];
      out += digits[c & 15];
    } else {
      out += text[i];
    }
  }
  if (text.size() <= limit) return out;
  return out + "... (" + std::to_string(text.size() - limit) + " more characters)";
}

// `text` for an error message, cut to longest_echo characters.
std::string echo(const std::string& text) {
  if (text.size() <= longest_echo) return text;
  return text.substr(0, longest_echo) + "… (" + std::to_string(text.size()) + " characters)";
}
std::string echo(const nlohmann::json& value) { return echo(value.dump()); }

// The value of a decimal already matched by the reader's pattern, as a long double, for range
// checks; nullopt when it is outside long double's range (e.g. "1e5000", "1e-5000").
std::optional<long double> decimal_value_of(const std::string& text) {
  try {
    std::size_t used = 0;
    const long double value = std::stold(text, &used);
    if (used != text.size()) return std::nullopt;
    return value;
  } catch (const std::exception&) {  // std::out_of_range on overflow or underflow
    return std::nullopt;
  }
}

// The value of a decimal "0.5" or a fraction "1/2", to compare two of them (both checked already).
long double fraction_value(const std::string& text) {
  auto slash = text.find('/');
  if (slash == std::string::npos) return decimal_value_of(text).value_or(0);
  return decimal_value_of(text.substr(0, slash)).value_or(0) /
         decimal_value_of(text.substr(slash + 1)).value_or(1);
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

// Edit distance between two names, case, '-' and '_' ignored ("global_order" is "global-order").
std::size_t name_distance(const std::string& a, const std::string& b) {
  auto normal = [](const std::string& text) {
    std::string out;
    for (char c : text)
      out += c == '_' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
  };
  const std::string x = normal(a), y = normal(b);
  std::vector<std::size_t> row(y.size() + 1);
  for (std::size_t j = 0; j <= y.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= x.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= y.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (x[i - 1] == y[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[y.size()];
}

// " (did you mean 'steps'?)" when one of `choices` is within `limit` edits of `name` (by default
// a third of the name's length, at least 2), the nearest; else nothing.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& choices,
                         std::size_t limit) {
  if (name.size() > 200) return "";
  if (limit == 0) limit = std::max<std::size_t>(2, name.size() / 3);
  const std::string* best = nullptr;
  std::size_t best_distance = limit + 1;
  for (const auto& choice : choices) {
    const std::size_t d = name_distance(name, choice);
    if (d < best_distance && choice != name) best = &choice, best_distance = d;
  }
  return best ? " (did you mean '" + *best + "'?)" : "";
}

// A name a formula may use for a coordinate, velocity or parameter.
bool is_formula_name(const std::string& name) {
  return is_name_text(name, 32, "_");
}

// The formula at `key`, parsed; a CaseError names the field, the character and what was expected.
std::shared_ptr<const FormulaNode> read_formula(Reader& reader, const std::string& key, std::string& text) {
  text = reader.string(key);
  if (text.size() > longest_formula)
    reader.fail(key, "expected a formula of at most " + std::to_string(longest_formula) + " characters, got " +
                         std::to_string(text.size()));
  try {
    return std::make_shared<const FormulaNode>(parse_formula(text));
  } catch (const FormulaError& error) {
    reader.fail(key, describe_formula_error(text, error));
  }
}

}  // namespace vivv::case_reading

namespace vivv::case_reading {

std::string Reader::number_value(const nlohmann::json& value, const std::string& where) const {
  // Text of digits, points, signs and exponents alone is a decimal, or a malformed one ("+2",
  // ".5"), which decimal_value names as such; anything else is read as a formula.
  if (!value.is_string() || is_numeral_text(value.get<std::string>()))
    return decimal_value(value, where);
  const std::string text = value.get<std::string>();
  const std::string expected =
      "expected a decimal number such as \"-0.5\" or \"1.25e-3\", or a formula of numbers and pi "
      "such as \"pi/4\" or \"1/3\"";
  if (text.size() > longest_echo)
    throw CaseError(file_, where, expected + ", got " + std::to_string(text.size()) + " characters");
  std::string decimal;
  try {
    const FormulaNode tree = parse_formula(text);
    PrecisionGuard guard(maximum_digits + 20);
    const FormulaScope<mpfr_real, mpfr_real> scope;  // no names: numbers, pi and functions
    const FormulaValue<mpfr_real> result = interpret(tree, scope);
    if (result.is_vector || result.components.size() != 1)
      throw FormulaError(tree.position, "expected a number, got a vector");
    using std::isfinite;
    if (!isfinite(result.components[0]))
      throw FormulaError(tree.position, "the value is not a finite number");
    decimal = to_decimal<mpfr_real>(result.components[0], maximum_digits + 10);
  } catch (const FormulaError& error) {
    throw CaseError(file_, where, expected + ": " + describe_formula_error(text, error));
  }
  if (!decimal_value_of(decimal))
    throw CaseError(file_, where, "\"" + echo(text) + "\" is " + decimal.substr(0, 20) +
                                      "…, outside the range vivv accepts (about 1e-4900 to 1e4900)");
  decimals_->emplace_back(where, decimal);
  written_->emplace_back(where, text);
  return decimal;
}

}  // namespace vivv::case_reading
