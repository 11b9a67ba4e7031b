// The user's test suite: vivv's claims on the user's own integrator, as GoogleTest assertions.
#include "split_kick.hpp"

#include <sstream>
#include <stdexcept>
#include <vivv/gtest.hpp>
#include <vivv/vivv.hpp>

#include "quartic.hpp"

namespace {

const std::string cases = CASES_DIR;

class SplitKickTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    vivv::register_map<SplitKick<TenthWeights>>("split-kick", 2);
    vivv::register_map<SplitKick<TenthLiteralWeights>>("split-kick-literal", 2);
    vivv::register_system<QuarticOscillator>("quartic-oscillator");
    vivv::register_discrete_lagrangian<GaussTwoLine>("gauss-two-line", 2);
  }
};

std::string verdict_of(const vivv::Run& run, const std::string& claim) {
  for (const auto& result : run.results)
    for (const auto& c : result.claims)
      if (c.id == claim) return c.verdict;
  return "missing";
}

// Weights computed in the scalar: order 2, symplectic, bounded energy, no precision leak.
TEST_F(SplitKickTest, HoldsItsOrderAndStructureAndLeaksNoPrecision) {
  const vivv::Run run = vivv::run({cases + "/split-kick-pendulum.json"});
  EXPECT_TRUE(vivv::check(run));
  EXPECT_EQ(verdict_of(run, "precision-leak"), "pass");
  EXPECT_EQ(vivv::write_reports(run, "report-split-kick").size(),
            4u);  // report.json, report.html, junit.xml, report.csv
}

// The double literal 0.1: order and symplecticity still hold at the case's steps,
// and precision-leak flags what the literal lost (the case marks it xfail, so check holds).
TEST_F(SplitKickTest, ADoubleLiteralIsFlaggedAsAPrecisionLeak) {
  const vivv::Run run = vivv::run({cases + "/split-kick-literal-pendulum.json"});
  EXPECT_TRUE(vivv::check(run));
  EXPECT_EQ(verdict_of(run, "global-order"), "pass");
  EXPECT_EQ(verdict_of(run, "symplecticity"), "pass");
  EXPECT_EQ(verdict_of(run, "precision-leak"), "xfail");
  EXPECT_EQ(vivv::write_reports(run, "report-split-kick-literal").size(),
            4u);  // report.json, report.html, junit.xml, report.csv
  for (const auto& claim : run.results.front().claims)
    if (claim.id == "precision-leak") {
      EXPECT_NE(claim.explanation.find("bits"), std::string::npos) << claim.explanation;
    }
}

// The user's own system and discrete Lagrangian: the Q×Q claims hold in MPFR, order and
// symplecticity in float128; the user's map runs on the user's system in double, and over a
// T of many periods its energy error stays bounded (energy-behaviour needs 4 returns of the
// motion: the short cases do not name it).
TEST_F(SplitKickTest, AUserRuleOnAUserSystemKeepsItsPromises) {
  const vivv::Run run = vivv::run({cases + "/gauss-two-line-quartic.json",
                                   cases + "/gauss-two-line-quartic-float128.json",
                                   cases + "/split-kick-quartic-double.json",
                                   cases + "/split-kick-quartic-energy-double.json"});
  EXPECT_TRUE(vivv::check(run));
  ASSERT_EQ(run.results.size(), 4u);
  EXPECT_EQ(run.results[0].claims.size(), 4u);
  EXPECT_EQ(run.results[1].scalar, "float128");
  EXPECT_EQ(run.results[2].scalar, "double");
  EXPECT_EQ(verdict_of(run, "energy-behaviour"), "pass");
  EXPECT_EQ(vivv::write_reports(run, "report-user-types").size(),
            4u);  // report.json, report.html, junit.xml, report.csv
}

// Registering again is harmless: the same method under its name does nothing; another type
// under a taken name is refused.
TEST_F(SplitKickTest, RegisteringTheSameMethodAgainIsHarmless) {
  EXPECT_NO_THROW(vivv::register_map<SplitKick<TenthWeights>>("split-kick", 2));
  EXPECT_NO_THROW(vivv::register_system<QuarticOscillator>("quartic-oscillator"));
  EXPECT_THROW(vivv::register_map<SplitKick<TenthLiteralWeights>>("split-kick", 2),
               std::invalid_argument);
  EXPECT_THROW(vivv::register_map<SplitKick<TenthWeights>>("split-kick", 4), std::invalid_argument);
}

// The options of vivv run: two cases in two worker processes; the report holds both, in their
// order, and the console table prints them. A scalar override a case cannot take is refused
// before anything runs.
TEST_F(SplitKickTest, RunsWithTheOptionsOfTheCommandLine) {
  vivv::RunOptions options;
  options.jobs = 2;
  options.max_seconds = 300;
  const vivv::Run run = vivv::run(
      {cases + "/split-kick-quartic-double.json", cases + "/gauss-two-line-quartic-float128.json"},
      options);
  EXPECT_TRUE(vivv::check(run));
  EXPECT_TRUE(run.results.empty());
  ASSERT_EQ(run.report["cases"].size(), 2u);
  EXPECT_EQ(run.report.at("cases").at(0).at("precision").at("scalar"), "double");
  EXPECT_EQ(run.report.at("cases").at(1).at("precision").at("scalar"), "float128");
  options.scalar = "double";
  EXPECT_THROW(vivv::run({cases + "/gauss-two-line-quartic.json"}, options), vivv::CaseError);
  std::ostringstream table;
  vivv::print_table(table, run);
  EXPECT_NE(table.str().find("split-kick-quartic-double"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("claims: "), std::string::npos) << table.str();
}

// A case naming a map nobody registered is bad input.
TEST_F(SplitKickTest, AnUnregisteredMapIsBadInput) {
  EXPECT_THROW(vivv::run({cases + "/unregistered-map.json"}), vivv::CaseError);
}

}  // namespace
