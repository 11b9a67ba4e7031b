#include "reports/junit_report.hpp"

#include <sstream>

#include "reports/report.hpp"
#include "reports/report_text.hpp"

namespace vivv {

namespace {

std::string string_field(const nlohmann::json& object, const char* key) {
  return object.contains(key) && object[key].is_string() ? object[key].get<std::string>() : "";
}

std::string order_text(const nlohmann::json& value) {
  return value.is_number() ? format_number(value.get<double>(), 4) : "-";
}

}  // namespace

std::string evidence_summary(const nlohmann::json& claim) {
  std::ostringstream out;
  out << "source: " << string_field(claim, "source") << "\n";
  out << "prediction: " << string_field(claim, "prediction") << "\n";
  out << "verdict: " << string_field(claim, "verdict") << " — "
      << string_field(claim, "explanation") << "\n";
  for (const auto& series : claim.value("series", nlohmann::json::array())) {
    out << "series " << string_field(series, "label") << ":";
    if (series.contains("observed_order") || series.contains("predicted_order"))
      out << " observed order " << order_text(series.value("observed_order", nlohmann::json()))
          << ", predicted " << order_text(series.value("predicted_order", nlohmann::json()))
          << (series.value("exact_order", false) ? " (exact)" : "");
    if (series.contains("fit_points")) {
      const auto& points = series["fit_points"];
      out << "; fit uses " << points.value("used", nlohmann::json::array()).size() << " of "
          << series.value("h", nlohmann::json::array()).size() << " points";
      for (const auto& dropped : points.value("dropped", nlohmann::json::array()))
        out << "; point " << dropped.value("index", -1)
            << " dropped: " << string_field(dropped, "reason");
    }
    out << "\n  h:";
    for (const auto& h : series.value("h", nlohmann::json::array())) out << " " << short_decimal(h);
    out << "\n  error:";
    for (const auto& e : series.value("error", nlohmann::json::array()))
      out << " " << short_decimal(e);
    out << "\n";
    if (!string_field(series, "explanation").empty())
      out << "  " << string_field(series, "explanation") << "\n";
  }
  return out.str();
}

// A claim --baseline found regressed whose verdict alone is not a JUnit failure (a pass or an
// xfail): it becomes a failure of type "regressed".
bool regressed_only(const nlohmann::json& claim) {
  const std::string verdict = claim.value("verdict", std::string());
  return (verdict == "pass" || verdict == "xfail") && claim.contains("baseline") &&
         claim["baseline"].is_object() &&
         claim["baseline"].value("status", std::string()) == "regressed";
}

std::string render_junit(const nlohmann::json& report) {
  const auto& summary = report["summary"];
  int total = 0;
  for (const auto& [verdict, count] : summary.items()) total += count.get<int>();
  // A refused case is one testcase with an error (no claim computed).
  const nlohmann::json refused = report.value("refused", nlohmann::json::array());
  const nlohmann::json seconds = report["run"].value("case_seconds", nlohmann::json::object());
  const nlohmann::json claim_seconds = report["run"].value("claim_seconds", nlohmann::json::object());
  const nlohmann::json skipped_cases = report["run"].value("skipped_cases", nlohmann::json::array());
  // JUnit's words: a failing claim and an xpass (a known failure that went away) are failures,
  // an xfail is skipped with its reason.
  int regressed = 0, regressed_xfail = 0;
  for (const auto& c : report["cases"])
    for (const auto& claim : c["claims"])
      if (regressed_only(claim)) ++regressed, regressed_xfail += claim["verdict"] == "xfail";
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<testsuites name=\"vivv\" tests=\"" << total + refused.size() + skipped_cases.size() << "\" failures=\""
      << summary.value("fail", 0) + summary.value("inconclusive", 0) + summary.value("xpass", 0) +
             regressed
      << "\" errors=\"" << summary.value("error", 0) + refused.size() << "\" skipped=\""
      << summary.value("xfail", 0) - regressed_xfail + static_cast<int>(skipped_cases.size()) << "\">\n";
  for (const auto& c : report["cases"]) {
    std::string name = c["name"];
    int failures = 0, errors = 0, skipped = 0;
    for (const auto& claim : c["claims"]) {
      failures += claim["verdict"] == "fail" || claim["verdict"] == "inconclusive" ||
                  claim["verdict"] == "xpass";
      errors += claim["verdict"] == "error";
      skipped += claim["verdict"] == "xfail" && !regressed_only(claim);
      failures += regressed_only(claim);
    }
    out << "  <testsuite name=\"" << xml_escape(name) << "\" tests=\"" << c["claims"].size()
        << "\" failures=\"" << failures << "\" errors=\"" << errors << "\" skipped=\"" << skipped << "\"";
    if (seconds.contains(name) && seconds[name].is_number())
      out << " time=\"" << format_number(seconds[name].get<double>(), 6) << "\"";
    out << ">\n";
    for (const auto& claim : c["claims"]) {
      std::string verdict = claim["verdict"], summary_text = evidence_summary(claim);
      out << "    <testcase classname=\"" << xml_escape(name) << "\" name=\""
          << xml_escape(claim["id"].get<std::string>()) << "\"";
      // The claim's own seconds (run.claim_seconds): its judgement and the runs it was the first to need.
      const nlohmann::json own = claim_seconds.value(name, nlohmann::json::object()).value(
          claim["id"].get<std::string>(), nlohmann::json());
      if (own.is_number()) out << " time=\"" << format_number(own.get<double>(), 6) << "\"";
      out << ">\n";
      if (verdict == "fail" || verdict == "inconclusive" || verdict == "error" ||
          verdict == "xpass") {
        // An inconclusive claim fails the run like a failure; its message says it is inconclusive.
        const char* element = verdict == "error" ? "error" : "failure";
        std::string message = string_field(claim, "explanation");
        if (verdict == "inconclusive" && message.rfind("inconclusive:", 0) != 0)
          message = "inconclusive: " + message;
        // A claim that also regressed says so: the verdict's type, both in the message.
        if (claim.contains("baseline") && claim["baseline"].is_object() &&
            claim["baseline"].value("status", std::string()) == "regressed")
          message += "; also regressed against the baseline: " + string_field(claim["baseline"], "explanation");
        out << "      <" << element << " type=\"" << verdict << "\" message=\""
            << xml_escape(message) << "\">" << xml_escape(summary_text) << "</" << element << ">\n";
      } else if (regressed_only(claim)) {
        out << "      <failure type=\"regressed\" message=\""
            << xml_escape("regressed against the baseline: " +
                          string_field(claim["baseline"], "explanation"))
            << "\">" << xml_escape(summary_text) << "</failure>\n";
      } else if (verdict == "xfail") {
        out << "      <skipped message=\"xfail: " << xml_escape(string_field(claim, "xfail_reason"))
            << "\"/>\n";
      }
      out << "      <system-out>" << xml_escape(summary_text) << "</system-out>\n";
      out << "    </testcase>\n";
    }
    out << "  </testsuite>\n";
  }
  // A case whose map program failed while it ran is an error of its own type, "could-not-run".
  for (const auto& entry : refused) {
    const std::string name = string_field(entry, "name");
    const char* type = could_not_run(entry) ? "could-not-run" : "refused";
    out << "  <testsuite name=\"" << xml_escape(name)
        << "\" tests=\"1\" failures=\"0\" errors=\"1\" skipped=\"0\">\n"
        << "    <testcase classname=\"" << xml_escape(name) << "\" name=\"" << type << "\">\n"
        << "      <error type=\"" << type << "\" message=\"" << xml_escape(string_field(entry, "message"))
        << "\">" << xml_escape(string_field(entry, "file") + ": " + string_field(entry, "message"))
        << "</error>\n"
        << "    </testcase>\n  </testsuite>\n";
  }
  // A case --claims skipped is one testcase skipped, naming the claims it lists.
  for (const auto& entry : skipped_cases) {
    const std::string name = string_field(entry, "name");
    std::string claims;
    for (const auto& id : entry.value("claims", nlohmann::json::array()))
      claims += (claims.empty() ? "" : ", ") + id.get<std::string>();
    out << "  <testsuite name=\"" << xml_escape(name)
        << "\" tests=\"1\" failures=\"0\" errors=\"0\" skipped=\"1\">\n"
        << "    <testcase classname=\"" << xml_escape(name) << "\" name=\"skipped\">\n"
        << "      <skipped message=\"" << xml_escape("--claims selects none of its claims (" + claims + ")")
        << "\"/>\n    </testcase>\n  </testsuite>\n";
  }
  out << "</testsuites>\n";
  return out.str();
}

}  // namespace vivv
