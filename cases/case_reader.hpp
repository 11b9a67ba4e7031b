// Reading a case file field by field (docs/case-files.md). A Reader knows the file and the
// path of the JSON object it reads, checks each value's form as it is asked for it, names the
// field in every error and at the end rejects each field it was not asked about; the helpers
// shorten what an error echoes of a hostile input and suggest the name that was meant.
// cases/case_file.cpp reads the top level with it, cases/case_sections.hpp the sections.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/case_file.hpp"
#include "cases/lexical_forms.hpp"
#include "core/formulas/formula.hpp"

namespace vivv::case_reading {

// The longest number a case file may write: enough for 2000-digit inputs.
constexpr std::size_t longest_number = 4000;
// Offending values are echoed at most this long.
constexpr std::size_t longest_echo = 80;
// The longest formula a case file may write.
constexpr std::size_t longest_formula = 20000;

// At most `limit` characters of `text`, and how many more there were: a hostile input's
// 100 000-character key or value must not become a message of that size.
// Control characters (a NUL byte once cut a message short) are shown as \xNN.
std::string excerpt(const std::string& text, std::size_t limit);
// `text` for an error message, cut to longest_echo characters.
std::string echo(const std::string& text);
std::string echo(const nlohmann::json& value);
// The value of a decimal already matched by the reader's pattern, as a long double, for range
// checks; nullopt when it is outside long double's range (e.g. "1e5000", "1e-5000").
std::optional<long double> decimal_value_of(const std::string& text);
// The value of a decimal "0.5" or a fraction "1/2", to compare two of them (both checked already).
long double fraction_value(const std::string& text);
std::string join(const std::vector<std::string>& items);
// " (did you mean 'steps'?)" when one of `choices` is within `limit` edits of `name` (by default
// a third of the name's length, at least 2), the nearest; else nothing.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& choices,
                         std::size_t limit = 0);
// A name a formula may use for a coordinate, velocity or parameter.
bool is_formula_name(const std::string& name);

