// The textual forms of numbers and names a case file and a report use, each matched by a parser
// that loops over the characters (Boost.Spirit X3): libstdc++'s std::regex recurses once per
// character, and a 50,000-digit "T" once ended vivv with SIGSEGV before any length check ran.
// Every function takes text of any length and reads it once.
#pragma once

#include <cstddef>
#include <string_view>

namespace vivv {

// -?D+(.D+)?([eE][+-]?D+)?, D a digit: "-0.5", "2", "1.25e-3"; not "+2", ".5", "2." (the form
// report.json keeps, reports/schema.json).
bool is_decimal_text(std::string_view text);

// [-+0-9.eE]+: text of digits, points, signs and exponent letters alone (a decimal, or a malformed
// one such as "+2" or ".5", rather than a formula).
bool is_numeral_text(std::string_view text);

// D+(.D+)?(/[1-9]D*)?: a decimal or a fraction "p/q" with q > 0.
bool is_fraction_text(std::string_view text);

// A letter followed by at most `longest - 1` letters, digits or characters of `others`
// ("_" for a formula's names; "_.-" for a system's name).
bool is_name_text(std::string_view text, std::size_t longest, std::string_view others);

}  // namespace vivv
