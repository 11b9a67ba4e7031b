// A case runs in the scalar it names: every claim of a small Q×Q case and a
// small TQ case, a formula system and a catalogue one, in double, long double,
// float128 and MPFR. The report says which scalar and how many bits, and the
// floor below which errors are round-off follows the scalar.
#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "cases/case_file.hpp"
#include "harness/run/run_case.hpp"

namespace vivv {
namespace {


CaseSpec case_in(const std::string& scalar, nlohmann::json system, nlohmann::json discretization,
                 std::vector<std::string> claims, const nlohmann::json& more = nlohmann::json::object()) {
  nlohmann::json json = {{"name", "scalar-case"},
                         {"system", std::move(system)},
                         {"initial", {{"q", {"1"}}, {"w", {"0.5"}}}},
                         {"T", "1"},
                         {"steps", {8, 16, 32, 64}},
                         {"scalar", scalar},
                         {"discretization", std::move(discretization)},
                         {"claims", claims}};
  json.update(more);
  return parse_case(json, "scalar-case.json");
}

const nlohmann::json pendulum_formula = {{"name", "pendulum-formula"},
                                         {"lagrangian", "w^2/2 - k*(1 - cos(q))"},
                                         {"coordinates", {"q"}},
                                         {"velocities", {"w"}},
                                         {"params", {{"k", "1"}}}};

int expected_bits(const std::string& scalar) {
  if (scalar == "double") return 53;
  if (scalar == "long double") return 64;
  if (scalar == "float128") return 113;
  PrecisionGuard guard(60);  // the default digits
  return precision_bits<mpfr_real>();
}

class RunCaseScalarTest : public ::testing::TestWithParam<std::string> {};

TEST_P(RunCaseScalarTest, EveryClaimOfAFormulaCaseRunsAndHolds) {
  const std::string scalar = GetParam();
  const nlohmann::json midpoint = {{"kind", "expression"}, {"L_d", "h*L((qb + qe)/2, (qe - qb)/h)"}, {"order", 2}};
  const nlohmann::json tq_midpoint = {{"formalism", "tq"}, {"psi", "linear"}, {"theta", "1/2"},
                                      {"lagrangian", "quadrature"}, {"nodes", 1}};
  const nlohmann::json tq_taylor = {{"formalism", "tq"}, {"psi", "taylor"}, {"r", 2}, {"theta", "1/2"},
                                    {"lagrangian", "quadrature"}, {"nodes", 2}};
  nlohmann::json twinned = midpoint;
  twinned["twin"] = {{"a", {"1"}}, {"power", 3}};
  const std::vector<std::tuple<nlohmann::json, std::vector<std::string>, nlohmann::json>> more = {
      {midpoint, {"mismatched-legendre"}, {{"past_discretization", twinned}}},
      {tq_midpoint, {"contact-order", "past-future-symmetry"}, {{"compare_discretization", tq_taylor}}},
      {{{"formalism", "tq"}, {"psi", "exact"}, {"theta", "1/2"}, {"lagrangian", "exact"}}, {"exact-discretization"}, nlohmann::json::object()},
  };
  for (const auto& [discretization, claims, extra] : more) {
    CaseResult result =
        run_case(case_in(scalar, pendulum_formula, discretization, claims, extra), std::nullopt, false, {});
    ASSERT_EQ(result.claims.size(), claims.size()) << scalar;
    for (const auto& claim : result.claims) EXPECT_EQ(claim.verdict, "pass") << scalar << ": " << claim.id << ": " << claim.explanation;
  }
  const std::vector<std::pair<nlohmann::json, std::vector<std::string>>> cases = {
      {{{"kind", "expression"}, {"L_d", "h*L((qb + qe)/2, (qe - qb)/h)"}, {"order", 2}, {"twin", {{"a", {"0.5"}}, {"power", 2}}}},
       {"global-order", "lagrangian-order", "legendre-order", "twin-term-invariance"}},
      {{{"formalism", "tq"}, {"psi", "linear"}, {"theta", "1/2"}, {"lagrangian", "pullback"},
        {"qxq", {{"kind", "expression"}, {"L_d", "h*L((qb + qe)/2, (qe - qb)/h)"}, {"order", 2}}}},
       {"order", "global-order", "qxq-tq-equivalence", "existence-uniqueness"}},
  };
  for (const auto& [discretization, claims] : cases) {
    CaseResult result = run_case(case_in(scalar, pendulum_formula, discretization, claims), std::nullopt, false, {});
    EXPECT_EQ(result.scalar, scalar);
    EXPECT_EQ(result.precision_bits, expected_bits(scalar));
    EXPECT_EQ(result.implementation, "formula");
    ASSERT_EQ(result.claims.size(), claims.size()) << scalar;
    for (const auto& claim : result.claims) EXPECT_EQ(claim.verdict, "pass") << scalar << ": " << claim.id << ": " << claim.explanation;
  }
}

// The structure claims on a catalogue system with a symmetry (outside MPFR its formula twin,
// which declares the same generator): symplectic, momentum map and energy, in every scalar; T
// holds 7 orbits, so that energy-behaviour sees the 4 returns it needs.
TEST_P(RunCaseScalarTest, StructureClaimsRunAndHoldOnKepler) {
  const std::string scalar = GetParam();
  const std::vector<std::string> claims = {"symplecticity", "discrete-noether", "energy-behaviour"};
  CaseResult result = run_case(case_in(scalar, {{"name", "kepler"}}, {{"kind", "midpoint"}}, claims,
                                       {{"initial", {{"q", {"0.5", "0"}}, {"w", {"0", "1.5"}}}},
                                        {"T", "20"},
                                        {"steps", {250, 500, 1000}}}),
                               std::nullopt, false, {});
  ASSERT_EQ(result.claims.size(), claims.size()) << scalar;
  for (const auto& claim : result.claims) EXPECT_EQ(claim.verdict, "pass") << scalar << ": " << claim.id << ": " << claim.explanation;
}

// A catalogue system runs through its formula twin in every scalar; one with a closed-form flow
// takes it as its reference in MPFR (chosen at run time), every other one, and every system outside
// MPFR, the Taylor flow. Each says how it ran.
TEST_P(RunCaseScalarTest, ACatalogueSystemSaysHowItRan) {
  const std::string scalar = GetParam();
  CaseResult result =
      run_case(case_in(scalar, {{"name", "pendulum"}}, {{"kind", "midpoint"}}, {"global-order"}), std::nullopt, false, {});
  EXPECT_EQ(result.claims.at(0).verdict, "pass") << result.claims.at(0).explanation;
  EXPECT_EQ(result.implementation, "formula twin of the catalogue system");
  if (scalar == "mpfr")
    EXPECT_EQ(result.reference_method, "closed form: Jacobi elliptic functions (Boost.Math sn, cn, F)");
  else
    EXPECT_EQ(result.reference_method.rfind("Taylor series", 0), 0u) << result.reference_method;
  CaseResult twin =
      run_case(case_in(scalar, {{"name", "henon_heiles"}}, {{"kind", "midpoint"}}, {"global-order"},
                       {{"initial", {{"q", {"0.1", "0.2"}}, {"w", {"0.3", "0"}}}}}),
               std::nullopt, false, {});
  EXPECT_EQ(twin.claims.at(0).verdict, "pass") << twin.claims.at(0).explanation;
  EXPECT_NE(twin.implementation.find("formula twin"), std::string::npos) << twin.implementation;
  EXPECT_EQ(twin.reference_method.find("closed form"), std::string::npos) << twin.reference_method;
}

INSTANTIATE_TEST_SUITE_P(Scalars, RunCaseScalarTest, ::testing::Values("double", "long double", "float128", "mpfr"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (auto& c : name)
                             if (c == ' ') c = '_';
                           return name;
                         });

// The floor follows the scalar: far above double's round-off in double, far below it in MPFR.
// Negative control of the floors: the same case's floor in double is at least 1e20 times MPFR's.
TEST(RunCaseScalarFloor, FollowsTheScalar) {
  auto floor_of = [](const std::string& scalar) {
    CaseResult result = run_case(case_in(scalar, pendulum_formula, {{"kind", "midpoint"}}, {"global-order"}),
                                 std::nullopt, false, {});
    return std::stold(result.claims.at(0).series.at(0).floor);
  };
  const long double in_double = floor_of("double"), in_mpfr = floor_of("mpfr");
  EXPECT_GT(in_double, 1e-16L);
  EXPECT_LT(in_double, 1e-8L);
  EXPECT_GT(in_double, 1e20L * in_mpfr);
}

}  // namespace
}  // namespace vivv
