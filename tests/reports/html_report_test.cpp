// report.html on a small synthetic report: every claim has its row and its
// plot, a failing claim renders as fail, errors of exactly 0 are drawn at the
// plot floor, long decimals are shortened with the full value kept.
#include "reports/html_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "reports/report_text.hpp"
#include "tests/reports/synthetic_report.hpp"

namespace vivv {
namespace {

int count(const std::string& text, const std::string& needle) {
  int n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
    ++n;
  return n;
}

TEST(HtmlReport, EveryClaimHasItsRowAndItsPlot) {
  const std::string page = render_html(testing::synthetic_report());
  for (const char* key :
       {"alpha/global-order", "alpha/lagrangian-order", "beta/twin-term-invariance"}) {
    EXPECT_EQ(count(page, std::string("data-claim-row=\"") + key + "\""), 1) << key;
    EXPECT_EQ(count(page, std::string("data-claim-plot=\"") + key + "\""), 1) << key;
  }
  EXPECT_EQ(count(page, "data-claim-row="), 3);
  EXPECT_EQ(count(page, "<svg class=\"plot\""), 3);
}

TEST(HtmlReport, IsSelfContained) {
  const std::string page = render_html(testing::synthetic_report());
  EXPECT_EQ(page.find("<script src"), std::string::npos);
  EXPECT_EQ(page.find("<link"), std::string::npos);
  EXPECT_EQ(page.find("@import"), std::string::npos);
  EXPECT_EQ(page.find("url(http"), std::string::npos);
  // The only URL is the SVG namespace, which is a name, not a fetch.
  EXPECT_EQ(count(page, "http"), count(page, "xmlns=\"http://www.w3.org/2000/svg\""));
}

TEST(HtmlReport, FailingClaimRendersAsFail) {
  const std::string page = render_html(testing::synthetic_report());
  std::smatch row;
  ASSERT_TRUE(std::regex_search(
      page, row,
      std::regex(
          "<tr class=\"row-fail[^\"]*\" data-claim-row=\"alpha/lagrangian-order\">.*?</tr>")));
  EXPECT_NE(row.str().find("data-verdict=\"fail\""), std::string::npos);
  EXPECT_NE(row.str().find("FAIL"), std::string::npos);
  EXPECT_NE(row.str().find("the order is too low"), std::string::npos);
  EXPECT_NE(page.find("class=\"claim fail\""), std::string::npos);
}

TEST(HtmlReport, ZeroErrorsAreDrawnAtThePlotFloor) {
  const std::string plot =
      render_claim_plot(testing::synthetic_report()["cases"][1]["claims"][0], "beta/twin");
  EXPECT_EQ(count(plot, "data-point=\"zero\""), 4);
  EXPECT_NE(plot.find("data-zero-band"), std::string::npos);
  EXPECT_NE(plot.find("drawn at the plot floor"), std::string::npos);
  EXPECT_EQ(plot.find("nan"), std::string::npos);
  EXPECT_EQ(plot.find("inf"), std::string::npos);
}

TEST(HtmlReport, UsedAndDroppedPointsAreMarkedApartWithTheReason) {
  const std::string plot =
      render_claim_plot(testing::synthetic_report()["cases"][0]["claims"][0], "alpha/global");
  EXPECT_EQ(count(plot, "data-point=\"used\""), 3);
  EXPECT_EQ(count(plot, "data-point=\"dropped\""), 1);
  EXPECT_NE(plot.find("dropped from the fit: pre-asymptotic"), std::string::npos);
  EXPECT_EQ(count(plot, "data-fit=\"1\""), 1);
  EXPECT_NE(plot.find("data-legend"), std::string::npos);
}

TEST(HtmlReport, LongDecimalsAreShortenedWithTheFullValueAsTitle) {
  const std::string page = render_html(testing::synthetic_report());
  EXPECT_NE(page.find("title=\"1.234567890123456789012345678901234567890e-05\">1.235e-5<"),
            std::string::npos);
}

TEST(ReportText, ShortensAndTakesLogarithmsOfDecimalStrings) {
  EXPECT_EQ(short_decimal("1.378330627092785801439799552813122186213933e-02"), "0.01378");
  EXPECT_EQ(short_decimal("3.344089762276601068088605395253226063998727e-06"), "3.344e-6");
  EXPECT_EQ(short_decimal("0.000000000000000000000000000000000000000000e+00"), "0");
  EXPECT_EQ(short_decimal("9.99999999e-500"), "1e-499");
  EXPECT_EQ(short_decimal("not a number"), "not a number");
  EXPECT_NEAR(*log10_decimal("2.5e-700"), std::log10(2.5) - 700, 1e-12);
  EXPECT_FALSE(log10_decimal("0.0e+00"));
  EXPECT_FALSE(log10_decimal("-1e-3"));
}

}  // namespace
}  // namespace vivv
