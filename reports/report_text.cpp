#include "reports/report_text.hpp"

#include <cctype>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include "cases/lexical_forms.hpp"

namespace vivv {

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        // XML 1.0 allows no control characters but tab, newline and carriage return.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')
          out += "\xEF\xBF\xBD";  // U+FFFD REPLACEMENT CHARACTER
        else
          out += c;
    }
  }
  return out;
}

bool is_decimal(const std::string& text) {
  return is_decimal_text(text);
}

namespace {

// Splits "m e k" into the mantissa's value and the exponent k (0 without one).
bool split_decimal(const std::string& decimal, double& mantissa, long& exponent) {
  if (!is_decimal(decimal)) return false;
  std::size_t e = decimal.find_first_of("eE");
  mantissa = std::strtod(decimal.substr(0, e).c_str(), nullptr);
  exponent = e == std::string::npos ? 0 : std::strtol(decimal.c_str() + e + 1, nullptr, 10);
  return std::isfinite(mantissa);
}

// Removes the exponent's '+' and leading zeros: "3.344e-06" -> "3.344e-6".
std::string tidy_exponent(std::string text) {
  std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string mantissa = text.substr(0, e), exponent = text.substr(e + 1);
  std::string sign = exponent[0] == '-' ? "-" : "";
  std::size_t first = exponent.find_first_not_of("+-0");
  return mantissa + "e" + sign + (first == std::string::npos ? "0" : exponent.substr(first));
}

}  // namespace

std::string format_number(double x, int digits) {
  if (!std::isfinite(x)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return tidy_exponent(buffer);
}

std::string short_decimal(const std::string& decimal, int digits) {
  double mantissa = 0;
  long exponent = 0;
  if (!split_decimal(decimal, mantissa, exponent)) return decimal;
  if (mantissa == 0) return "0";
  // Normalize to m·10^k with 1 <= |m| < 10; k may be far outside a double's range.
  int shift = static_cast<int>(std::floor(std::log10(std::fabs(mantissa))));
  long k = exponent + shift;
  if (k > -300 && k < 300) return format_number(std::strtod(decimal.c_str(), nullptr), digits);
  double m = mantissa / std::pow(10.0, shift);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, m);
  std::string text = buffer;
  if (text == "10" || text == "-10") {  // rounding carried into the next decade
    text = m < 0 ? "-1" : "1";
    ++k;
  }
  return text + "e" + std::to_string(k);
}

std::string rounded_decimal(const std::string& decimal, int digits) {
  std::size_t at = 0;
  const bool negative = !decimal.empty() && decimal[0] == '-';
  if (negative) ++at;
  std::string mantissa;
  long point = -1, exponent = 0;
  for (; at < decimal.size() && decimal[at] != 'e' && decimal[at] != 'E'; ++at) {
    if (decimal[at] == '.' && point < 0)
      point = static_cast<long>(mantissa.size());
    else if (std::isdigit(static_cast<unsigned char>(decimal[at])))
      mantissa += decimal[at];
    else
      return decimal;
  }
  if (at < decimal.size()) {
    const std::string tail = decimal.substr(at + 1);
    if (tail.empty() || tail.size() > 18 ||
        tail.find_first_not_of("+-0123456789") != std::string::npos)
      return decimal;
    exponent = std::stol(tail);
  }
  if (point < 0) point = static_cast<long>(mantissa.size());
  // value = 0.mantissa × 10^(point + exponent)
  while (!mantissa.empty() && mantissa[0] == '0') mantissa.erase(0, 1), --point;
  if (mantissa.empty() || digits < 1) return "0";
  if (static_cast<long>(mantissa.size()) > digits) {
    const bool up = mantissa[static_cast<std::size_t>(digits)] >= '5';
    mantissa.resize(static_cast<std::size_t>(digits));
    for (long i = digits - 1; up && i >= 0; --i) {
      if (mantissa[static_cast<std::size_t>(i)] != '9') {
        ++mantissa[static_cast<std::size_t>(i)];
        break;
      }
      mantissa[static_cast<std::size_t>(i)] = '0';
      if (i == 0) mantissa.insert(0, "1"), ++point, mantissa.pop_back();
    }
  }
  while (mantissa.size() > 1 && mantissa.back() == '0') mantissa.pop_back();
  const long scientific = point - 1 + exponent;
  return std::string(negative ? "-" : "") + mantissa[0] +
         (mantissa.size() > 1 ? "." + mantissa.substr(1) : std::string()) +
         (scientific != 0 ? "e" + std::to_string(scientific) : std::string());
}

std::optional<double> log10_decimal(const std::string& decimal) {
  double mantissa = 0;
  long exponent = 0;
  if (!split_decimal(decimal, mantissa, exponent) || !(mantissa > 0)) return std::nullopt;
  return std::log10(mantissa) + static_cast<double>(exponent);
}

}  // namespace vivv
