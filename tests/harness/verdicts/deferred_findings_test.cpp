// An order defect precision-leak defers to local-order reaches a verdict (docs/claims.md,
// "Evidence of a defect never passes"): precision-leak fails when local-order is not run, and
// local-order fails on it when its own steps did not reach the defect.
#include "harness/verdicts/deferred_findings.hpp"

#include <gtest/gtest.h>

namespace vivv {
namespace {

ClaimResult claim(const std::string& id, const std::string& verdict, bool order_defect = false) {
  ClaimResult result;
  result.id = id;
  result.verdict = verdict;
  result.explanation = id + " explained";
  if (order_defect) result.evidence["order_defect"] = true;
  return result;
}

TEST(DeferredFindings, AnOrderDefectFailsPrecisionLeakWhenLocalOrderIsNotRun) {
  std::vector<ClaimResult> claims{claim("global-order", "pass"), claim("precision-leak", "pass", true)};
  settle_deferred_findings(claims);
  EXPECT_EQ(claims[0].verdict, "pass");
  EXPECT_EQ(claims[1].verdict, "fail");
  EXPECT_NE(claims[1].explanation.find("local-order, which judges it, is not among the claims run"),
            std::string::npos)
      << claims[1].explanation;
}

TEST(DeferredFindings, LocalOrderThatDidNotReachTheDefectFailsOnIt) {
  std::vector<ClaimResult> claims{claim("local-order", "pass"), claim("precision-leak", "pass", true)};
  settle_deferred_findings(claims);
  EXPECT_EQ(claims[0].verdict, "fail");
  EXPECT_NE(claims[0].explanation.find("precision-leak explained"), std::string::npos) << claims[0].explanation;
  EXPECT_EQ(claims[1].verdict, "pass");  // deferred to a claim that judged it
}

TEST(DeferredFindings, NothingChangesWithoutAnOrderDefectOrWhenLocalOrderFailedAlready) {
  std::vector<ClaimResult> clean{claim("precision-leak", "pass")};
  settle_deferred_findings(clean);
  EXPECT_EQ(clean[0].verdict, "pass");
  std::vector<ClaimResult> judged{claim("local-order", "fail"), claim("precision-leak", "pass", true)};
  settle_deferred_findings(judged);
  EXPECT_EQ(judged[0].verdict, "fail");
  EXPECT_EQ(judged[0].explanation, "local-order explained");
  EXPECT_EQ(judged[1].verdict, "pass");
  std::vector<ClaimResult> leak{claim("precision-leak", "fail", true)};
  settle_deferred_findings(leak);
  EXPECT_EQ(leak[0].explanation, "precision-leak explained");
}

}  // namespace
}  // namespace vivv
