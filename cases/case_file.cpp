#include "cases/case_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "cases/case_reader.hpp"
#include "cases/case_sections.hpp"
#include "cases/catalogue.hpp"
#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/maps/odeint_map.hpp"
#include "core/maps/user_map.hpp"
#include "core/platform/text.hpp"
#include "core/qxq/discrete_lagrangian.hpp"

// The top level of a case file and the checks across its sections; the reader and the longer
// sections are cases/case_reader.hpp and cases/case_sections.hpp.
namespace vivv {

using namespace case_reading;

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

// The names a formula reads: plain names and indexed families (m in m[i]).
void collect_names(const FormulaNode& node, std::set<std::string>& names) {
  if (node.kind == FormulaNode::Kind::name || node.kind == FormulaNode::Kind::component) names.insert(node.text);
  for (const FormulaNode& operand : node.operands) collect_names(operand, names);
}

// A formula system's parameter that L, its symmetry and L_d never name computes nothing: a
// warning, naming it (a family once, by its name).
void warn_of_unused_parameters(CaseSpec& spec) {
  if (!spec.formula || spec.formula->recorded) return;
  std::set<std::string> used;
  collect_names(spec.formula->lagrangian, used);
  for (const FormulaNode& component : spec.formula->symmetry) collect_names(component, used);
  if (spec.discretization.expression_tree) collect_names(*spec.discretization.expression_tree, used);
  std::set<std::string> warned;
  for (const auto& [name, value] : spec.parameters) {
    const std::string base = name.substr(0, name.find('['));
    if (used.count(base) || !warned.insert(base).second) continue;
    spec.warnings.push_back(
        "system.params." + base + ": L never uses this parameter" +
        (spec.discretization.expression_tree ? std::string(" (nor L_d, nor the symmetry)") : std::string(" (nor the symmetry)")) +
        (spec.discretization.kind == "process" ? "; the program receives it in its greeting, vivv computes nothing with it"
                                               : ": is it misspelt, or does L name another?"));
  }
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
  spec.q = initial.numbers("q", spec.dimension);
  spec.w = initial.numbers("w", spec.dimension);
  initial.finish();
  // "t0": the time of the initial state, which an L that depends on time reads.
  if (reader.has("t0")) {
    spec.start_time = reader.number("t0");
    if (!(spec.formula && spec.formula->time_dependent))
      reader.fail("t0", "is the initial time of a Lagrangian that depends on time, and this one does not (its "
                        "formula does not use the time" +
                            std::string(spec.formula && !spec.formula->time_name.empty()
                                            ? " '" + spec.formula->time_name + "'"
                                            : "") +
                            "): leave t0 out");
  }
  // The recording of L is held within the memory limit while it is read (record_within_limits);
  // checking the initial state needs no more (sparse, cases/system_section.cpp). What the case
  // will hold in its scalar is estimated once the rest of it is read (check_memory, below).
  check_initial_state(spec, file);

  spec.final_time = reader.number("T");
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
  if (reader.has("digits")) {
    if (spec.scalar != "mpfr")
      reader.fail("digits", "sets the MPFR working precision, and this case runs in \"" + spec.scalar + "\"");
    spec.digits = reader.integer(
        "digits", 20, maximum_digits,
        "MPFR's working precision in decimal digits: below 20 it is no more precise than "
        "long double; at 1000 the paper example's midpoint case takes 3 min and at 2000 "
        "its reference flow alone took 11 min");
  }
  // The time's name in an L_d expression, for an L that depends on time (empty: none).
  const std::string time_name = spec.formula && spec.formula->time_dependent ? spec.formula->time_name : "";
  spec.discretization = read_discretization(reader.object("discretization"), spec.dimension, spec.parameters, true, time_name);
  // A program that computes in double is judged in double: "scalar" need not repeat what
  // "precision" says (another scalar, written or given as --scalar, is refused by
  // check_precision_options, naming the field).
  if (spec.discretization.process_precision == "double" && !reader.has("scalar")) spec.scalar = "double";
  if (reader.has("past_discretization"))
    spec.past_discretization =
        read_discretization(reader.object("past_discretization"), spec.dimension, spec.parameters, true, time_name);
  if (reader.has("compare_discretization"))
    spec.compare_discretization =
        read_discretization(reader.object("compare_discretization"), spec.dimension, spec.parameters, true, time_name);
  // An L that depends on time runs through Q × Q discrete Lagrangians, which evaluate it at their
  // points' times, and their DEL, or through a program's map, whose requests carry the time; a TQ
  // discretization and a map registered in C++ do not take the time.
  if (!time_name.empty()) {
    const auto timed = [&](const DiscretizationSpec& d, const std::string& field) {
      const std::string depends = "this case's Lagrangian depends on time (its formula uses '" + time_name + "'), ";
      if (d.formalism != "qxq" && d.kind != "process")
        reader.fail(field, depends + "which vivv checks through a Q×Q discrete Lagrangian (a rule, galerkin or an "
                                     "expression) and its DEL, or through a program's map (kind \"process\", whose "
                                     "requests carry the time): a " +
                               (d.formalism == "tq" ? std::string("TQ discretization") : "one-step map (kind \"" + d.kind + "\")") +
                               " does not take the time");
      if (d.recorded)
        reader.fail(field, depends + "and an L_d registered as C++ code calls L(x, v) without a time: write it as an "
                                     "expression, whose L(x, v, s) takes one");
    };
    timed(spec.discretization, "discretization");
    if (spec.past_discretization) timed(*spec.past_discretization, "past_discretization");
    if (spec.compare_discretization) timed(*spec.compare_discretization, "compare_discretization");
  }
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
  // "comment": the case's own words — where its data come from — for its readers; vivv keeps none of it.
  if (reader.has("comment") && utf8_characters(reader.string("comment")) > 4000)
    reader.fail("comment", "expected a text of at most 4000 characters, got " +
                               std::to_string(utf8_characters(reader.string("comment"))));

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
    // A claim that does not apply refuses itself only (harness/claims/modified_energy.hpp); a
    // case with nothing else to judge is refused here, before its reference flow is computed.
    if (id == "modified-energy" && spec.claims.size() == 1)
      if (const std::string why = modified_energy_inapplicable(spec); !why.empty())
        throw CaseError(file, where, why);
    if (id == "precision-leak") {
      if (!spec.discretization.process_precision.empty())
        throw CaseError(file, where, "precision-leak runs the program again at twice the digits, and "
                                     "discretization.precision \"" + spec.discretization.process_precision +
                                     "\" says it computes in double only: leave precision-leak out, or run a "
                                     "program that computes with the digits it is asked for");
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
  spec.written = reader.written();
  warn_of_unused_parameters(spec);
  // What the run will hold depends on its discretizations, claims and steps, all read by now.
  check_memory(spec, file, spec.scalar, spec.digits);
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
  if (scalar || digits) check_memory(spec, spec.file, effective, digits ? *digits : spec.digits);
  if (digits && effective != "mpfr")
    throw CaseError(spec.file, "--digits",
                    "sets the MPFR working precision, and this case runs in \"" + effective +
                        "\" (" + option + ")");
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
  if (spec.discretization.process_precision == "double" && effective != "double")
    throw CaseError(spec.file, scalar ? "--scalar" : "scalar",
                    "discretization.precision \"double\" says the program computes in double, so the "
                    "case runs in double, not in " + option);
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

std::string modified_energy_inapplicable(const CaseSpec& spec) {
  const DiscretizationSpec& d = spec.discretization;
  if (d.formalism == "tq" || ((d.kind == "midpoint" || d.kind == "trapezoid") && !d.twin)) return "";
  return "modified-energy is derived for the midpoint and trapezoid rules without twin terms, not for "
         "discretization.kind \"" + d.kind + "\"" + (d.twin ? " with a twin term" : "");
}

}  // namespace vivv
