#include "cases/case_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "cases/catalogue.hpp"

namespace vivv {
namespace {

nlohmann::json minimal_case() {
  return nlohmann::json::parse(R"({
    "name": "c", "system": {"name": "pendulum", "params": {"k": "2"}},
    "initial": {"q": ["1.1"], "w": ["0"]}, "T": "2", "steps": [16, 32, 64], "digits": 30,
    "discretization": {"kind": "left-rectangle", "twin": {"a": ["1"], "power": 1}},
    "past_discretization": {"kind": "left-rectangle"},
    "claims": ["global-order", "twin-term-invariance"], "expect": {"global-order": 1}})");
}

// The field a CaseError names, or "" when parsing succeeds.
std::string failing_field(const nlohmann::json& json) {
  try {
    parse_case(json, "case.json");
  } catch (const CaseError& error) {
    return error.field;
  }
  return "";
}

TEST(CaseFile, TheIssueExampleParsesWithDefaultsFilledIn) {
  CaseSpec spec = parse_case(minimal_case(), "case.json");
  EXPECT_EQ(spec.system, "pendulum");
  ASSERT_EQ(spec.parameters.size(), 1u);
  EXPECT_EQ(spec.parameters[0].second, "2");
  EXPECT_EQ(spec.steps, (std::vector<int>{16, 32, 64}));
  ASSERT_TRUE(spec.discretization.twin);
  EXPECT_EQ(spec.discretization.twin->a, std::vector<std::string>{"1"});
  EXPECT_TRUE(spec.past_discretization);
  EXPECT_EQ(spec.expect.at("global-order"), 1);
  nlohmann::json defaults = minimal_case();
  defaults["system"].erase("params");
  EXPECT_EQ(parse_case(defaults, "case.json").parameters[0].second, "1");
}

// Each malformed variant must be rejected with the field that is wrong.
TEST(CaseFile, MalformedFieldsAreNamed) {
  struct Row {
    std::string pointer;  // JSON pointer to change
    nlohmann::json value;
    std::string field;    // expected field in the error
  };
  std::vector<Row> rows = {
      {"/system/name", "pendulumm", "system.name"},
      {"/system/params/k", 1, "system.params.k"},
      {"/system/params/omega", "1", "system.params.omega"},
      {"/initial/q", nlohmann::json::array({"1", "2"}), "initial.q"},
      {"/initial/w/0", "fast", "initial.w[0]"},
      {"/T", "-1", "T"},
      {"/T", 2, "T"},
      {"/steps", nlohmann::json::array({16, 32}), "steps"},
      {"/steps/1", 8, "steps"},
      {"/digits", 5, "digits"},
      {"/discretization/kind", "simpson", "discretization.kind"},
      {"/discretization/twin/power", 0, "discretization.twin.power"},
      {"/discretization/twin/a", nlohmann::json::array({"1", "1"}), "discretization.twin.a"},
      {"/discretization/colour", "red", "discretization.colour"},
      {"/claims/0", "energy-drift", "claims[0]"},
      {"/expect/lagrangian-order", 2, "expect.lagrangian-order"},
      {"/start", "guess", "start"},
      {"/unexpected", true, "unexpected"},
  };
  for (const auto& row : rows) {
    nlohmann::json json = minimal_case();
    json[nlohmann::json::json_pointer(row.pointer)] = row.value;
    EXPECT_EQ(failing_field(json), row.field) << row.pointer << " = " << row.value.dump();
  }
  nlohmann::json missing = minimal_case();
  missing.erase("T");
  EXPECT_EQ(failing_field(missing), "T");
  nlohmann::json alpha = minimal_case();
  alpha["discretization"] = {{"kind", "alpha"}};
  EXPECT_EQ(failing_field(alpha), "discretization.alpha");
  nlohmann::json no_twin = minimal_case();
  no_twin["discretization"].erase("twin");
  EXPECT_EQ(failing_field(no_twin), "claims[1]");
}

// The comment's limit counts characters, not the bytes of their UTF-8 ("é" is two).
TEST(CaseFile, CommentLimitCountsCharacters) {
  nlohmann::json json = minimal_case();
  std::string text;
  for (int i = 0; i < 4000; ++i) text += "\u00e9";
  json["comment"] = text;
  EXPECT_EQ(failing_field(json), "");
  json["comment"] = text + "\u00e9";
  EXPECT_EQ(failing_field(json), "comment");
}

// An expression L_d may name a member of a parameter array, as the system's L does (the run
// binds them so; the case reader once refused "m[2]" as "not a vector or an indexed family").
TEST(CaseFile, AnExpressionLdNamesAParameterArraysMembers) {
  nlohmann::json json = nlohmann::json::parse(R"({
    "name": "c", "system": {"name": "two-masses", "coordinates": [{"x": [2]}], "velocities": [{"v": [2]}],
                            "params": {"m": ["1", "2"]},
                            "lagrangian": "sum(i = 1..2, m[i]*v[i]^2)/2 - (x[2] - x[1])^2/2"},
    "initial": {"q": ["0", "1"], "w": ["0.1", "0"]}, "T": "1", "steps": [8, 16, 32],
    "discretization": {"kind": "expression", "order": 2,
                       "L_d": "h*L((qb + qe)/2, (qe - qb)/h) + 0*m[2]*h^3"},
    "claims": ["global-order"]})");
  EXPECT_EQ(failing_field(json), "");
  json["discretization"]["L_d"] = "h*L((qb + qe)/2, (qe - qb)/h) + 0*m[3]*h^3";
  EXPECT_EQ(failing_field(json), "discretization.L_d");
}

