// report.html on a small synthetic report: every claim has its row and its
// plot, a failing claim renders as fail, errors of exactly 0 are drawn at the
// plot floor, long decimals are shortened with the full value kept, and a
// claim with h_max_by_speed evidence gets its map of h_max against |w|.
#include "reports/html_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "reports/report_text.hpp"
#include "tests/reports/synthetic_report.hpp"

namespace vivv {
namespace {

using testing::count;

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

// A non-default order tolerance and an xfail reason are shown in the findings row; the
// summary counts all five verdicts.
TEST(HtmlReport, FindingsShowTolerancesAndKnownFailures) {
  nlohmann::json report = testing::synthetic_report();
  report["cases"][0]["order_tolerance"] = "0.25";
  report["cases"][0]["claims"][1]["verdict"] = "xfail";
  report["cases"][0]["claims"][1]["xfail_reason"] = "β ≠ 1/2";
  report["summary"] = {{"pass", 2}, {"fail", 0}, {"error", 0}, {"xfail", 1}, {"xpass", 0}};
  const std::string page = render_html(report);
  std::smatch row;
  ASSERT_TRUE(std::regex_search(
      page, row, std::regex("<tr class=\"row-xfail[^\"]*\" data-claim-row=\"alpha/lagrangian-order\">.*?</tr>")));
  EXPECT_NE(row.str().find("data-verdict=\"xfail\""), std::string::npos);
  EXPECT_NE(row.str().find("order tolerance 0.25 (default 0.2)"), std::string::npos) << row.str();
  EXPECT_NE(row.str().find("known failure: β ≠ 1/2"), std::string::npos) << row.str();
  for (const char* verdict : {"pass", "fail", "error", "xfail", "xpass"})
    EXPECT_EQ(count(page, std::string("data-count=\"") + verdict + "\""), 1) << verdict;
  // The default tolerance is not a finding.
  EXPECT_EQ(count(render_html(testing::synthetic_report()), "data-note=\"tolerance\""), 0);
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

TEST(HtmlReport, HmaxAgainstSpeedIsMappedWhereTheEvidenceHasIt) {
  // No map for claims without h_max_by_speed.
  EXPECT_EQ(count(render_html(testing::synthetic_report()), "data-claim-map="), 0);
  const std::string page = render_html(testing::synthetic_report_with_map());
  EXPECT_EQ(count(page, "data-claim-map="), 1);
  EXPECT_EQ(count(page, "data-claim-map=\"gamma/existence-uniqueness\""), 1);
  EXPECT_EQ(count(page, "data-claim-plot="), 4);  // the map is in addition to the plot
  EXPECT_NE(page.find("Theorem 4.2: h_max(v) &gt; 0 however fast v is"), std::string::npos);
  EXPECT_NE(page.find("h_max = 0 at 1 of 6 speeds"), std::string::npos);

  const std::string map =
      render_speed_map(testing::synthetic_existence_claim(), "gamma/existence-uniqueness");
  EXPECT_EQ(map.rfind("<svg class=\"plot map\"", 0), 0u);
  EXPECT_EQ(count(map, "data-map-point=\"positive\""), 5);
  EXPECT_EQ(count(map, "data-map-point=\"zero\""), 1);
  EXPECT_EQ(count(map, "data-map-line=\"1\""), 1);  // the positive points joined
  EXPECT_NE(map.find("data-zero-band"), std::string::npos);
  EXPECT_NE(map.find("h_max = 0: no step h &gt; 0 works at this speed"), std::string::npos);
  EXPECT_NE(map.find(">speed |w|</text>"), std::string::npos);
  EXPECT_NE(map.find(">h_max</text>"), std::string::npos);
  EXPECT_NE(map.find("|w| = 8, h_max = 0.0e+00"), std::string::npos);
  EXPECT_EQ(map.find("nan"), std::string::npos);
  EXPECT_EQ(map.find("inf"), std::string::npos);
  // h_max halves as |w| doubles: on log-log axes the five positive points
  // step right and down by equal amounts.
  std::regex circle("<circle cx=\"([0-9.]+)\" cy=\"([0-9.]+)\"");
  std::vector<std::pair<double, double>> xy;
  for (auto it = std::sregex_iterator(map.begin(), map.end(), circle); it != std::sregex_iterator();
       ++it)
    xy.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  ASSERT_GE(xy.size(), 5u);
  for (std::size_t i = 1; i < 5; ++i) {
    EXPECT_GT(xy[i].first, xy[i - 1].first);   // faster to the right
    EXPECT_GT(xy[i].second, xy[i - 1].second);  // smaller h_max lower down
    EXPECT_NEAR(xy[i].first - xy[i - 1].first, xy[1].first - xy[0].first, 0.2);
    EXPECT_NEAR(xy[i].second - xy[i - 1].second, xy[1].second - xy[0].second, 0.2);
  }

  // Without a zero: no band, and the caption says h_max > 0 everywhere.
  nlohmann::json positive = testing::synthetic_existence_claim();
  positive["evidence"]["h_max_by_speed"][5]["h_max"] = "1.25e-01";
  EXPECT_EQ(render_speed_map(positive, "k").find("data-zero-band"), std::string::npos);
  nlohmann::json no_map = testing::synthetic_existence_claim();
  no_map["evidence"].erase("h_max_by_speed");
  EXPECT_EQ(render_speed_map(no_map, "k"), "");
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
