// The fields of a map program's answer (protocol vivv-map/1, docs/process-protocol.md) as vivv
// reads them: numbers as decimal strings with the digits the greeting asked for, counts as JSON
// whole numbers. Anything else is a malformed answer: MapProcess::fail_answer names the field.
#pragma once

#include <charconv>
#include <cstddef>
#include <exception>
#include <nlohmann/json.hpp>
#include <string>

#include "core/numerics/scalar.hpp"
#include "core/platform/text.hpp"
#include "harness/process/program.hpp"

namespace vivv {

// `value`, the answer's `field`, as a decimal string with at least `digits` significant digits
// (or zero), in S.
template <class S>
S answer_decimal(const MapProcess& process, const nlohmann::json& value, const std::string& field, int digits) {
  if (!value.is_string())
    process.fail_answer(field + " is " + quoted_text(value.dump(), 100) +
                        ", not a decimal string (a JSON number would carry a double's 17 digits at most)");
  const std::string text = value.get<std::string>();
  const int significant = significant_digits(text);
  if (significant < 0) process.fail_answer(field + " = \"" + quoted_text(text, 100) + "\" is not a decimal number");
  if (significant > 0 && significant < digits)
    process.fail_answer(field + " = \"" + quoted_text(text, 100) + "\" has " + std::to_string(significant) +
                        " significant digits, and the greeting asked for " + std::to_string(digits) +
                        " (trailing zeros count: write them)");
  try {
    return from_decimal<S>(text);
  } catch (const std::exception& error) {  // beyond the scalar's range (float128 and MPFR too)
    process.fail_answer(field + ": " + error.what());
  }
}

// x as the 17 significant digits that a double program reads back as x ("1.2345678901234567e-01",
// the protocol's D = 17 for a double case): its perturbed inputs written without a wider
// scalar's decimal conversion.
inline std::string double_decimal(double x) {
  char text[32];
  const auto written = std::to_chars(text, text + sizeof text, x, std::chars_format::scientific, 16);
  return std::string(text, written.ptr);
}

// answer[key][i] of an array of n decimal strings (q or p of a system of n coordinates), in S.
template <class S>
S answer_number(const MapProcess& process, const nlohmann::json& answer, const char* key, int i, int n, int digits) {
  if (!answer.contains(key) || !answer[key].is_array() || answer[key].size() != static_cast<std::size_t>(n))
    process.fail_answer("expected \"" + std::string(key) + "\": an array of " + std::to_string(n) +
                        " decimal strings (the system has " + std::to_string(n) + " coordinates), got " +
                        (answer.contains(key) ? quoted_text(answer[key].dump(), 200) : std::string("none")));
  return answer_decimal<S>(process, answer[key][static_cast<std::size_t>(i)],
                           std::string(key) + "[" + std::to_string(i) + "]", digits);
}

// answer[key], the count an extension the program took up puts in its answer ("evaluations",
// "steps"): a JSON whole number from 0 to `maximum` (a count, not a measurement: not a decimal
// string); anything else ends the case, naming the field and `what` it should be.
inline long answer_count(const MapProcess& process, const nlohmann::json& answer, const char* key, long maximum,
                         const std::string& what) {
  const auto found = answer.find(key);
  if (found == answer.end() || !found->is_number_unsigned() ||
      found->get<unsigned long long>() > static_cast<unsigned long long>(maximum))
    process.fail_answer(std::string("it took up the extension \"") + key + "\" and its answer's \"" + key + "\" is " +
                        (found == answer.end() ? std::string("missing") : quoted_text(found->dump(), 80)) + ", not " +
                        what);
  return static_cast<long>(found->get<unsigned long long>());
}

}  // namespace vivv