// Field-by-field reader for one JSON object: it knows the file and the path
// of the object, and at the end rejects any field it was not asked about.
class Reader {
 public:
  using Decimals = std::vector<std::pair<std::string, std::string>>;
  Reader(const nlohmann::json& json, std::string file, std::string path,
         std::shared_ptr<Decimals> decimals = std::make_shared<Decimals>(),
         std::shared_ptr<Decimals> written = std::make_shared<Decimals>())
      : json_(json),
        file_(std::move(file)),
        path_(std::move(path)),
        decimals_(std::move(decimals)),
        written_(std::move(written)) {
    if (!json_.is_object()) fail("", "expected a JSON object");
  }
  // Every decimal read so far by this reader and those it made, with its field.
  const Decimals& decimals() const { return *decimals_; }
  // Every number written as a formula ("pi/4", "1/3") so far, with its field and its text.
  const Decimals& written() const { return *written_; }

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    throw CaseError(file_, field(key), message);
  }
  std::string field(const std::string& key) const {
    if (key.empty()) return path_;
    return path_.empty() ? key : path_ + "." + key;
  }
  bool has(const std::string& key) {
    known_.insert(key);
    return json_.contains(key);
  }
  const nlohmann::json& get(const std::string& key) {
    if (!has(key)) {
      // A misspelt field ("step" for "steps") is named as what it is, not only as a missing one:
      // a present field not read yet within a quarter of the name's length (at least 1) of edits.
      // (Stricter than for values: a field not read yet may still be a valid one.)
      const std::size_t close = std::max<std::size_t>(1, key.size() / 4);
      for (const auto& [present, value] : json_.items())
        if (!known_.count(present) && present.size() >= 3 &&
            !did_you_mean(present, {key}, close).empty())
          fail(present, "unknown field" + did_you_mean(present, {key}, close));
      fail(key, "missing");
    }
    return json_.at(key);
  }
  Reader object(const std::string& key) { return Reader(get(key), file_, field(key), decimals_, written_); }

  // A number written as a decimal string, e.g. "1.1" or "-2.5e-3".
  std::string decimal(const std::string& key) { return decimal_value(get(key), field(key)); }
  std::string decimal_value(const nlohmann::json& value, const std::string& where) const {
    // The form report.json keeps (reports/schema.json): "-0.5", "2", "1.25e-3"; not "+2", ".5", "2.".
    if (!value.is_string())
      throw CaseError(file_, where, "expected a decimal string such as \"1.5\", got " + echo(value));
    std::string text = value.get<std::string>();
    if (text.size() > longest_number)
      throw CaseError(file_, where, "expected a decimal number of at most " + std::to_string(longest_number) +
                                        " characters, got " + std::to_string(text.size()));
    if (!is_decimal_text(text))
      throw CaseError(file_, where, "expected a decimal number such as \"-0.5\", \"2\" or \"1.25e-3\" (digits on "
                                    "both sides of a point, no '+'), got \"" + echo(text) + "\"");
    if (!decimal_value_of(text))
      throw CaseError(file_, where, "the number \"" + echo(text) + "\" is outside the range vivv accepts "
                                    "(about 1e-4900 to 1e4900)");
    decimals_->emplace_back(where, text);
    return text;
  }
  // A number written as a decimal string ("1.1") or as a formula of numbers and pi ("pi/4",
  // "1/3", "2*pi - sqrt(2)/10"; the formula syntax without names): the formula is evaluated in
  // MPFR at maximum_digits + 20 digits and returned as a decimal of maximum_digits + 10
  // significant digits, which holds any working precision a run may ask for; its text as
  // written is kept (written()).
  std::string number(const std::string& key) { return number_value(get(key), field(key)); }
  std::string number_value(const nlohmann::json& value, const std::string& where) const;
  std::vector<std::string> numbers(const std::string& key, std::size_t size) {
    const auto& value = get(key);
    if (!value.is_array() || value.size() != size)
      fail(key, "expected an array of " + std::to_string(size) +
                    " decimal strings (or formulas such as \"pi/4\"), got " + echo(value));
    std::vector<std::string> out;
    for (std::size_t i = 0; i < size; ++i)
      out.push_back(number_value(value[i], field(key) + "[" + std::to_string(i) + "]"));
    return out;
  }
  // A number in [0, 1] written as a decimal string or a fraction "p/q".
  std::string fraction(const std::string& key) {
    const auto& value = get(key);
    if (!value.is_string() || value.get<std::string>().size() > longest_echo ||
        !is_fraction_text(value.get<std::string>()))
      fail(key, "expected a decimal or a fraction such as \"1/2\", got " + echo(value));
    std::string text = value.get<std::string>();
    auto slash = text.find('/');
    const std::string numerator = text.substr(0, slash);
    if (!decimal_value_of(numerator) ||
        (slash != std::string::npos && !decimal_value_of(text.substr(slash + 1))))
      fail(key, "expected a value in [0, 1], got \"" + echo(text) + "\"");
    long double x = fraction_value(text);
    if (x < 0 || x > 1) fail(key, "expected a value in [0, 1], got \"" + echo(text) + "\"");
    return text;
  }
  std::vector<std::string> decimals(const std::string& key, std::size_t size) {
    const auto& value = get(key);
    if (!value.is_array() || value.size() != size)
      fail(key, "expected an array of " + std::to_string(size) + " decimal strings, got " + echo(value));
    std::vector<std::string> out;
    for (std::size_t i = 0; i < size; ++i)
      out.push_back(decimal_value(value[i], field(key) + "[" + std::to_string(i) + "]"));
    return out;
  }
  // An integer in [low, high]; `why` says why the range is what it is (shown when refused).
  int integer(const std::string& key, int low, int high, const std::string& why) {
    const auto& value = get(key);
    if (!value.is_number_integer() || value.get<long long>() < low || value.get<long long>() > high)
      fail(key, "expected an integer in [" + std::to_string(low) + ", " + std::to_string(high) +
                    "], got " + echo(value) + ": " + why);
    return value.get<int>();
  }
  std::string string(const std::string& key) {
    const auto& value = get(key);
    if (!value.is_string()) fail(key, "expected a string, got " + echo(value));
    return value.get<std::string>();
  }
  std::string one_of(const std::string& key, const std::vector<std::string>& choices) {
    std::string value = string(key);
    if (std::find(choices.begin(), choices.end(), value) == choices.end())
      fail(key, "unknown name '" + echo(value) + "'" + did_you_mean(value, choices) +
                    "; expected one of: " + join(choices));
    return value;
  }
  std::vector<std::string> strings(const std::string& key) {
    const auto& value = get(key);
    if (!value.is_array()) fail(key, "expected an array of strings, got " + echo(value));
    std::vector<std::string> out;
    for (const auto& item : value) {
      if (!item.is_string()) fail(key, "expected an array of strings, got " + echo(value));
      out.push_back(item.get<std::string>());
    }
    return out;
  }
  // Every field present must have been read.
  void finish() const {
    for (const auto& [key, value] : json_.items())
      if (!known_.count(key))
        fail(key, "unknown field" +
                      did_you_mean(key, std::vector<std::string>(known_.begin(), known_.end())));
  }
  const std::string& file() const { return file_; }

 private:
  const nlohmann::json& json_;
  std::string file_, path_;
  std::shared_ptr<Decimals> decimals_, written_;
  std::set<std::string> known_;
};

// The formula at `key`, parsed; a CaseError names the field, the character and what was expected.
std::shared_ptr<const FormulaNode> read_formula(Reader& reader, const std::string& key, std::string& text);

}  // namespace vivv::case_reading
