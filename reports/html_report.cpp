#include "reports/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "cases/case_file.hpp"
#include "reports/html/page_style.hpp"
#include "reports/html/plot_frame.hpp"
#include "reports/html/verdict_text.hpp"
#include "reports/report.hpp"
#include "reports/report_text.hpp"

namespace vivv {

using namespace html;

namespace {

// The largest of a list of measured errors (decimal strings), or what their zeros mean.
std::string largest_error_html(const json& errors, const std::string& verdict) {
  if (!errors.is_array() || errors.empty()) return "&#8212;";
  std::optional<double> largest;
  std::string largest_text = "0";
  for (const auto& e : errors) {
    if (!e.is_string()) continue;
    auto log = log10_decimal(e.get<std::string>());
    if (log && (!largest || *log > *largest)) {
      largest = log;
      largest_text = e.get<std::string>();
    }
  }
  if (!largest) {
    // Zeros that were measured (an exact method) read as such; an inconclusive claim's zeros are
    // what it could not measure, not an error of 0.
    if (verdict == "inconclusive") return "not measured";
    return "max error 0 <span class=\"small\">(all " + std::to_string(errors.size()) +
           " exactly 0)</span>";
  }
  return "max error " + decimal_html(largest_text);
}

// The observed order with its 95% interval; for a claim without an order, the largest error.
std::string observed_html(const json& claim) {
  const json observed = claim.value("observed_order", json());
  if (observed.is_number()) {
    std::string text = "<b>" + format_number(observed.get<double>(), 4) + "</b>";
    const json interval = claim.value("order_confidence_95", json());
    if (interval.is_array() && interval.size() == 2 && interval[0].is_number() &&
        interval[1].is_number())
      text += " <span class=\"small\">[" + format_number(interval[0].get<double>(), 4) + ", " +
              format_number(interval[1].get<double>(), 4) + "]</span>";
    return text;
  }
  // A claim judged on several series (energy-behaviour: the drift and the energy error's size)
  // shows the largest of each, named: the claim's own errors are only the first series'.
  const json series_list = claim.value("series", json::array());
  if (series_list.size() > 1) {
    std::string text;
    for (const auto& series : series_list) {
      if (!text.empty()) text += "<br>";
      text += "<span class=\"small\">" + escape(text_of(series, "label")) + ":</span> " +
              largest_error_html(series.value("error", json::array()), text_of(claim, "verdict"));
    }
    return text;
  }
  return largest_error_html(claim.value("error", json::array()), text_of(claim, "verdict"));
}

// "observed order 1.99 (95% interval [1.98, 2] from 6 points) within 2 ± 0.2: holds"
// -> "within 2 ± 0.2: holds": the comparison, without the numbers the row already shows.
std::string comparison_part(const std::string& explanation) {
  if (explanation.rfind("observed order", 0) != 0) return explanation;
  std::size_t close = explanation.find(") ");
  std::string comparison = close == std::string::npos ? explanation : explanation.substr(close + 2);
  if (comparison.rfind(">= ", 0) == 0) comparison = "\u2265 " + comparison.substr(3);
  return comparison;
}

// Why observed and predicted differ (or agree): for a failing claim its
// explanation; for a passing one the comparison each series passed.
std::string why_html(const json& claim) {
  std::string explanation = text_of(claim, "explanation");
  if (claim.value("verdict", "") == "pass" && explanation == "every prediction holds") {
    const json series_list = claim.value("series", json::array());
    std::string series_text;
    for (const auto& series : series_list) {
      std::string text = text_of(series, "explanation");
      if (text.empty()) continue;
      if (!series_text.empty()) series_text += "<br>";
      if (series_list.size() > 1)
        series_text += "<span class=\"small\">" + escape(text_of(series, "label")) + ":</span> ";
      series_text += escape(comparison_part(text));
    }
    if (!series_text.empty()) return series_text;
  }
  return escape(explanation);
}

// Any JSON value as HTML: objects as key/value tables, lists of objects as
// tables, decimal strings shortened with the full value as a tooltip.
std::string value_html(const json& value) {
  if (value.is_string()) {
    const std::string text = value.get<std::string>();
    return is_decimal(text) ? decimal_html(text) : escape(text);
  }
  if (value.is_boolean()) return value.get<bool>() ? "&#10003; true" : "&#10007; false";
  if (value.is_null()) return "&#8212;";
  if (value.is_number_float())
    return "<span class=\"num\" title=\"" + value.dump() + "\">" +
           format_number(value.get<double>(), 6) + "</span>";
  if (value.is_number()) return value.dump();
  if (value.is_object()) {
    if (value.empty()) return "<span class=\"small\">(none)</span>";
    std::string out = "<table class=\"kv\">";
    for (const auto& [key, item] : value.items())
      out += "<tr><th>" + escape(key) + "</th><td>" + value_html(item) + "</td></tr>";
    return out + "</table>";
  }
  // An array.
  bool all_objects =
      !value.empty() &&
      std::all_of(value.begin(), value.end(), [](const json& item) { return item.is_object(); });
  if (all_objects) {
    std::vector<std::string> columns;
    for (const auto& item : value)
      for (const auto& [key, unused] : item.items())
        if (std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
    std::string out = "<table class=\"points\"><tr>";
    for (const auto& column : columns) out += "<th>" + escape(column) + "</th>";
    out += "</tr>";
    for (const auto& item : value) {
      out += "<tr>";
      for (const auto& column : columns)
        out += "<td>" + (item.contains(column) ? value_html(item[column]) : "") + "</td>";
      out += "</tr>";
    }
    return out + "</table>";
  }
  std::string out;
  for (std::size_t i = 0; i < value.size(); ++i) out += (i ? ", " : "") + value_html(value[i]);
  return "[" + out + "]";
}

}  // namespace

namespace {

// The map of h_max against |w| with its caption, for a claim whose evidence has one; else "".
std::string speed_map_figure(const json& claim, const std::string& key) {
  const std::string map = render_speed_map(claim, key);
  if (map.empty()) return "";
  std::size_t total = 0, zero = 0;
  for (const auto& row : claim["evidence"]["h_max_by_speed"]) {
    ++total;
    if (!log10_decimal(text_of(row, "h_max"))) ++zero;
  }
  std::ostringstream out;
  out << "<figure class=\"map\">" << map << "<figcaption><b>Theorem 4.2: h_max(v) &gt; 0 however "
      << "fast v is.</b> ";
  if (zero == 0)
    out << "h_max &gt; 0 at all " << total << " speeds.";
  else
    out << "<span class=\"fail-text\">h_max = 0 at " << zero << " of " << total
        << " speeds</span>: h_max = 0 has no logarithm, so those speeds are drawn in the shaded "
           "band below the axis, not at their value.";
  const std::string search = text_of(claim["evidence"], "h_max_search");
  if (!search.empty()) out << " <span class=\"small\">Search: " << escape(search) << ".</span>";
  out << "</figcaption></figure>";
  return out.str();
}

// What a reader must know beside the verdict: a non-default order tolerance
// (it widens what an order claim accepts) and the case's xfail reason.
std::string notes_html(const json& c, const json& claim) {
  std::string notes;
  const std::string tolerance = text_of(c, "order_tolerance");
  if (claim.value("predicted_order", json()).is_number() && !default_tolerance(tolerance))
    notes += "<div class=\"note-cell\" data-note=\"tolerance\">order tolerance " + escape(tolerance) +
             " (default " + default_order_tolerance + ")</div>";
  if (claim.contains("xfail_reason"))
    notes += "<div class=\"note-cell\" data-note=\"xfail\">known failure: " +
             escape(text_of(claim, "xfail_reason")) + "</div>";
  if (!text_of(claim, "weakness").empty())
    notes += "<div class=\"note-cell\" data-note=\"weakness\"><b>weak pass:</b> " +
             escape(text_of(claim, "weakness")) + "</div>";
  if (!text_of(claim, "detection_limit").empty())
    notes += "<div class=\"note-cell\" data-note=\"detection-limit\">detection limit: " +
             escape(text_of(claim, "detection_limit")) + "</div>";
  if (claim.contains("baseline") && claim["baseline"].is_object())
    notes += "<div class=\"note-cell\" data-note=\"baseline\"><b>" +
             escape(text_of(claim["baseline"], "status")) +
             "</b> against the baseline: " + escape(text_of(claim["baseline"], "explanation")) +
             "</div>";
  return notes;
}

// One claim's findings row.
// The case cell spans the case's rows (`case_rows` > 0 on its first row, 0 on the others).
std::string findings_row(const json& c, const json& claim, const std::string& key,
                         const std::string& anchor, std::size_t case_rows) {
  std::string verdict = text_of(claim, "verdict");
  std::ostringstream row;
  row << "<tr class=\"row-" << escape(verdict) << (case_rows ? " first" : "")
      << "\" data-claim-row=\"" << escape(key) << "\">";
  if (case_rows)
    row << "<td class=\"case\" rowspan=\"" << case_rows << "\">" << escape(text_of(c, "name"))
        << "</td>";
  row << "<td><a href=\"#" << anchor << "\">" << escape(text_of(claim, "id")) << "</a></td>"
      << "<td>" << escape(text_of(claim, "source")) << "</td>"
      << "<td>" << predicted_html(claim) << "<div class=\"small\">"
      << escape(text_of(claim, "prediction")) << "</div></td>"
      << "<td class=\"num\">" << observed_html(claim) << "</td>"
      << "<td>" << verdict_badge(verdict) << "</td>"
      << "<td>" << why_html(claim) << notes_html(c, claim) << "</td></tr>\n";
  return row.str();
}

// Per series: label, observed and predicted order, interval, pairwise orders, verdict.
std::string series_table(const json& claim) {
  std::ostringstream out;
  out << "<table class=\"series\"><tr><th>series</th><th>observed</th><th>predicted</th>"
         "<th>pairwise orders (largest h first)</th><th>holds</th></tr>";
  const json series_list = claim.value("series", json::array());
  for (std::size_t i = 0; i < series_list.size(); ++i) {
    const json& s = series_list[i];
    out << "<tr><td><span class=\"swatch\" style=\"background:"
        << series_colors[i % series_colors.size()] << "\"></span>" << escape(text_of(s, "label"))
        << "</td><td class=\"mono\">" << order_html(s.value("observed_order", json()));
    const json interval = s.value("order_confidence_95", json());
    if (interval.is_array() && interval.size() == 2 && interval[0].is_number())
      out << " <span class=\"small\">[" << order_html(interval[0]) << ", "
          << order_html(interval[1]) << "]</span>";
    out << "</td><td class=\"mono\">"
        << (s.value("predicted_order", json()).is_number()
                ? std::string(s.value("exact_order", false) ? "= " : "&#8805; ") +
                      order_html(s["predicted_order"])
                : "&#8212;")
        << "</td><td class=\"mono\">";
    const json pairwise = s.value("pairwise_orders", json::array());
    for (std::size_t k = 0; k < pairwise.size(); ++k)
      out << (k ? ", " : "") << order_html(pairwise[k], 3);
    if (pairwise.empty()) out << "&#8212;";
    out << "</td><td>";
    if (s.value("holds", json()).is_boolean())
      out << verdict_badge(s["holds"].get<bool>()           ? "pass"
                           : s.value("inconclusive", false) ? "inconclusive"
                                                            : "fail");
    else
      out << "<span class=\"small\">(supporting)</span>";
    out << "</td></tr>";
  }
  return out.str() + "</table>";
}

// Every point of every series: h, error, and whether it is in the fit and why not.
std::string points_table(const json& claim) {
  std::ostringstream out;
  for (const auto& s : claim.value("series", json::array())) {
    std::map<int, std::string> dropped;
    std::set<int> used;
    if (s.contains("fit_points")) {
      for (const auto& d : s["fit_points"].value("dropped", json::array()))
        dropped[d.value("index", -1)] = text_of(d, "reason");
      for (const auto& u : s["fit_points"].value("used", json::array())) used.insert(u.get<int>());
    }
    out << "<div class=\"small\">" << escape(text_of(s, "label")) << "</div>"
        << "<table class=\"points\"><tr><th>#</th><th>h</th><th>error</th><th>fit</th></tr>";
    const json h = s.value("h", json::array()), error = s.value("error", json::array());
    for (std::size_t i = 0; i < h.size() && i < error.size(); ++i) {
      int index = static_cast<int>(i);
      out << "<tr><td>" << i << "</td><td class=\"mono\">" << decimal_html(h[i])
          << "</td><td class=\"mono\">" << decimal_html(error[i]) << "</td><td>"
          << (used.count(index)      ? "used"
              : dropped.count(index) ? "dropped: " + escape(dropped[index])
                                     : std::string("&#8212;"))
          << "</td></tr>";
    }
    out << "</table>";
  }
  return out.str();
}

std::string claim_section(const json& c, const json& claim, const std::string& key,
                          const std::string& anchor) {
  std::string verdict = text_of(claim, "verdict");
  std::ostringstream out;
  out << "<section class=\"claim " << escape(verdict) << "\" id=\"" << anchor << "\" data-claim=\""
      << escape(key) << "\">\n<h3>" << verdict_badge(verdict) << " " << escape(text_of(claim, "id"))
      << " <span class=\"small\">" << escape(text_of(c, "name")) << " &#183; "
      << escape(text_of(claim, "source")) << "</span></h3>\n";
  // Every claim's plot and facts are shown (the h² line a user came for, without a click); a
  // passing claim's other figures, series, points and evidence are collapsed (the default suite
  // then prints in far fewer pages), a claim that needs attention opens with them.
  const bool collapsed = verdict == "pass" || verdict == "xfail";
  out << "<div class=\"claim-body\"><div>" << render_claim_plot(claim, key);
  bool any_zero = false;
  std::string unmeasured;  // steps whose value was only recorded, not measured (undrawn)
  for (const auto& s : claim.value("series", json::array())) {
    const std::set<std::string> skipped = unmeasured_steps(claim, s);
    const json h = s.value("h", json::array()), error = s.value("error", json::array());
    for (std::size_t i = 0; i < h.size() && i < error.size(); ++i) {
      if (h[i].is_string() && skipped.count(h[i].get<std::string>())) {
        unmeasured += (unmeasured.empty() ? "" : ", ") + short_decimal(h[i].get<std::string>(), 4);
        continue;
      }
      any_zero = any_zero || (error[i].is_string() && !log10_decimal(error[i].get<std::string>()));
    }
  }
  if (!unmeasured.empty())
    out << "<p class=\"note\" data-not-measured=\"1\">Not drawn: the drift at h = " << escape(unmeasured)
        << " was not measured (too few returns of the motion in T, or an energy error at the rounding "
           "floor: evidence per_step).</p>";
  if (any_zero)
    out << "<p class=\"note\">Errors that are exactly 0 have no logarithm: they are drawn on the "
           "dashed line at the bottom of the plot (the plot floor), not at their value.</p>";
  out << "</div><div>\n<dl class=\"facts\"><dt>prediction</dt><dd>" << predicted_html(claim)
      << " — " << escape(text_of(claim, "prediction")) << "</dd><dt>observed</dt><dd>"
      << observed_html(claim) << "</dd><dt>verdict</dt><dd>" << verdict_badge(verdict) << " "
      << escape(text_of(claim, "explanation")) << "</dd>";
  if (!text_of(claim, "detection_limit").empty())
    out << "<dt>detection limit</dt><dd>" << escape(text_of(claim, "detection_limit")) << "</dd>";
  out << "</dl>\n</div></div>\n";
  out << "<details class=\"claim-details\"" << (collapsed ? "" : " open")
      << "><summary>more figures, series, points and evidence</summary>\n<div>";
  out << speed_map_figure(claim, key);
  if (const std::string time_plot = render_time_plot(claim, key); !time_plot.empty())
    out << "<figure class=\"time\">" << time_plot << "<figcaption>"
        << (text_of(claim, "id") == "modified-energy" ? "The modified energy's" : "The energy")
        << " error against t at each h (the largest in each of about 200 runs of steps): a drift "
           "grows "
           "with t, a symplectic method's error stays in a band that shrinks with "
           "h.</figcaption></figure>";
  out << series_table(claim) << "\n";
  out << "<details><summary>points: h, error, used or dropped</summary>" << points_table(claim)
      << "</details>\n";
  out << "<details><summary>evidence</summary>"
      << value_html(claim.value("evidence", json::object())) << "</details>\n";
  out << "</div></details></section>\n";
  return out.str();
}

std::string case_facts(const json& c) {
  std::ostringstream out;
  out << "<dl class=\"facts\">";
  out << "<dt>system</dt><dd><code>" << escape(text_of(c, "system")) << "</code>";
  const json parameters = c.value("parameters", json::object());
  bool first = true;
  for (const auto& [name, value] : parameters.items()) {
    out << (first ? " " : ", ") << escape(name) << " = " << value_html(value);
    first = false;
  }
  // A formula system's L (and its symmetry generator) as written in the case file.
  const json file = c.value("case_file", json::object());
  const json system = file.is_object() ? file.value("system", json::object()) : json::object();
  const std::string lagrangian = !text_of(c, "lagrangian_formula").empty()
                                     ? text_of(c, "lagrangian_formula")
                                 : system.is_object() ? text_of(system, "lagrangian")
                                                      : std::string();
  if (!lagrangian.empty())
    out << "<div data-fact=\"lagrangian\">L = <code>" << escape(lagrangian) << "</code></div>";
  if (system.is_object() && system.contains("symmetry"))
    out << "<div data-fact=\"symmetry\">symmetry generator &#958; = <code>"
        << escape(system["symmetry"].dump()) << "</code></div>";
  out << "</dd>";
  // The discretizations as the case file states them: kind, rule, its parameters, L_d.
  for (const auto& [key, title] : std::vector<std::pair<std::string, std::string>>{
           {"discretization", "discretization"},
           {"past_discretization", "past side"},
           {"compare_discretization", "compared with"}}) {
    if (!file.is_object() || !file.contains(key) || !file[key].is_object()) continue;
    const json& d = file[key];
    out << "<dt>" << title << "</dt><dd data-fact=\"" << key << "\">";
    if (!text_of(d, "kind").empty()) out << "<code>" << escape(text_of(d, "kind")) << "</code>";
    for (const auto& [field, value] : d.items()) {
      if (field == "kind" || field == "L_d") continue;
      out << " " << escape(field) << " = <code>"
          << escape(value.is_string() ? value.get<std::string>() : value.dump()) << "</code>";
    }
    if (d.contains("L_d"))
      out << "<div data-fact=\"L_d\">L<sub>d</sub> = <code>" << escape(text_of(d, "L_d"))
          << "</code></div>";
    out << "</dd>";
  }
  out << "<dt>initial</dt><dd>q = " << value_html(c["initial"].value("q", json::array()))
      << ", w = " << value_html(c["initial"].value("w", json::array())) << "</dd>";
  out << "<dt>sweep</dt><dd>T = " << value_html(c.value("T", json()))
      << ", N = " << value_html(c.value("steps", json::array())) << " (h = T/N)</dd>";
  const json precision = c.value("precision", json::object());
  out << "<dt>precision</dt><dd>" << escape(text_of(precision, "scalar")) << ", "
      << value_html(precision.value("digits", json())) << " digits ("
      << value_html(precision.value("bits", json())) << " bits); smallest fitted error "
      << (text_of(precision, "smallest_error").empty()
              ? "&#8212;"
              : decimal_html(text_of(precision, "smallest_error")))
      << ", guard " << value_html(precision.value("guard_bits", json()))
      << " bits <span class=\"small\">(" << escape(text_of(precision, "rule")) << ")</span></dd>";
  const json reference = c.value("reference", json::object());
  out << "<dt>reference</dt><dd>" << escape(text_of(reference, "method")) << "; tolerance "
      << decimal_html(text_of(reference, "tolerance"))
      << "; cross-check at T: " << decimal_html(text_of(reference, "error_estimate_at_T"))
      << "<div class=\"small\">" << escape(text_of(reference, "cross_check")) << "</div></dd>";
  out << "<dt>case file</dt><dd><code>" << escape(text_of(c, "file"))
      << "</code><details><summary>content</summary><pre>"
      << escape(c.value("case_file", json()).dump(2)) << "</pre></details></dd>";
  out << "</dl>";
  return out.str();
}

}  // namespace

std::string render_html(const json& report) {
  const json& cases = report.at("cases");
  const json& summary = report.at("summary");
  const json& run = report.at("run");
  int total = 0;
  std::string counts, badges;
  for (const auto& [verdict, count] : summary.items()) total += count.get<int>();
  const json refused = report.value("refused", json::array());
  // A claim needs attention unless it passed or failed as its case expects.
  const auto needs_attention = [](const std::string& verdict) {
    return verdict != "pass" && verdict != "xfail";
  };
  for (const char* verdict : {"pass", "fail", "inconclusive", "error", "xfail", "xpass"}) {
    const int count = summary.value(verdict, 0);
    counts += std::string(counts.empty() ? "" : ", ") + std::to_string(count) + " " + verdict;
    // Each badge links to where its claims are listed: the non-passing ones to "Needs attention".
    const std::string target = count > 0 && needs_attention(verdict) ? "#attention" : "#findings";
    badges += "<a class=\"verdict v-" + std::string(verdict) + "\" data-count=\"" + verdict +
              "\" href=\"" + target + "\">" + std::to_string(count) + " " + verdict + "</a>";
  }
  const int regressed_count = run.contains("baseline") && run["baseline"].is_object()
                                  ? run["baseline"].value("regressed", 0)
                                  : 0;
  if (regressed_count > 0) {
    counts += ", " + std::to_string(regressed_count) + " regressed";
    badges += "<a class=\"verdict v-fail\" data-count=\"regressed\" href=\"#attention\">" +
              std::to_string(regressed_count) + " regressed</a>";
  }
  const auto not_run = static_cast<std::size_t>(
      std::count_if(refused.begin(), refused.end(), [](const json& entry) { return could_not_run(entry); }));
  if (refused.size() > not_run) {
    counts += ", " + std::to_string(refused.size() - not_run) + " refused";
    badges += "<a class=\"verdict v-error\" data-count=\"refused\" href=\"#attention\">" +
              std::to_string(refused.size() - not_run) + " refused</a>";
  }
  if (not_run > 0) {
    counts += ", " + std::to_string(not_run) + " could not run";
    badges += "<a class=\"verdict v-error\" data-count=\"could-not-run\" href=\"#attention\">" +
              std::to_string(not_run) + " could not run</a>";
  }
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
       << "<title>vivv report: " << counts << "</title>\n<style>" << page_style
       << "</style>\n</head>\n<body>\n<main>\n";
  page << "<h1>vivv verification report</h1>\n<p class=\"lede\">" << cases.size() << " cases, "
       << total << " claims of the error analysis of variational integrators, each checked "
       << "against a near-exact reference flow. Schema <code>" << escape(text_of(report, "schema"))
       << "</code>.</p>\n";
  // The claims --claims selected, and the cases it left without one.
  const json selected = run.value("overrides", json::object()).value("claims", json());
  if (selected.is_array()) {
    std::string names, skipped;
    for (const auto& id : selected) names += (names.empty() ? "" : ", ") + id.get<std::string>();
    for (const auto& entry : run.value("skipped_cases", json::array()))
      skipped += (skipped.empty() ? "" : ", ") + text_of(entry, "name");
    page << "<p class=\"lede\" data-claims-selected=\"1\">Only the claims <code>" << escape(names)
         << "</code> were run (--claims)"
         << (skipped.empty() ? std::string() : "; skipped, listing none of them: " + escape(skipped))
         << ".</p>\n";
  }
  page << "<div class=\"summary\" data-summary=\"1\">" << badges << "</div>\n";

  // Keys and anchors, in report order.
  std::vector<std::tuple<const json*, const json*, std::string, std::string>> claims;
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (std::size_t k = 0; k < cases[i]["claims"].size(); ++k) {
      const json& claim = cases[i]["claims"][k];
      claims.emplace_back(&cases[i], &claim, text_of(cases[i], "name") + "/" + text_of(claim, "id"),
                          "claim-" + std::to_string(i) + "-" + std::to_string(k));
    }

  // Failures first: every claim that did not pass and every refused case, each linked to its
  // section, with the series that decided it and why, before the full findings table.
  std::ostringstream attention;
  for (std::size_t i = 0; i < refused.size(); ++i)
    attention << "<li data-attention=\"" << (could_not_run(refused[i]) ? "could-not-run" : "refused")
              << "\"><span class=\"verdict v-error\">"
              << (could_not_run(refused[i]) ? "could not run" : "refused") << "</span> <b>"
              << escape(text_of(refused[i], "name")) << "</b> <span class=\"small\">("
              << escape(text_of(refused[i], "file"))
              << ")</span>: " << escape(text_of(refused[i], "message")) << "</li>\n";
  for (const auto& [c, claim, key, anchor] : claims) {
    const std::string verdict = text_of(*claim, "verdict");
    const bool regressed = claim->contains("baseline") && (*claim)["baseline"].is_object() &&
                           text_of((*claim)["baseline"], "status") == "regressed";
    if (regressed)
      attention << "<li data-attention=\"regressed\" data-attention-claim=\"" << escape(key)
                << "\"><span class=\"verdict v-fail\">regressed</span> <a href=\"#" << anchor
                << "\">" << escape(key) << "</a>: against the baseline: "
                << escape(text_of((*claim)["baseline"], "explanation")) << "</li>\n";
    if (!needs_attention(verdict)) continue;
    attention << attention_line(*claim, key, anchor);
  }
  if (!attention.str().empty())
    page << "<h2 id=\"attention\">Needs attention</h2>\n<p class=\"lede\">Every claim that did not "
            "pass (or did not fail as its case expects), regressed against the baseline, and every "
            "case refused, first; each links to its section.</p>\n<ul class=\"attention\">\n"
         << attention.str() << "</ul>\n";

  page << "<h2 id=\"findings\">Findings</h2>\n<p class=\"lede\">One row per claim. Predicted "
          "orders are the theorems' lower bounds (&#8805;) unless the case declares the exact "
          "order (=). Observed: least-squares order with its 95% interval. Hover a shortened "
          "number for all its digits.</p>\n";
  page << "<table class=\"findings\"><colgroup><col style=\"width:12%\"><col style=\"width:11%\">"
          "<col style=\"width:10%\"><col style=\"width:20%\"><col style=\"width:11%\">"
          "<col style=\"width:15%\"><col style=\"width:21%\"></colgroup>"
          "<thead><tr><th>case</th><th>claim</th><th>source</th>"
          "<th>prediction</th><th>observed order</th><th>verdict</th><th>why they differ / "
          "agree</th>"
          "</tr></thead><tbody>\n";
  const json* previous_case = nullptr;
  for (const auto& [c, claim, key, anchor] : claims) {
    page << findings_row(*c, *claim, key, anchor, c == previous_case ? 0 : (*c)["claims"].size());
    previous_case = c;
  }
  page << "</tbody></table>\n";

  if (const std::string diagrams =
          render_work_precision(cases, run, false) + render_work_precision(cases, run, true);
      !diagrams.empty())
    page << "<h2 id=\"work-precision\">Work and precision</h2>\n<p class=\"lede\">For the cases "
            "that share a "
            "system, parameters, initial state and T: each method's global error against what its "
            "runs cost, "
            "counted in evaluations of L (deterministic, the same on any machine).</p>\n"
         << diagrams;

  std::size_t next = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const json& c = cases[i];
    page << "<h2 id=\"case-" << i << "\" data-case=\"" << escape(text_of(c, "name")) << "\">"
         << escape(text_of(c, "name"));
    for (const auto& label : c.value("labels", json::array()))
      page << " <span class=\"small\">[" << escape(label.get<std::string>()) << "]</span>";
    page << "</h2>\n" << case_facts(c) << "\n";
    for (std::size_t k = 0; k < c["claims"].size(); ++k, ++next) {
      const auto& [unused_case, claim, key, anchor] = claims[next];
      page << claim_section(c, *claim, key, anchor);
    }
  }

  page << "<h2 id=\"run\">Run</h2>\n<p class=\"lede\">Everything that may differ between two "
          "runs of the same input lives in this block (the \"run\" field of report.json).</p>\n"
       << "<details><summary>command line, versions, timings and paths</summary>" << value_html(run)
       << "</details>\n";
  page << "</main>\n</body>\n</html>\n";
  return page.str();
}

}  // namespace vivv