// A parameter that neither L, its symmetry nor L_d names is a warning naming it (a family once);
// one that L_d alone names is used; a catalogue system's are never warned of.
TEST(CaseFile, AParameterNothingNamesIsWarnedOf) {
  nlohmann::json json = nlohmann::json::parse(R"json({
    "name": "c", "system": {"name": "two-masses", "coordinates": [{"x": [2]}], "velocities": [{"v": [2]}],
                            "params": {"m": ["1", "2"], "mass": "3", "c": ["1", "1"]},
                            "lagrangian": "sum(i = 1..2, m[i]*v[i]^2)/2 - (x[2] - x[1])^2/2"},
    "initial": {"q": ["0", "1"], "w": ["0.1", "0"]}, "T": "1", "steps": [8, 16, 32],
    "discretization": {"kind": "expression", "order": 2, "L_d": "h*L((qb + qe)/2, (qe - qb)/h)"},
    "claims": ["global-order"]})json");
  CaseSpec spec = parse_case(json, "case.json");
  ASSERT_EQ(spec.warnings.size(), 2u);
  EXPECT_NE(spec.warnings[0].find("system.params.c: L never uses this parameter"), std::string::npos)
      << spec.warnings[0];
  EXPECT_NE(spec.warnings[1].find("system.params.mass: L never uses"), std::string::npos) << spec.warnings[1];
  json["discretization"]["L_d"] = "h*L((qb + qe)/2, (qe - qb)/h) + 0*mass*c[1]*h^3";
  EXPECT_TRUE(parse_case(json, "case.json").warnings.empty());
  EXPECT_TRUE(parse_case(minimal_case(), "case.json").warnings.empty());
}

TEST(CaseFile, EveryDefaultSuiteCaseParses) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(VIVV_SOURCE_DIR) + "/cases/suite")) {
    if (entry.path().extension() != ".json") continue;  // each case's .verdicts beside it
    EXPECT_NO_THROW(read_case_file(entry.path().string())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 10);
}

TEST(CaseFile, CatalogueBuildsEverySystemWithItsDefaults) {
  for (const auto& info : system_catalogue()) {
    std::vector<std::string> defaults;
    for (const auto& p : info.parameters) defaults.push_back(p.default_value);
    int dimension = visit_system<double>(info.name, defaults, [](auto system) { return decltype(system)::dimension; });
    EXPECT_EQ(dimension, info.dimension);
    // Every catalogue system runs through its formula twin (harness/run/run_case.cpp): a system
    // without one could not run.
    std::vector<std::pair<std::string, std::string>> named;
    for (const auto& p : info.parameters) named.emplace_back(p.name, p.default_value);
    EXPECT_EQ(static_cast<int>(catalogue_twin(info.name, named).coordinates.size()), info.dimension) << info.name;
  }
  EXPECT_THROW(visit_system<double>("nonexistent", {}, [](auto) { return 0; }), std::invalid_argument);
}

}  // namespace
}  // namespace vivv
