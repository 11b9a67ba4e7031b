// junit.xml on a small synthetic report: every claim a test case, failing
// claims with a <failure> carrying the explanation and the evidence summary.
#include "reports/junit_report.hpp"
#include "reports/report.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tests/reports/synthetic_report.hpp"

namespace vivv {
namespace {

using testing::count;

TEST(JunitReport, EveryClaimIsATestCase) {
  const std::string xml = render_junit(testing::synthetic_report());
  EXPECT_EQ(count(xml, "<testcase "), 3);
  EXPECT_NE(xml.find("<testcase classname=\"alpha\" name=\"global-order\">"), std::string::npos);
  EXPECT_NE(xml.find("<testcase classname=\"beta\" name=\"twin-term-invariance\">"),
            std::string::npos);
  EXPECT_NE(xml.find("<testsuites name=\"vivv\" tests=\"3\" failures=\"1\" errors=\"0\" skipped=\"0\">"),
            std::string::npos);
  EXPECT_NE(xml.find("<testsuite name=\"alpha\" tests=\"2\" failures=\"1\" errors=\"0\" skipped=\"0\" "
                     "time=\"0.25\">"),
            std::string::npos);
}

// A known failure is skipped with its reason; a known failure that went away (xpass) fails.
TEST(JunitReport, ExpectedFailureIsSkippedAndAnUnexpectedPassFails) {
  nlohmann::json report = testing::synthetic_report();
  auto& claims = report["cases"][0]["claims"];
  claims[1]["verdict"] = "xfail";
  claims[1]["xfail_reason"] = "β ≠ 1/2 <is> order 1";
  claims[0]["verdict"] = "xpass";
  claims[0]["xfail_reason"] = "was broken";
  report["summary"] = verdict_counts(report["cases"]);
  const std::string xml = render_junit(report);
  EXPECT_NE(xml.find("<skipped message=\"xfail: β ≠ 1/2 &lt;is&gt; order 1\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure type=\"xpass\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("tests=\"3\" failures=\"1\" errors=\"0\" skipped=\"1\">"), std::string::npos) << xml;
  EXPECT_FALSE(run_succeeded(report["summary"]));
  claims[0]["verdict"] = "pass";
  report["summary"] = verdict_counts(report["cases"]);
  EXPECT_TRUE(run_succeeded(report["summary"])) << report["summary"];
}

// XML 1.0 has no control characters but tab, newline and carriage return: any other in a
// reason or explanation is replaced, so junit.xml stays well-formed.
TEST(JunitReport, ControlCharactersAreReplaced) {
  nlohmann::json report = testing::synthetic_report();
  report["cases"][0]["claims"][1]["verdict"] = "xfail";
  report["cases"][0]["claims"][1]["xfail_reason"] = std::string("bell\x07 and escape\x1b");
  report["summary"] = verdict_counts(report["cases"]);
  const std::string xml = render_junit(report);
  EXPECT_EQ(xml.find('\x07'), std::string::npos);
  EXPECT_EQ(xml.find('\x1b'), std::string::npos);
  EXPECT_NE(xml.find("bell\xEF\xBF\xBD and escape\xEF\xBF\xBD"), std::string::npos) << xml;
}

TEST(JunitReport, FailingClaimCarriesExplanationAndEvidence) {
  const std::string xml = render_junit(testing::synthetic_report());
  EXPECT_EQ(count(xml, "<failure "), 1);
  std::size_t failure =
      xml.find("<failure type=\"fail\" message=\"the order is too low: 1 &lt; 2\">");
  ASSERT_NE(failure, std::string::npos);
  std::size_t testcase = xml.rfind("<testcase ", failure);
  EXPECT_NE(xml.substr(testcase, 80).find("lagrangian-order"), std::string::npos);
  std::string body = xml.substr(failure, xml.find("</failure>", failure) - failure);
  EXPECT_NE(body.find("observed order 1, predicted 2 (exact)"), std::string::npos);
  EXPECT_NE(body.find("|L_d − L_d^E|"), std::string::npos);
}

}  // namespace
}  // namespace vivv
