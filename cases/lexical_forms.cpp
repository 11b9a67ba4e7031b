#include "cases/lexical_forms.hpp"

#include <boost/spirit/home/x3.hpp>

namespace vivv {
namespace {

namespace x3 = boost::spirit::x3;

// The whole of `text` matches `parser`.
template <class Parser>
bool matches(std::string_view text, const Parser& parser) {
  auto begin = text.begin();
  return x3::parse(begin, text.end(), parser) && begin == text.end();
}

const auto digits = +x3::digit;

}  // namespace

bool is_decimal_text(std::string_view text) {
  return matches(text, -x3::lit('-') >> digits >> -('.' >> digits) >>
                           -(x3::char_("eE") >> -x3::char_("+-") >> digits));
}

bool is_numeral_text(std::string_view text) { return matches(text, +x3::char_("-+0-9.eE")); }

bool is_fraction_text(std::string_view text) {
  return matches(text, digits >> -('.' >> digits) >> -('/' >> x3::char_('1', '9') >> *x3::digit));
}

bool is_name_text(std::string_view text, std::size_t longest, std::string_view others) {
  if (text.empty() || text.size() > longest) return false;
  const auto letter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  if (!letter(text.front())) return false;
  for (char c : text.substr(1))
    if (!letter(c) && !(c >= '0' && c <= '9') && others.find(c) == std::string_view::npos) return false;
  return true;
}

}  // namespace vivv
