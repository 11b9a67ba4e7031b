// Text helpers shared by the HTML and JUnit renderers: escaping, and decimal
// strings (full working precision, ~40 digits) shortened for reading or
// turned into base-10 logarithms for plotting, without passing the whole
// number through a double (its exponent may lie outside a double's range).
#pragma once

#include <optional>
#include <string>

namespace vivv {

// The text with & < > " ' replaced by XML/HTML entities.
std::string xml_escape(const std::string& text);

// "1.378330627092785801439799552813122186213933e-02" -> "0.01378": `digits`
// significant digits, %g style, exponent without leading zeros. Text that is
// not a decimal number comes back unchanged.
std::string short_decimal(const std::string& decimal, int digits = 4);

// The decimal string rounded to `digits` significant digits (half up), as "d.ddde-k" — digit by
// digit, never through a double: "7.853981633974483096156608458198757e-1", 17 ->
// "7.8539816339744831e-1". Text that is not a decimal comes back unchanged.
std::string rounded_decimal(const std::string& decimal, int digits);

// log10(x) of the decimal string x: log10(mantissa) + exponent. Empty when x
// is zero, negative, not finite or not a number.
std::optional<double> log10_decimal(const std::string& decimal);

// True for text of the form [-]digits[.digits][e[+-]digits].
bool is_decimal(const std::string& text);

// A double with `digits` significant digits (%g), "-" when not finite.
std::string format_number(double x, int digits = 4);

}  // namespace vivv
