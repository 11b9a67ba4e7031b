#include "cases/case_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include "cases/catalogue.hpp"
#include "cases/formula_parser.hpp"
#include "core/qxq/discrete_lagrangian.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/maps/odeint_map.hpp"
#include "core/maps/user_map.hpp"

namespace vivv {

namespace {

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

}  // namespace

CaseError::CaseError(const std::string& file, const std::string& field, const std::string& message)
    : std::runtime_error(excerpt(file, 500) + ": " +
                         (field.empty() ? "" : "field '" + excerpt(field, 120) + "': ") +
                         excerpt(message, 2000)),
      file(file),
      field(field) {}

std::vector<std::string> system_names() {
  std::vector<std::string> names;
  for (const auto& info : system_catalogue()) names.push_back(info.name);
  for (const auto& registered : registered_systems()) names.push_back(registered.name);
  return names;
}

std::vector<std::string> claim_names() { return claim_ids(); }

const std::vector<std::string>& scalar_names() {
  static const std::vector<std::string> names = {"double", "long double", "float128", "mpfr"};
  return names;
}

FormulaSystemDefinition catalogue_twin(const std::string& name,
                                       const std::vector<std::pair<std::string, std::string>>& parameters) {
  // cases/systems.hpp, formula by formula.
  static const std::map<std::string, std::string> formulas = {
      {"paper_example", "(g0 + g2*q^2) * w^2 / 2 - (k*(1 - cos(q)) + m*q^2/2)"},
      {"harmonic_oscillator", "w^2/2 - omega^2*q^2/2"},
      {"pendulum", "w^2/2 - k*(1 - cos(q))"},
      {"relativistic_particle", "-mass*sqrt(1 - w^2) - k*q^2/2"},
      {"charged_particle", "(w1^2 + w2^2)/2 + B*(q1*w2 - q2*w1)/2 - k*(q1^2 + q2^2)/2"},
      {"kepler", "(w1^2 + w2^2)/2 + mu/sqrt(q1^2 + q2^2)"},
      {"henon_heiles", "(w1^2 + w2^2)/2 - (q1^2 + q2^2)/2 - lambda*(q1^2*q2 - q2^3/3)"},
      {"double_pendulum", "(m1 + m2)*l1^2*w1^2/2 + m2*l2^2*w2^2/2 + m2*l1*l2*w1*w2*cos(q1 - q2)"
                          " + (m1 + m2)*g*l1*cos(q1) + m2*g*l2*cos(q2)"}};
  auto found = formulas.find(name);
  if (found == formulas.end()) throw std::invalid_argument("no formula twin for the system '" + name + "'");
  FormulaSystemDefinition definition;
  definition.name = name;
  definition.text = found->second;
  definition.lagrangian = parse_formula(found->second);
  const bool planar = name == "charged_particle" || name == "kepler" || name == "henon_heiles" ||
                      name == "double_pendulum";
  if (planar) {
    definition.coordinates = {"q1", "q2"};
    definition.velocities = {"w1", "w2"};
  } else {
    definition.coordinates = {"q"};
    definition.velocities = {"w"};
  }
  definition.parameters = parameters;
  if (name == "charged_particle" || name == "kepler")  // rotations about the origin
    definition.symmetry = {parse_formula("-q2"), parse_formula("q1")};
  return definition;
}

namespace {

// The longest number a case file may write: enough for 2000-digit inputs.
constexpr std::size_t longest_number = 4000;
// Offending values are echoed at most this long.
constexpr std::size_t longest_echo = 80;

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
                         std::size_t limit = 0) {
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

// Field-by-field reader for one JSON object: it knows the file and the path
// of the object, and at the end rejects any field it was not asked about.
class Reader {
 public:
  using Decimals = std::vector<std::pair<std::string, std::string>>;
  Reader(const nlohmann::json& json, std::string file, std::string path,
         std::shared_ptr<Decimals> decimals = std::make_shared<Decimals>())
      : json_(json),
        file_(std::move(file)),
        path_(std::move(path)),
        decimals_(std::move(decimals)) {
    if (!json_.is_object()) fail("", "expected a JSON object");
  }
  // Every decimal read so far by this reader and those it made, with its field.
  const Decimals& decimals() const { return *decimals_; }

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
  Reader object(const std::string& key) { return Reader(get(key), file_, field(key), decimals_); }

  // A number written as a decimal string, e.g. "1.1" or "-2.5e-3".
  std::string decimal(const std::string& key) { return decimal_value(get(key), field(key)); }
  std::string decimal_value(const nlohmann::json& value, const std::string& where) const {
    // The form report.json keeps (reports/schema.json): "-0.5", "2", "1.25e-3"; not "+2", ".5", "2.".
    static const std::regex pattern(R"(-?\d+(\.\d+)?([eE][+-]?\d+)?)");
    if (!value.is_string())
      throw CaseError(file_, where, "expected a decimal string such as \"1.5\", got " + echo(value));
    std::string text = value.get<std::string>();
    if (text.size() > longest_number)
      throw CaseError(file_, where, "expected a decimal number of at most " + std::to_string(longest_number) +
                                        " characters, got " + std::to_string(text.size()));
    if (!std::regex_match(text, pattern))
      throw CaseError(file_, where, "expected a decimal number such as \"-0.5\", \"2\" or \"1.25e-3\" (digits on "
                                    "both sides of a point, no '+'), got \"" + echo(text) + "\"");
    if (!decimal_value_of(text))
      throw CaseError(file_, where, "the number \"" + echo(text) + "\" is outside the range vivv accepts "
                                    "(about 1e-4900 to 1e4900)");
    decimals_->emplace_back(where, text);
    return text;
  }
  // A number in [0, 1] written as a decimal string or a fraction "p/q".
  std::string fraction(const std::string& key) {
    const auto& value = get(key);
    static const std::regex pattern(R"(\d+(\.\d+)?(/[1-9]\d*)?)");
    if (!value.is_string() || value.get<std::string>().size() > longest_echo ||
        !std::regex_match(value.get<std::string>(), pattern))
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
  std::shared_ptr<Decimals> decimals_;
  std::set<std::string> known_;
};

// The longest formula a case file may write.
constexpr std::size_t longest_formula = 20000;

// A name a formula may use for a coordinate, velocity or parameter.
bool is_formula_name(const std::string& name) {
  static const std::regex pattern(R"([A-Za-z][A-Za-z0-9_]{0,31})");
  return std::regex_match(name, pattern);
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

// What a discrete Lagrangian formula means, checked by recording it in long double: qb and qe
// are vectors of `dimension` components, h a scalar, the parameters constants, and L(x, v)
// stands for the system's Lagrangian.
void check_expression(const FormulaNode& tree, int dimension,
                      const std::vector<std::pair<std::string, std::string>>& parameters) {
  using T = long double;
  using V = TapeScalar<T>;
  TapeRecording<T> recording(2 * dimension + 1);
  FormulaScope<T, V> scope;
  FormulaValue<V> qb{{}, true, false}, qe{{}, true, false};
  for (int i = 0; i < dimension; ++i)
    qb.components.push_back(recording.input(i)), qe.components.push_back(recording.input(dimension + i));
  scope.names["qb"] = qb;
  scope.names["qe"] = qe;
  scope.names["h"] = FormulaValue<V>::scalar(recording.input(2 * dimension), false);
  for (const auto& [name, value] : parameters) scope.names[name] = FormulaValue<V>::scalar(V(from_decimal<T>(value)), true);
  scope.dimension = dimension;
  scope.lagrangian = [](const std::vector<V>& x, const std::vector<V>& v) {
    V sum = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sum = sum + x[i] * v[i];
    return sum;
  };
  const FormulaValue<V> value = interpret(tree, scope);
  if (value.is_vector) throw FormulaError(tree.position, "expected L_d to be a scalar, got a vector");
}

DiscretizationSpec read_discretization(Reader reader, int dimension,
                                       const std::vector<std::pair<std::string, std::string>>& parameters,
                                       bool allow_tq = true) {
  DiscretizationSpec spec;
  if (reader.has("kind") && reader.get("kind") == "process") {
    // A one-step map in another program (protocol vivv-map/1): its command and declared order.
    spec.kind = "process";
    if (!allow_tq)
      reader.fail("kind", "a one-step map cannot be pulled back as a Q×Q discrete Lagrangian");
    if (reader.has("formalism"))
      reader.fail("formalism",
                  "a one-step map (kind \"process\") is neither a Q×Q nor a TQ discretization: "
                  "leave formalism out");
    spec.formalism = "map";
    const auto& command = reader.get("command");
    if (!command.is_array() || command.empty() || command.size() > 64)
      reader.fail(
          "command",
          "expected the program and its arguments as an array of 1 to 64 strings, such as "
          "[\"python3\", \"step.py\"] (run without a shell, in the case file's folder), got " +
              echo(command));
    for (std::size_t i = 0; i < command.size(); ++i) {
      const std::string where = "command[" + std::to_string(i) + "]";
      if (!command[i].is_string()) reader.fail(where, "expected a string, got " + echo(command[i]));
      const std::string word = command[i].get<std::string>();
      if ((i == 0 && word.empty()) || word.size() > 4096 || word.find('\0') != std::string::npos)
        reader.fail(
            where,
            i == 0 ? "expected the program to start: a name on PATH or a path relative to the case "
                     "file's folder, at most 4096 characters without NUL"
                   : "expected an argument of at most 4096 characters without NUL");
      spec.command.push_back(word);
    }
    spec.declared_order =
        reader.integer("order", 1, 64,
                       "the order its author states, |Phi_h - F_h| = O(h^(order+1)), "
                       "which global-order checks");
    if (reader.has("twin"))
      reader.fail("twin", "a one-step map has no discrete Lagrangian to add a twin term to");
    reader.finish();
    return spec;
  }
  if (reader.has("kind") && (reader.get("kind") == "odeint" || reader.get("kind") == "map")) {
    // A one-step map of another library (odeint's, or one a program linking vivv registered):
    // no formalism, no twin term, nothing but its name.
    spec.kind = reader.get("kind").get<std::string>();
    if (!allow_tq) reader.fail("kind", "a one-step map cannot be pulled back as a Q×Q discrete Lagrangian");
    if (reader.has("formalism"))
      reader.fail("formalism", "a one-step map (kind \"" + spec.kind + "\") is neither a Q×Q nor a TQ "
                               "discretization: leave formalism out");
    spec.formalism = "map";
    std::vector<std::string> names;
    if (spec.kind == "odeint") {
      for (const auto& stepper : odeint_steppers()) names.push_back(stepper.name);
      spec.stepper = reader.one_of("stepper", names);
    } else {
      for (const auto& map : registered_maps()) names.push_back(map.name);
      if (names.empty())
        reader.fail("kind", "\"map\" puts a method that a program linking vivv registered (vivv::register_map) "
                            "under test, and this program registered none; the vivv tool has odeint's steppers "
                            "(\"kind\": \"odeint\")");
      spec.stepper = reader.one_of("name", names);
    }
    if (reader.has("twin")) reader.fail("twin", "a one-step map has no discrete Lagrangian to add a twin term to");
    reader.finish();
    return spec;
  }
  if (reader.has("formalism"))
    spec.formalism = reader.one_of("formalism", allow_tq ? std::vector<std::string>{"qxq", "tq"}
                                                         : std::vector<std::string>{"qxq"});
  if (spec.formalism == "tq") {
    TQSpec tq;
    tq.psi = reader.one_of("psi", {"linear", "taylor", "exact"});
    if (tq.psi == "taylor")
      tq.r =
          reader.integer("r", 1, 8, "the degree of the Taylor psi; vivv expands it up to degree 8");
    if (tq.psi != "taylor" && reader.has("r"))
      reader.fail("r", "a degree r is taken only by psi \"taylor\", not \"" + tq.psi + "\"");
    tq.theta = reader.fraction("theta");
    tq.lagrangian = reader.one_of("lagrangian", {"quadrature", "pullback", "exact"});
    if (tq.lagrangian == "exact" && tq.psi != "exact")
      reader.fail("lagrangian", "\"exact\" is the action along the exact psi: needs psi \"exact\", not \"" +
                                    tq.psi + "\"");
    if (tq.lagrangian == "quadrature")
      tq.nodes = reader.integer("nodes", 1, 64,
                                "the Gauss nodes of the quadrature of L along psi; at most 64");
    if (tq.lagrangian == "pullback") {
      tq.qxq = std::make_shared<DiscretizationSpec>(
          read_discretization(reader.object("qxq"), dimension, parameters, false));
      if (tq.qxq->kind == "galerkin")
        reader.fail("qxq", "a Galerkin L_d is extremized by Newton in the working precision and cannot be pulled "
                           "back through psi's derivatives; use it on Q × Q");
    }
    spec.tq = tq;
  } else if (reader.has("kind") && reader.get("kind") == "user") {
    // L_d registered as C++ code by a program linking vivv: run as an "expression" L_d.
    std::vector<std::string> names;
    for (const auto& rule : registered_discrete_lagrangians()) names.push_back(rule.name);
    if (names.empty())
      reader.fail("kind", "\"user\" puts a discrete Lagrangian that a program linking vivv registered "
                          "(vivv::register_discrete_lagrangian) under test, and this program registered none; "
                          "write L_d as a formula instead (\"kind\": \"expression\")");
    const std::string name = reader.one_of("name", names);
    for (const auto& rule : registered_discrete_lagrangians())
      if (rule.name == name) spec.recorded = rule.recorder, spec.declared_order = rule.order;
    spec.kind = "expression";
    spec.expression = "registered C++ discrete Lagrangian '" + name + "'";
  } else {
    spec.kind = reader.one_of("kind", rule_names());
    QxQRule rule = *rule_from_name(spec.kind);
    if (rule == QxQRule::alpha) spec.parameter = reader.decimal("alpha");
    if (rule == QxQRule::weighted) spec.parameter = reader.decimal("beta");
    if (rule == QxQRule::galerkin) {
      spec.galerkin_degree = reader.integer(
          "degree", 1, 8, "the degree of the Galerkin curve; vivv builds curves up to degree 8");
      spec.galerkin_quadrature = reader.one_of("quadrature", {"gauss", "lobatto"});
      // Fewer nodes than the degree leave the interior values too loosely tied to L (degree 3 with 2
      // Gauss nodes measures order 2, not min(2s, 2m) = 4): vivv has no prediction there.
      spec.galerkin_nodes = reader.integer(
          "nodes", std::max(spec.galerkin_degree, spec.galerkin_quadrature == "lobatto" ? 2 : 1),
          16,
          "fewer nodes than the degree leave the curve's interior values too loosely tied to L "
          "(degree 3 with 2 Gauss nodes measures order 2, not 4), so vivv has no prediction there "
          "(and Lobatto needs 2 nodes, its end points); at most 16 nodes");
    }
    if (rule == QxQRule::expression) {
      spec.expression_tree = read_formula(reader, "L_d", spec.expression);
      try {
        check_expression(*spec.expression_tree, dimension, parameters);
      } catch (const FormulaError& error) {
        reader.fail("L_d", describe_formula_error(spec.expression, error));
      }
      spec.declared_order =
          reader.integer("order", 1, 64, "the order the rule declares, which its claims check");
    }
  }
  if (reader.has("twin")) {
    Reader twin = reader.object("twin");
    spec.twin = TwinSpec{
        twin.decimals("a", dimension),
        twin.integer("power", 1, 16, "the power s of h in the twin term h^s·a·w; at most 16")};
    twin.finish();
  }
  reader.finish();
  return spec;
}

// "system": {"name", "lagrangian", "coordinates", "velocities", "params"}: a system as a formula.
void read_formula_system(Reader& system, CaseSpec& spec) {
  spec.system = system.string("name");
  const auto catalogue = system_names();
  if (std::find(catalogue.begin(), catalogue.end(), spec.system) != catalogue.end())
    system.fail("name", "'" + spec.system + "' is a catalogue system; a system given by its lagrangian needs a "
                        "name of its own");
  if (!is_formula_name(spec.system) && !std::regex_match(spec.system, std::regex(R"([A-Za-z][A-Za-z0-9_.-]{0,63})")))
    system.fail("name", "expected a name of letters, digits, '_', '-' and '.', starting with a letter, got \"" +
                            echo(spec.system) + "\"");
  auto definition = std::make_shared<FormulaSystemDefinition>();
  definition->name = spec.system;
  definition->coordinates = system.strings("coordinates");
  definition->velocities = system.strings("velocities");
  const std::size_t n = definition->coordinates.size();
  if (n < 1 || n > 4) system.fail("coordinates", "expected 1 to 4 coordinate names, got " + std::to_string(n));
  if (definition->velocities.size() != n)
    system.fail("velocities", "expected " + std::to_string(n) + " velocity names, one per coordinate, got " +
                                  std::to_string(definition->velocities.size()));
  // Every name once, in one role, and not one the grammar reserves.
  std::map<std::string, std::string> role;
  auto claim_name = [&](const std::string& name, const std::string& field, const std::string& what) {
    if (!is_formula_name(name))
      throw CaseError(system.file(), field, "expected a name of letters, digits and '_' starting with a letter "
                                            "(at most 32 characters), got \"" + echo(name) + "\"");
    if (is_reserved_formula_name(name) || name == "qb" || name == "qe" || name == "h")
      throw CaseError(system.file(), field, "'" + name + "' is reserved (functions, pi, L, qb, qe, h)");
    if (role.count(name))
      throw CaseError(system.file(), field, "'" + name + "' is used both as " + role[name] + " and as " + what);
    role[name] = what;
  };
  for (std::size_t i = 0; i < n; ++i)
    claim_name(definition->coordinates[i], system.field("coordinates") + "[" + std::to_string(i) + "]",
               "a coordinate");
  for (std::size_t i = 0; i < n; ++i)
    claim_name(definition->velocities[i], system.field("velocities") + "[" + std::to_string(i) + "]",
               "a velocity");
  if (system.has("params")) {
    const auto& params = system.get("params");
    if (!params.is_object()) system.fail("params", "expected an object of name: decimal string, got " + echo(params));
    Reader values = system.object("params");
    for (const auto& [name, value] : params.items()) {
      claim_name(name, system.field("params") + "." + name, "a parameter");
      spec.parameters.emplace_back(name, values.decimal(name));
    }
    values.finish();
  }
  definition->parameters = spec.parameters;
  std::string text;
  definition->lagrangian = *read_formula(system, "lagrangian", text);
  definition->text = text;
  spec.dimension = static_cast<int>(n);
  std::vector<std::string> symmetry_texts;
  if (system.has("symmetry")) {
    symmetry_texts = system.strings("symmetry");
    if (symmetry_texts.size() != n)
      system.fail("symmetry", "expected the generator ξ(q) as " + std::to_string(n) +
                                  " formulas, one per coordinate, got " + std::to_string(symmetry_texts.size()));
    for (std::size_t i = 0; i < n; ++i) {
      const std::string field = "symmetry[" + std::to_string(i) + "]";
      if (symmetry_texts[i].size() > longest_formula) system.fail(field, "formula too long");
      try {
        definition->symmetry.push_back(parse_formula(symmetry_texts[i]));
      } catch (const FormulaError& error) {
        system.fail(field, describe_formula_error(symmetry_texts[i], error));
      }
    }
  }
  // Each component of ξ alone, so that an error names its field: a scalar in the coordinates
  // and parameters (the velocities are unknown names there).
  for (std::size_t i = 0; i < symmetry_texts.size(); ++i) {
    using V = TapeScalar<long double>;
    TapeRecording<long double> recording(static_cast<int>(n));
    FormulaScope<long double, V> scope;
    for (std::size_t j = 0; j < n; ++j)
      scope.names[definition->coordinates[j]] = FormulaValue<V>::scalar(recording.input(static_cast<int>(j)), false);
    for (const auto& [name, value] : definition->parameters)
      scope.names[name] = FormulaValue<V>::scalar(V(from_decimal<long double>(value)), true);
    try {
      if (interpret(definition->symmetry[i], scope).is_vector)
        throw FormulaError(0, "expected a number, got a vector");
    } catch (const FormulaError& error) {
      system.fail("symmetry[" + std::to_string(i) + "]", describe_formula_error(symmetry_texts[i], error));
    }
  }
  try {
    switch (n) {
      case 1: make_formula_system<long double, 1>(*definition); break;
      case 2: make_formula_system<long double, 2>(*definition); break;
      case 3: make_formula_system<long double, 3>(*definition); break;
      default: make_formula_system<long double, 4>(*definition); break;
    }
  } catch (const FormulaError& error) {
    system.fail("lagrangian", describe_formula_error(text, error));
  }
  spec.formula = std::move(definition);
}

// "system.params": a decimal for each declared parameter (name, default), the default where the
// case gives none; a parameter that is not declared is an error (params.finish).
std::vector<std::pair<std::string, std::string>> read_parameters(
    Reader& system, const std::vector<std::pair<std::string, std::string>>& declared) {
  std::vector<std::pair<std::string, std::string>> values = declared;
  if (!system.has("params")) return values;
  Reader params = system.object("params");
  for (auto& [name, value] : values)
    if (params.has(name)) value = params.decimal(name);
  params.finish();
  return values;
}

// The system registered under the name "system.name" gives, if one is.
const RegisteredSystem* registered_system(Reader& system) {
  if (!system.has("name") || !system.get("name").is_string()) return nullptr;
  for (const auto& registered : registered_systems())
    if (registered.name == system.get("name").get<std::string>()) return &registered;
  return nullptr;
}

// d²L/dw² of `system` at (q, w), or a CaseError naming the field when it is singular there.
template <class System>
void check_regular(const System& system, const CaseSpec& spec, const std::string& file) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  Vector<T, n> q, w;
  for (int i = 0; i < n; ++i) q[i] = from_decimal<T>(spec.q[i]), w[i] = from_decimal<T>(spec.w[i]);
  const auto d = lagrangian_derivatives(system, q, w);
  const std::string field = spec.formula ? "system.lagrangian" : "initial";
  using std::isfinite;
  if (!isfinite(d.value))
    throw CaseError(file, field, "L is not finite at the initial state: the state is outside the Lagrangian's domain");
  const T determinant = d.d2L_dw2.determinant();
  const T scale = d.d2L_dw2.cwiseAbs().maxCoeff();
  Eigen::FullPivLU<Matrix<T, n, n>> lu(d.d2L_dw2);
  lu.setThreshold(1024 * epsilon<T>());
  if (!isfinite(determinant) || !(scale > 0) || !lu.isInvertible())
    throw CaseError(file, field, "the Lagrangian is not regular at the initial state: det d2L/dw2 = " +
                                     to_decimal<T>(determinant) + " (d2L/dw2 is singular there, so the "
                                     "Euler–Lagrange equations do not determine the acceleration)");
}

// The initial state in the formula's domain (sqrt, log, powers, quotients) and the Lagrangian
// regular there, checked in long double before any work.
void check_initial_state(const CaseSpec& spec, const std::string& file) {
  using T = long double;
  std::vector<T> q, w;
  for (int i = 0; i < spec.dimension; ++i) q.push_back(from_decimal<T>(spec.q[i])), w.push_back(from_decimal<T>(spec.w[i]));
  if (spec.formula) {
    try {
      if (!spec.formula->recorded) check_formula_domain<T>(*spec.formula, q, w);
    } catch (const FormulaError& error) {
      throw CaseError(file, "system.lagrangian", describe_formula_error(spec.formula->text, error));
    }
    switch (spec.dimension) {
      case 1: check_regular(make_formula_system<T, 1>(*spec.formula), spec, file); break;
      case 2: check_regular(make_formula_system<T, 2>(*spec.formula), spec, file); break;
      case 3: check_regular(make_formula_system<T, 3>(*spec.formula), spec, file); break;
      default: check_regular(make_formula_system<T, 4>(*spec.formula), spec, file); break;
    }
    return;
  }
  std::vector<std::string> parameters;
  for (const auto& [name, value] : spec.parameters) parameters.push_back(value);
  visit_system<T>(spec.system, parameters, [&](const auto& system) { check_regular(system, spec, file); });
}

}  // namespace

CaseSpec parse_case(const nlohmann::json& json, const std::string& file) {
  Reader reader(json, file, "");
  CaseSpec spec;
  spec.file = file;
  spec.source = json;
  spec.name = reader.string("name");
  if (spec.name.empty() || spec.name.size() > 200 || spec.name.find_first_of("/\\ ") != std::string::npos ||
      std::any_of(spec.name.begin(), spec.name.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; }))
    reader.fail("name", "expected a non-empty name of at most 200 characters without spaces, slashes or "
                        "control characters");

  Reader system = reader.object("system");
  if (system.has("lagrangian")) {
    read_formula_system(system, spec);
  } else if (const RegisteredSystem* registered = registered_system(system); registered) {
    // A system registered as C++ code by a program linking vivv: run as a formula system.
    spec.system = registered->name;
    spec.dimension = registered->dimension;
    spec.parameters = read_parameters(system, registered->parameters);
    auto definition = std::make_shared<FormulaSystemDefinition>();
    definition->name = registered->name;
    definition->text = "registered C++ system '" + registered->name + "'";
    definition->recorded = registered->recorder;
    for (int i = 1; i <= registered->dimension; ++i)
      definition->coordinates.push_back("q" + std::to_string(i)), definition->velocities.push_back("w" + std::to_string(i));
    definition->parameters = spec.parameters;
    spec.formula = std::move(definition);
  } else {
    spec.system = system.one_of("name", system_names());
    SystemInfo info;
    for (const auto& candidate : system_catalogue())
      if (candidate.name == spec.system) info = candidate;
    spec.dimension = info.dimension;
    std::vector<std::pair<std::string, std::string>> declared;
    for (const auto& parameter : info.parameters) declared.emplace_back(parameter.name, parameter.default_value);
    spec.parameters = read_parameters(system, declared);
  }
  system.finish();

  Reader initial = reader.object("initial");
  spec.q = initial.decimals("q", spec.dimension);
  spec.w = initial.decimals("w", spec.dimension);
  initial.finish();
  check_initial_state(spec, file);

  spec.final_time = reader.decimal("T");
  if (spec.final_time.front() == '-' || !(*decimal_value_of(spec.final_time) > 0))
    reader.fail("T", "expected a positive time, got \"" + spec.final_time + "\"");

  const auto& steps = reader.get("steps");
  if (!steps.is_array() || steps.size() < 3)
    reader.fail("steps", "expected an array of at least 3 step counts N (h = T/N), got " +
                             steps.dump());
  for (const auto& n : steps) {
    if (!n.is_number_integer() || n.get<long long>() < 2 || n.get<long long>() > 1000000)
      reader.fail(
          "steps",
          "expected integers N in [2, 1000000] (N = 1 solves no DEL step; a run keeps every q_k in "
          "memory, so a million is the bound), got " +
              n.dump());
    if (!spec.steps.empty() && n.get<int>() <= spec.steps.back())
      reader.fail("steps", "expected strictly increasing step counts, got " + steps.dump());
    spec.steps.push_back(n.get<int>());
  }

  if (reader.has("scalar")) spec.scalar = reader.one_of("scalar", scalar_names());
  if (spec.scalar != "mpfr" && spec.dimension > 2)
    reader.fail("scalar", "a system of " + std::to_string(spec.dimension) +
                              " coordinates runs in mpfr only (double, long double and float128 are built for 1 "
                              "and 2 coordinates)");
  if (reader.has("digits")) {
    if (spec.scalar != "mpfr")
      reader.fail("digits", "sets the MPFR working precision, and this case runs in \"" + spec.scalar + "\"");
    spec.digits = reader.integer(
        "digits", 20, maximum_digits,
        "MPFR's working precision in decimal digits: below 20 it is no more precise than "
        "long double; at 1000 the paper example's midpoint case takes 3 min and at 2000 "
        "its reference flow alone took 11 min");
  }
  spec.discretization = read_discretization(reader.object("discretization"), spec.dimension, spec.parameters);
  if (reader.has("past_discretization"))
    spec.past_discretization =
        read_discretization(reader.object("past_discretization"), spec.dimension, spec.parameters);
  if (reader.has("compare_discretization"))
    spec.compare_discretization =
        read_discretization(reader.object("compare_discretization"), spec.dimension, spec.parameters);
  if (reader.has("start")) spec.start = reader.one_of("start", {"reference", "momentum"});
  if (reader.has("order_tolerance")) {
    spec.order_tolerance = reader.decimal("order_tolerance");
    const long double tolerance = *decimal_value_of(spec.order_tolerance);
    if (!(tolerance >= 0.001L) || tolerance > *decimal_value_of(maximum_order_tolerance))
      reader.fail("order_tolerance", std::string("expected a tolerance in [0.001, ") + maximum_order_tolerance +
                                         "], got \"" + echo(spec.order_tolerance) +
                                         "\": a wider one would accept an order-r prediction at order r − 1, "
                                         "a narrower one is below what a fitted order can resolve");
  }
  if (reader.has("labels")) spec.labels = reader.strings("labels");

  spec.claims = reader.strings("claims");
  if (spec.claims.empty()) reader.fail("claims", "expected at least one claim");
  for (std::size_t i = 1; i < spec.claims.size(); ++i)
    if (std::find(spec.claims.begin(), spec.claims.begin() + i, spec.claims[i]) != spec.claims.begin() + i)
      throw CaseError(file, "claims[" + std::to_string(i) + "]", "'" + echo(spec.claims[i]) + "' is listed twice");
  for (std::size_t i = 0; i < spec.claims.size(); ++i) {
    const auto& id = spec.claims[i];
    std::string where = "claims[" + std::to_string(i) + "]";
    if (std::find(claim_ids().begin(), claim_ids().end(), id) == claim_ids().end())
      throw CaseError(file, where,
                      "unknown claim '" + echo(id) + "'" + did_you_mean(id, claim_ids()) +
                          "; expected one of: " + join(claim_ids()));
    if (id == "twin-term-invariance" && !spec.discretization.twin)
      throw CaseError(file, where, "twin-term-invariance needs discretization.twin");
    if (id == "mismatched-legendre" && !spec.past_discretization)
      throw CaseError(file, where, "mismatched-legendre needs past_discretization");
    if (spec.discretization.formalism == "map" && !map_claim_ids().count(id))
      throw CaseError(file, where, id + " is a claim about discrete Lagrangians, and discretization kind \"" +
                                        spec.discretization.kind + "\" is a one-step map without one: a map takes " + join(std::vector<std::string>(
                                            map_claim_ids().begin(), map_claim_ids().end())));
    bool tq = spec.discretization.formalism == "tq";
    if (tq && id == "local-order")
      throw CaseError(file, where, "local-order measures one step of a map; on a discretization of TQ that "
                                   "measurement is the claim \"order\" (paper Thm 5.5): list \"order\" instead");
    if (!tq && tq_claim_ids().count(id))
      throw CaseError(file, where, id + " is a claim about discretizations of TQ: needs discretization.formalism \"tq\"");
    if (tq && qxq_claim_ids().count(id))
      throw CaseError(file, where, id + " is a claim about Q×Q discrete Lagrangians: needs discretization.formalism \"qxq\"");
    bool pair = id == "contact-order" || id == "past-future-symmetry";
    if (pair && !spec.compare_discretization)
      throw CaseError(file, where, id + " needs compare_discretization");
    if (pair && tq && spec.compare_discretization->tq &&
        fraction_value(spec.compare_discretization->tq->theta) !=
            fraction_value(spec.discretization.tq->theta))
      throw CaseError(file, where, id + " compares two discretizations with the same α± (Thm 5.4): "
                                   "compare_discretization.theta must equal discretization.theta");
    auto is_exact = [](const DiscretizationSpec* d) {
      return d && d->tq && d->tq->lagrangian == "exact";
    };
    const DiscretizationSpec* compare = spec.compare_discretization ? &*spec.compare_discretization : nullptr;
    bool order_of_one = id == "order" || id == "global-order";
    if ((order_of_one && is_exact(&spec.discretization)) ||
        (pair && is_exact(&spec.discretization) && is_exact(compare)))
      throw CaseError(file, where, id + " measures an order, and an exact discretization has none: "
                                   "its claim is exact-discretization");
    if (id == "discrete-noether") {
      const auto catalogue = system_catalogue();
      const bool symmetric =
          spec.formula ? !spec.formula->symmetry.empty()
                       : std::any_of(catalogue.begin(), catalogue.end(),
                                     [&](const SystemInfo& info) { return info.name == spec.system && info.symmetric; });
      if (!symmetric)
        throw CaseError(file, where, "discrete-noether needs a system with a symmetry: '" + spec.system +
                                         "' declares none (a formula system declares its generator as "
                                         "system.symmetry, a formula per coordinate)");
    }
    if (id == "modified-energy" && !tq &&
        ((spec.discretization.kind != "midpoint" && spec.discretization.kind != "trapezoid") ||
         spec.discretization.twin))
      throw CaseError(file, where, "modified-energy is derived for the midpoint and trapezoid rules without twin "
                                   "terms, not for discretization.kind \"" + spec.discretization.kind + "\"" +
                                   (spec.discretization.twin ? " with a twin term" : ""));
    if (id == "precision-leak") {
      if (spec.scalar != "mpfr")
        throw CaseError(file, where, "precision-leak runs the case again at twice its digits: it needs \"scalar\": "
                                     "\"mpfr\", not \"" + spec.scalar + "\"");
      if (2 * spec.digits > maximum_digits)
        throw CaseError(file, where, "precision-leak runs the case again at twice its digits, and digits " +
                                         std::to_string(spec.digits) + " would make that more than " +
                                         std::to_string(maximum_digits));
      if (spec.past_discretization)
        throw CaseError(file, where, "precision-leak measures the local defect of one consistent method, and "
                                     "past_discretization makes a mismatched one");
    }
    if (id == "qxq-tq-equivalence" && (!tq || spec.discretization.tq->lagrangian != "pullback"))
      throw CaseError(file, where, "qxq-tq-equivalence needs a TQ discretization with lagrangian \"pullback\"");
  }
  if (spec.discretization.formalism == "map") {
    if (spec.past_discretization)
      reader.fail("past_discretization", "a one-step map has no past side: the DEL it would mismatch is not there");
    if (spec.compare_discretization)
      reader.fail("compare_discretization", "the claims that compare two discretizations are not claims about maps");
    if (spec.start != "reference")
      reader.fail("start", "a one-step map starts from the exact initial state (q0, w0); \"momentum\" starts a DEL");
  }
  if (spec.past_discretization && spec.past_discretization->formalism != spec.discretization.formalism)
    reader.fail("past_discretization", "expected the same formalism as discretization");
  if (spec.past_discretization && spec.discretization.formalism == "tq") {
    // A mismatched TQ pair is measured only where it is a negative control.
    for (const auto& id : spec.claims)
      if (id != "past-future-symmetry" && id != "twin-term-invariance" && id != "contact-order" &&
          id != "qxq-tq-equivalence")
        reader.fail("past_discretization", "a TQ past_discretization is used by past-future-symmetry, "
                                           "twin-term-invariance, contact-order and qxq-tq-equivalence only "
                                           "(as their negative controls), not by " + id);
    if (fraction_value(spec.past_discretization->tq->theta) != fraction_value(spec.discretization.tq->theta))
      reader.fail("past_discretization", "expected the same theta as discretization");
  }
  if (spec.compare_discretization && spec.compare_discretization->formalism != spec.discretization.formalism)
    reader.fail("compare_discretization", "expected the same formalism as discretization");
  if (reader.has("expect")) {
    Reader expect = reader.object("expect");
    for (const auto& id : spec.claims)
      if (expect.has(id))  // order <= 0 predicts no convergence
        spec.expect[id] =
            expect.integer(id, 1, 64,
                           "the exact order the case expects; an order <= 0 predicts no "
                           "convergence, which no claim checks");
    expect.finish();  // an expectation for a claim the case does not check is an error
  }
  if (reader.has("xfail")) {
    Reader xfail = reader.object("xfail");
    for (const auto& id : spec.claims) {
      if (!xfail.has(id)) continue;
      // "reason", or {"reason": "...", "observed_order": ["low", "high"]}: the failure it expects.
      ExpectedFailure expected;
      if (xfail.get(id).is_object()) {
        Reader entry = xfail.object(id);
        expected.reason = entry.string("reason");
        if (entry.has("observed_order")) {
          const std::vector<std::string> range = entry.decimals("observed_order", 2);
          for (const auto& end : range)
            if (!(std::fabs(*decimal_value_of(end)) <= 1000))
              entry.fail("observed_order",
                         "expected orders in [-1000, 1000], got \"" + echo(end) + "\"");
          if (!(*decimal_value_of(range[0]) <= *decimal_value_of(range[1])))
            entry.fail("observed_order", "expected [low, high] with low <= high, got [\"" +
                                             echo(range[0]) + "\", \"" + echo(range[1]) + "\"]");
          expected.observed_order = std::make_pair(range[0], range[1]);
        }
        entry.finish();
      } else if (xfail.get(id).is_string()) {
        expected.reason = xfail.string(id);
      } else {
        xfail.fail(id,
                   "expected the reason the claim is known to fail, or {\"reason\": \"...\", "
                   "\"observed_order\": "
                   "[\"low\", \"high\"]}, got " +
                       echo(xfail.get(id)));
      }
      if (expected.reason.find_first_not_of(" \t\n") == std::string::npos)
        xfail.fail(id, "expected the reason the claim is known to fail, got an empty string");
      spec.xfail[id] = expected;
    }
    xfail.finish();  // an expected failure of a claim the case does not check is an error
  }
  if (reader.has("refine")) {
    const auto& refine = reader.get("refine");
    if (!refine.is_boolean()) reader.fail("refine", "expected true or false, got " + refine.dump());
    spec.refine = refine.get<bool>();
  }
  reader.finish();
  spec.decimals = reader.decimals();
  check_precision_options(spec, std::nullopt, std::nullopt);
  return spec;
}

nlohmann::json parse_json_strictly(std::istream& in, const std::string& where) {
  // Depth limit and duplicate keys, from the parser's events: one set of keys per open object.
  std::vector<std::set<std::string>> open_objects;
  auto strict = [&](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using event_t = nlohmann::json::parse_event_t;
    if (depth > maximum_json_depth)
      throw CaseError(where, "", "nested deeper than " + std::to_string(maximum_json_depth) + " levels");
    if (event == event_t::object_start) open_objects.emplace_back();
    if (event == event_t::object_end && !open_objects.empty()) open_objects.pop_back();
    if (event == event_t::key && !open_objects.empty() &&
        !open_objects.back().insert(parsed.get<std::string>()).second)
      throw CaseError(where, parsed.get<std::string>(), "the key occurs twice in one object");
    return true;
  };
  try {
    return nlohmann::json::parse(in, strict);
  } catch (const nlohmann::json::parse_error& error) {
    throw CaseError(where, "", std::string("not valid JSON: ") + error.what());
  }
}

CaseSpec read_case_file(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw CaseError(path, "", std::filesystem::exists(path, error) ? "not a regular file (a directory?)"
                                                                   : "cannot open the case file: no such file");
  std::ifstream in(path);
  if (!in) throw CaseError(path, "", "cannot open the case file");
  return parse_case(parse_json_strictly(in, path), path);
}

void check_precision_options(const CaseSpec& spec, const std::optional<std::string>& scalar,
                             std::optional<int> digits) {
  const std::string effective = scalar ? *scalar : spec.scalar;
  const std::string option = scalar ? "--scalar " + effective : "\"scalar\": \"" + effective + "\"";
  if (digits && effective != "mpfr")
    throw CaseError(spec.file, "--digits",
                    "sets the MPFR working precision, and this case runs in \"" + effective +
                        "\" (" + option + ")");
  if (effective != "mpfr" && spec.dimension > 2)
    throw CaseError(spec.file, "--scalar",
                    "a system of " + std::to_string(spec.dimension) +
                        " coordinates runs in mpfr only, not in " + option +
                        " (double, long double and float128 are built for 1 and 2 coordinates)");
  // double is the one scalar whose range is narrower than what a case file may write (about
  // 1e±4900; long double and float128 reach 1e±4932): "1e400" once gave only "vivv: stod".
  if (effective == "double")
    for (const auto& [field, text] : spec.decimals) {
      const long double value = decimal_value_of(text).value_or(0);
      const long double size = value < 0 ? -value : value;
      if (size > std::numeric_limits<double>::max() ||
          (size != 0 && size < std::numeric_limits<double>::denorm_min()))
        throw CaseError(
            spec.file, field,
            "\"" + echo(text) + "\" is out of range for double (" + option +
                "): its magnitude must lie between 4.9e-324 and 1.8e308, or be 0; long double, "
                "float128 and mpfr reach about 1e±4900");
    }
  const bool leak =
      std::find(spec.claims.begin(), spec.claims.end(), "precision-leak") != spec.claims.end();
  if (leak && effective != "mpfr")
    throw CaseError(
        spec.file, "--scalar",
        "precision-leak runs the case again at twice its digits: it needs mpfr, not " + option);
  if (leak && digits && 2 * *digits > maximum_digits)
    throw CaseError(spec.file, "--digits",
                    "precision-leak runs the case again at twice its digits, and --digits " +
                        std::to_string(*digits) + " would make that more than " +
                        std::to_string(maximum_digits));
}

}  // namespace vivv
