// Every claim on a case where it must hold and on a broken input where it
// must fail (its negative control), in double, quad and MPFR.
#include "harness/claims.hpp"

#include "cases/catalogue.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

template <class T>
class ClaimsTest : public testing::ScalarTest<T> {
 protected:
  // The verdict of `claim` on the case `json` (a case file without the boilerplate).
  std::string verdict(const std::string& claim, nlohmann::json json) {
    json["name"] = "test";
    json["T"] = "2";
    if (!json.contains("steps")) json["steps"] = {32, 64, 128, 256};
    json["claims"] = {claim};
    if (!json.contains("initial")) json["initial"] = {{"q", {"0.5"}}, {"w", {"0.75"}}};
    CaseSpec spec = parse_case(json, "test.json");
    std::vector<std::string> parameters;
    for (const auto& [name, value] : spec.parameters) parameters.push_back(value);
    return visit_system<T>(spec.system, parameters, [&](auto system) {
      CaseContext context(spec, system, {});
      ClaimResult result = evaluate_claim(claim, context);
      return result.verdict + ": " + result.explanation;
    });
  }
};
TYPED_TEST_SUITE(ClaimsTest, testing::Scalars);

const nlohmann::json paper = {{"name", "paper_example"}};
const nlohmann::json left_rectangle = {{"kind", "left-rectangle"}};
const nlohmann::json left_rectangle_twin = {{"kind", "left-rectangle"},
                                            {"twin", {{"a", {"1"}}, {"power", 1}}}};
const nlohmann::json midpoint = {{"kind", "midpoint"}};
const nlohmann::json wrong_weight = {{"kind", "weighted"}, {"beta", "0.6"}};

TYPED_TEST(ClaimsTest, GlobalOrderHoldsForMidpointAndRejectsAWrongQuadratureWeight) {
  EXPECT_EQ(this->verdict("global-order", {{"system", paper}, {"discretization", midpoint},
                                           {"expect", {{"global-order", 2}}}})
                .substr(0, 4),
            "pass");
  EXPECT_EQ(this->verdict("global-order", {{"system", paper}, {"discretization", wrong_weight},
                                           {"expect", {{"global-order", 2}}}})
                .substr(0, 4),
            "fail");
}

TYPED_TEST(ClaimsTest, LagrangianOrderHoldsForMidpointAndRejectsAWrongQuadratureWeight) {
  EXPECT_EQ(this->verdict("lagrangian-order", {{"system", paper}, {"discretization", midpoint}}).substr(0, 4),
            "pass");
  EXPECT_EQ(this->verdict("lagrangian-order", {{"system", paper}, {"discretization", wrong_weight},
                                               {"expect", {{"lagrangian-order", 3}}}})
                .substr(0, 4),
            "fail");
}

// The paper's correction of Marsden–West Thm 2.3.1 (2): order r, not r + 1.
TYPED_TEST(ClaimsTest, LegendreOrderIsROnTheExampleAndMarsdenWestsRPlusOneIsRejected) {
  EXPECT_EQ(this->verdict("legendre-order", {{"system", paper}, {"discretization", left_rectangle_twin}})
                .substr(0, 4),
            "pass");
  EXPECT_EQ(this->verdict("legendre-order", {{"system", paper}, {"discretization", left_rectangle_twin},
                                             {"expect", {{"legendre-order", 2}}}})
                .substr(0, 4),
            "fail");
}

TYPED_TEST(ClaimsTest, TwinTermCancelsInTheDelButNotInAMismatchedOne) {
  EXPECT_EQ(this->verdict("twin-term-invariance", {{"system", paper}, {"discretization", left_rectangle_twin}})
                .substr(0, 4),
            "pass");
  EXPECT_EQ(this->verdict("twin-term-invariance", {{"system", paper},
                                                   {"discretization", left_rectangle_twin},
                                                   {"past_discretization", left_rectangle}})
                .substr(0, 4),
            "fail");
}

TYPED_TEST(ClaimsTest, MismatchedTwinsAreInconsistentAndAMatchedPairIsNot) {
  EXPECT_EQ(this->verdict("mismatched-legendre", {{"system", paper},
                                                  {"discretization", left_rectangle_twin},
                                                  {"past_discretization", left_rectangle}})
                .substr(0, 4),
            "pass");
  EXPECT_EQ(this->verdict("mismatched-legendre", {{"system", paper},
                                                  {"discretization", left_rectangle_twin},
                                                  {"past_discretization", left_rectangle_twin}})
                .substr(0, 4),
            "fail");
}

TEST(ClaimRegistry, EveryClaimACaseMayNameIsRegistered) {
  std::vector<std::string> registered;
  for (const auto& claim : registered_claims()) registered.push_back(claim.id);
  EXPECT_EQ(registered, claim_ids());
}

}  // namespace
}  // namespace vivv
