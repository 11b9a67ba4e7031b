// Every claim on a case where it must hold and on a broken input where it
// must fail (its negative control), in double, quad and MPFR.
#include "harness/claims.hpp"

#include <functional>

#include "cases/catalogue.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

template <class T>
class ClaimsTest : public testing::ScalarTest<T> {
 protected:
  // The verdict of `claim` on the case `json` (a case file without the boilerplate).
  // `tamper(context)` may break the case after it is built (negative controls).
  std::string verdict(const std::string& claim, nlohmann::json json,
                      const std::function<void(TQDiscretization<T>&)>& tamper = {}) {
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
      if (tamper && context.tq) tamper(*context.tq);
      ClaimResult result = evaluate_claim(claim, context);
      return result.verdict + ": " + result.explanation;
    });
  }
};
TYPED_TEST_SUITE(ClaimsTest, testing::Scalars, testing::ScalarNames);

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

const nlohmann::json tq_left_rectangle = {{"formalism", "tq"},  {"psi", "linear"},
                                           {"theta", "0"},       {"lagrangian", "pullback"},
                                           {"qxq", left_rectangle}};
const nlohmann::json tq_midpoint_quadrature = {{"formalism", "tq"}, {"psi", "linear"},
                                               {"theta", "1/2"},    {"lagrangian", "quadrature"},
                                               {"nodes", 3}};

// Theorem 5.5 on the paper's example in TQ form: local error O(h^2) for the
// order-1 discretization; an order-1 psi declared order 2 is rejected.
TYPED_TEST(ClaimsTest, LocalOrderOfTheLinearDiscretizationAndItsNegativeControl) {
  EXPECT_EQ(this->verdict("order", {{"system", paper}, {"discretization", tq_left_rectangle},
                                    {"expect", {{"order", 2}}}})
                .substr(0, 4),
            "pass");
  EXPECT_EQ(this->verdict("order", {{"system", paper}, {"discretization", tq_left_rectangle},
                                    {"expect", {{"order", 3}}}})
                .substr(0, 4),
            "fail");
}

// Lemma 6.1, and its negative control: a TQ evolution compared with the DEL
// of a different Q×Q discrete Lagrangian (a sign slip in the twin term).
TYPED_TEST(ClaimsTest, QxQTQEquivalenceHoldsForPullbacksAndRejectsAnotherLagrangian) {
  using T = TypeParam;
  nlohmann::json json = {{"system", paper}, {"discretization", tq_left_rectangle}, {"steps", {8, 16, 32}}};
  EXPECT_EQ(this->verdict("qxq-tq-equivalence", json).substr(0, 4), "pass");
  // The TQ side uses the midpoint rule while the DEL keeps the left rectangle.
  EXPECT_EQ(this->verdict("qxq-tq-equivalence", json,
                          [](TQDiscretization<T>& d) {
                            d.lagrangian = TQLagrangianKind::quadrature;
                            d.nodes = {T(1) / 2};
                            d.weights = {T(1)};
                          })
                .substr(0, 4),
            "fail");
}

TYPED_TEST(ClaimsTest, ExistenceUniquenessHasPositiveStepsAtEverySpeed) {
  using T = TypeParam;
  nlohmann::json json = {{"system", paper}, {"discretization", tq_midpoint_quadrature}};
  EXPECT_EQ(this->verdict("existence-uniqueness", json).substr(0, 4), "pass");
  // Negative control: a zero-length interval (θ shifted so α+ = α− is impossible;
  // here every node weight vanishes) makes L_h ≡ 0 and the principle degenerate.
  EXPECT_EQ(this->verdict("existence-uniqueness", json,
                          [](TQDiscretization<T>& d) {
                            for (auto& weight : d.weights) weight = 0;
                          })
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
