#include "reports/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "cases/case_file.hpp"
#include "reports/report.hpp"
#include "reports/report_text.hpp"

namespace vivv {

namespace {

using nlohmann::json;

const char* const page_style = R"css(
:root { --ink: #1d2430; --muted: #5b6576; --rule: #d8dde6; --panel: #f6f8fb;
        --pass: #11612b; --pass-bg: #dcf3e2; --fail: #a40e26; --fail-bg: #fde2e5;
        --error: #8a4b00; --error-bg: #fff0d1; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff;
       font: 14px/1.45 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", Arial, sans-serif; }
main { max-width: 1240px; margin: 0 auto; padding: 20px 28px 60px; }
h1 { font-size: 24px; margin: 0 0 4px; }
h2 { font-size: 19px; margin: 36px 0 8px; padding-top: 10px; border-top: 2px solid var(--ink); }
h3 { font-size: 16px; margin: 0 0 6px; display: flex; gap: 10px; align-items: center; flex-wrap: wrap; }
a { color: #0b4f8a; text-decoration: none; } a:hover { text-decoration: underline; }
code, pre, .mono { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 12.5px; }
pre { background: var(--panel); padding: 8px 10px; overflow-x: auto; border-radius: 4px; }
.lede { color: var(--muted); margin: 0 0 14px; }
.summary { display: flex; gap: 10px; margin: 10px 0 16px; flex-wrap: wrap; }
.verdict { display: inline-block; padding: 1px 8px; border-radius: 10px; font-weight: 700;
           font-size: 12.5px; letter-spacing: .02em; white-space: nowrap; border: 1px solid; }
.v-pass { color: var(--pass); background: var(--pass-bg); border-color: #9ad2ab; }
.v-fail { color: var(--fail); background: var(--fail-bg); border-color: #f2a3ad; }
.v-error { color: var(--error); background: var(--error-bg); border-color: #f0c36b; }
.v-xfail { color: #4b5563; background: #eef0f3; border-color: #b8bec8; }
.v-xpass { color: var(--fail); background: var(--fail-bg); border-color: #f2a3ad; border-style: dashed; }
.v-inconclusive { color: #5b2a86; background: #efe4fa; border-color: #c3a3e3; }
.note-cell { font-size: 12px; color: var(--muted); }
.summary .verdict { font-size: 15px; padding: 4px 14px; }
.attention li { margin: 5px 0; }
ul.legend { list-style: none; padding: 0; margin: 2px 0 8px 72px; max-width: 560px; font-size: 13px; }
ul.legend li { margin: 2px 0; overflow-wrap: anywhere; }
table { border-collapse: collapse; }
table.findings { width: 100%; font-size: 13px; }
table.findings th, table.findings td { border-bottom: 1px solid var(--rule); padding: 5px 7px;
                                       vertical-align: top; text-align: left; }
table.findings th { background: var(--ink); color: #fff; font-weight: 600; position: sticky; top: 0; }
table.findings tr.row-fail td { background: #fff5f6; }
table.findings tr.row-error td { background: #fffaf0; }
table.findings { table-layout: fixed; }
table.findings td.case { font-weight: 600; word-break: break-word; background: #fff !important;
                         border-right: 1px solid var(--rule); }
table.findings tr.first td { border-top: 2px solid #9aa4b5; }
table.findings td .small { font-size: 11.5px; line-height: 1.35; }
table.findings td.num { font-variant-numeric: tabular-nums; }
.small { color: var(--muted); font-size: 12px; }
.facts { display: grid; grid-template-columns: max-content 1fr; gap: 2px 14px; margin: 6px 0 10px;
         font-size: 13px; }
.facts dt { color: var(--muted); } .facts dd { margin: 0; }
.claim { border: 1px solid var(--rule); border-left: 5px solid var(--pass); border-radius: 6px;
         padding: 12px 14px; margin: 14px 0; background: #fff; }
.claim.fail { border-left-color: var(--fail); } .claim.error { border-left-color: var(--error); }
.claim-body { display: grid; grid-template-columns: 660px 1fr; gap: 16px; align-items: start; }
@media (max-width: 1100px) { .claim-body { grid-template-columns: 1fr; } }
svg.plot { background: #fff; border: 1px solid var(--rule); border-radius: 4px; max-width: 100%; height: auto; }
svg.plot text { font-size: 12px; fill: var(--ink); }
svg.plot .tick text { fill: var(--muted); font-size: 11px; }
table.series, table.kv, table.points { font-size: 12.5px; margin: 4px 0 8px; }
table.series { width: 100%; }
table.series th, table.series td, table.kv th, table.kv td, table.points th, table.points td {
  border: 1px solid var(--rule); padding: 3px 6px; text-align: left; vertical-align: top; }
table.series th, table.points th, table.kv th { background: var(--panel); font-weight: 600; }
.swatch { display: inline-block; width: 12px; height: 12px; border-radius: 50%; margin-right: 5px;
          vertical-align: -1px; }
details { margin: 6px 0; } summary { cursor: pointer; color: #0b4f8a; }
.note { color: var(--muted); font-size: 12px; margin: 2px 0 6px; }
span.num[title] { border-bottom: 1px dotted #98a2b3; cursor: help; }
figure.map { margin: 10px 0 0; }
figure.map figcaption { font-size: 12.5px; margin: 3px 2px 0; max-width: 640px; }
.fail-text { color: var(--fail); font-weight: 600; }
)css";

const std::vector<std::string> series_colors = {"#1565c0", "#e07b00", "#7b1fa2",
                                                "#00897b", "#6d4c41", "#c2185b"};

std::string text_of(const json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_string()
             ? object[key].get<std::string>()
             : "";
}

std::string escape(const std::string& text) { return xml_escape(text); }

// A decimal string shortened, with the full value as a tooltip.
std::string decimal_html(const std::string& decimal) {
  std::string shown = short_decimal(decimal);
  if (shown == decimal) return escape(decimal);
  return "<span class=\"num\" title=\"" + escape(decimal) + "\">" + escape(shown) + "</span>";
}

std::string verdict_badge(const std::string& verdict) {
  std::string mark = verdict == "pass"           ? "&#10003; pass"
                     : verdict == "fail"         ? "&#10007; FAIL"
                     : verdict == "xfail"        ? "&#8856; xfail"
                     : verdict == "xpass"        ? "&#10007; XPASS"
                     : verdict == "inconclusive" ? "&#63; INCONCLUSIVE"
                                                 : "&#9888; ERROR";
  return "<span class=\"verdict v-" + escape(verdict) + "\" data-verdict=\"" + escape(verdict) +
         "\">" + mark + "</span>";
}

std::string order_html(const json& value, int digits = 4) {
  return value.is_number() ? format_number(value.get<double>(), digits) : "&#8212;";
}

// "≥ 2" for a lower bound, "= 2 (exact)" for an exact order, "—" for none.
std::string predicted_html(const json& claim) {
  const json predicted = claim.value("predicted_order", json());
  if (!predicted.is_number()) return "<span class=\"small\">(no order)</span>";
  return "order " + std::string(claim.value("exact_order", false) ? "= " : "&#8805; ") +
         format_number(predicted.get<double>(), 4) +
         (claim.value("exact_order", false) ? " <span class=\"small\">(exact)</span>" : "");
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
  const json errors = claim.value("error", json::array());
  if (errors.empty()) return "&#8212;";
  std::optional<double> largest;
  std::string largest_text = "0";
  for (const auto& e : errors) {
    auto log = log10_decimal(e.get<std::string>());
    if (log && (!largest || *log > *largest)) {
      largest = log;
      largest_text = e.get<std::string>();
    }
  }
  if (!largest)
    return "max error 0 <span class=\"small\">(all " + std::to_string(errors.size()) +
           " exactly 0)</span>";
  return "max error " + decimal_html(largest_text);
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

// --- The log-log plot ------------------------------------------------------

struct PlotPoint {
  int index = 0;
  double x = 0;             // log10 h
  std::optional<double> y;  // log10 e; empty for e = 0
  std::string h, error;     // the decimal strings
  std::string status;       // used, dropped, zero, measured
  std::string reason;       // why dropped
};

struct PlotSeries {
  std::string label, color;
  std::vector<PlotPoint> points;
  std::optional<double> order, log10_constant, predicted;
  bool exact = false;
  std::optional<bool> holds;
  std::string fit_failure;
  // A value judged against its own tolerance at each h (an identity, a conserved quantity): no
  // order is fitted or drawn for it.
  bool per_step = false;
};

PlotSeries plot_series(const json& series, const std::string& color) {
  PlotSeries out;
  out.label = text_of(series, "label");
  out.color = color;
  std::set<int> used;
  std::map<int, std::string> dropped;
  out.per_step = text_of(series, "rule") == "per-step-tolerance";
  bool has_fit = !out.per_step && series.contains("fit_points") && series["fit_points"].is_object();
  if (has_fit) {
    for (const auto& i : series["fit_points"].value("used", json::array()))
      used.insert(i.get<int>());
    for (const auto& d : series["fit_points"].value("dropped", json::array()))
      dropped[d.value("index", -1)] = text_of(d, "reason");
  }
  const json h = series.value("h", json::array()), error = series.value("error", json::array());
  for (std::size_t i = 0; i < h.size() && i < error.size(); ++i) {
    PlotPoint point;
    point.index = static_cast<int>(i);
    point.h = h[i].get<std::string>();
    point.error = error[i].get<std::string>();
    auto x = log10_decimal(point.h);
    if (!x) continue;  // a non-positive step cannot be placed on a log axis
    point.x = *x;
    point.y = log10_decimal(point.error);
    if (!point.y) {
      point.status = "zero";
      point.reason = dropped.count(point.index) ? dropped[point.index] : "";
    } else if (!has_fit || (!used.count(point.index) && !dropped.count(point.index))) {
      point.status = "measured";
    } else if (used.count(point.index)) {
      point.status = "used";
    } else {
      point.status = "dropped";
      point.reason = dropped[point.index];
    }
    out.points.push_back(point);
  }
  const json order = series.value("observed_order", json());
  const json constant = series.value("error_constant_log", json());
  if (!out.per_step && order.is_number() && constant.is_number()) {
    out.order = order.get<double>();
    out.log10_constant = constant.get<double>() / std::log(10.0);
  }
  if (series.value("predicted_order", json()).is_number())
    out.predicted = series["predicted_order"].get<double>();
  out.exact = series.value("exact_order", false);
  if (series.value("holds", json()).is_boolean()) out.holds = series["holds"].get<bool>();
  out.fit_failure = text_of(series, "fit_failure");
  return out;
}

// Tick positions (log10) over [low, high]: decades, thinned to at most ~7,
// with 2 and 5 multiples added when fewer than two decades fall in range.
// A report may hold any decimal ("1e-20000000000" is 2·10¹⁰ decades below 1): the step and the
// decades are 64-bit, so the count stays at most ~8 whatever the range.
std::vector<std::pair<double, std::string>> log_ticks(double low, double high) {
  std::vector<std::pair<double, std::string>> ticks;
  constexpr double largest = 1e15;  // decades beyond this are not on any page
  if (!std::isfinite(low) || !std::isfinite(high) || low > high || std::abs(low) > largest ||
      std::abs(high) > largest)
    return ticks;
  const long long step = std::max(1LL, static_cast<long long>(std::ceil((high - low) / 7)));
  for (long long d = static_cast<long long>(std::ceil(low / static_cast<double>(step))) * step;
       d <= high; d += step)
    ticks.push_back({static_cast<double>(d),
                     "10<tspan dy=\"-5\" font-size=\"9\">" + std::to_string(d) + "</tspan>"});
  if (ticks.size() < 2) {
    for (long long d = static_cast<long long>(std::floor(low)); d <= std::ceil(high); ++d)
      for (int k : {2, 5}) {
        double x = d + std::log10(static_cast<double>(k));
        if (x >= low && x <= high)
          ticks.push_back({x, std::to_string(k) + "&#183;10<tspan dy=\"-5\" font-size=\"9\">" +
                                  std::to_string(d) + "</tspan>"});
      }
  }
  return ticks;
}

std::string identifier(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return out;
}

std::string fixed(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", x);
  return buffer;
}

}  // namespace

std::string render_claim_plot(const json& claim, const std::string& key) {
  std::vector<PlotSeries> all;
  const json series_list = claim.value("series", json::array());
  for (std::size_t i = 0; i < series_list.size(); ++i)
    all.push_back(plot_series(series_list[i], series_colors[i % series_colors.size()]));

  // An identity's or conserved quantity's tolerance at each h (evidence per_step), drawn as the
  // line the values must stay below.
  std::vector<std::pair<double, double>> tolerance_line;
  const bool any_per_step =
      std::any_of(all.begin(), all.end(), [](const PlotSeries& s) { return s.per_step; });
  const json evidence = claim.value("evidence", json::object());
  if (any_per_step && evidence.is_object())
    for (const auto& row : evidence.value("per_step", json::array())) {
      if (!row.is_object()) continue;
      const auto x = log10_decimal(text_of(row, "h")), y = log10_decimal(text_of(row, "tolerance"));
      if (x && y) tolerance_line.emplace_back(*x, *y);
    }
  std::sort(tolerance_line.begin(), tolerance_line.end());

  // Ranges in log10.
  std::optional<double> x_low, x_high, y_low, y_high;
  for (const auto& [x, y] : tolerance_line) {
    y_low = std::min(y_low.value_or(y), y);
    y_high = std::max(y_high.value_or(y), y);
  }
  bool any_zero = false;
  for (const auto& s : all)
    for (const auto& p : s.points) {
      x_low = std::min(x_low.value_or(p.x), p.x);
      x_high = std::max(x_high.value_or(p.x), p.x);
      if (p.y) {
        y_low = std::min(y_low.value_or(*p.y), *p.y);
        y_high = std::max(y_high.value_or(*p.y), *p.y);
      } else {
        any_zero = true;
      }
    }
  // NaN when the main series states no floor (a plain double: GCC misreads optional here).
  double floor_log = NAN;
  if (!series_list.empty())
    if (auto log = log10_decimal(text_of(series_list[0], "floor"))) floor_log = *log;
  if (!x_low) {
    x_low = -2;
    x_high = -1;
  }
  if (!y_low) {  // every error is exactly zero: centre the axis on the stated floor
    double centre = std::isfinite(floor_log) ? floor_log : -30;
    y_low = centre - 2;
    y_high = centre + 1;
  }
  auto widen = [](std::optional<double>& low, std::optional<double>& high, double minimum_span,
                  double padding) {
    double span = *high - *low;
    if (span < minimum_span) {
      double middle = (*high + *low) / 2;
      *low = middle - minimum_span / 2;
      *high = middle + minimum_span / 2;
      span = minimum_span;
    }
    *low -= padding * span;
    *high += padding * span;
  };
  widen(x_low, x_high, 0.6, 0.06);
  widen(y_low, y_high, 1.0, 0.08);

  // Geometry: plot area, then the zero band below it, axis labels and legend.
  const double width = 640, left = 72, right = width - 24, top = 14, plot_bottom = 264;
  const double zero_band = any_zero ? 26 : 0, axis_bottom = plot_bottom + zero_band;
  // The marker key in the SVG (two rows of fixed text); the series' legend, whose labels and fit
  // notes can be long, is HTML below the plot, where it wraps instead of being clipped.
  std::size_t legend_rows = 2;
  const double legend_top = axis_bottom + 50, height = legend_top + 18.0 * legend_rows + 6;
  auto px = [&](double x) { return left + (x - *x_low) / (*x_high - *x_low) * (right - left); };
  auto py = [&](double y) {
    return plot_bottom - (y - *y_low) / (*y_high - *y_low) * (plot_bottom - top);
  };
  const double zero_y = plot_bottom + zero_band / 2 + 2;
  const std::string clip = "clip-" + identifier(key);

  std::ostringstream svg;
  svg << "<svg class=\"plot\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width
      << "\" height=\"" << fixed(height) << "\" viewBox=\"0 0 " << width << " " << fixed(height)
      << "\" data-claim-plot=\"" << escape(key) << "\" data-series=\"" << all.size()
      << "\" role=\"img\" aria-label=\"log-log plot of the error against h for " << escape(key)
      << "\">\n";
  svg << "<title>" << escape(key) << ": error against h (log-log)</title>\n";
  svg << "<defs><clipPath id=\"" << clip << "\"><rect x=\"" << left << "\" y=\"" << top
      << "\" width=\"" << right - left << "\" height=\"" << plot_bottom - top
      << "\"/></clipPath></defs>\n";
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left << "\" height=\""
      << axis_bottom - top << "\" fill=\"#fbfcfe\" stroke=\"#c5ccd8\"/>\n";
  // Grid and ticks.
  svg << "<g class=\"tick\">\n";
  for (const auto& [x, label] : log_ticks(*x_low, *x_high)) {
    svg << "<line x1=\"" << fixed(px(x)) << "\" y1=\"" << top << "\" x2=\"" << fixed(px(x))
        << "\" y2=\"" << axis_bottom << "\" stroke=\"#e3e7ee\"/>";
    svg << "<text x=\"" << fixed(px(x)) << "\" y=\"" << axis_bottom + 17
        << "\" text-anchor=\"middle\">" << label << "</text>\n";
  }
  for (const auto& [y, label] : log_ticks(*y_low, *y_high)) {
    svg << "<line x1=\"" << left << "\" y1=\"" << fixed(py(y)) << "\" x2=\"" << right << "\" y2=\""
        << fixed(py(y)) << "\" stroke=\"#e3e7ee\"/>";
    svg << "<text x=\"" << left - 6 << "\" y=\"" << fixed(py(y) + 4) << "\" text-anchor=\"end\">"
        << label << "</text>\n";
  }
  svg << "</g>\n";
  svg << "<text x=\"" << (left + right) / 2 << "\" y=\"" << axis_bottom + 36
      << "\" text-anchor=\"middle\">step h</text>\n";
  svg << "<text transform=\"translate(16 " << (top + plot_bottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">error</text>\n";
  // The stated floor of the main series, when it falls inside the plotted range.
  if (std::isfinite(floor_log) && floor_log > *y_low && floor_log < *y_high) {
    svg << "<g data-floor=\"1\"><line x1=\"" << left << "\" y1=\"" << fixed(py(floor_log))
        << "\" x2=\"" << right << "\" y2=\"" << fixed(py(floor_log))
        << "\" stroke=\"#98a2b3\" stroke-dasharray=\"2 3\"/><text x=\"" << right - 4 << "\" y=\""
        << fixed(py(floor_log) - 4) << "\" text-anchor=\"end\" fill=\"#5b6576\">floor "
        << escape(short_decimal(text_of(series_list[0], "floor"), 3))
        << "</text><title>round-off / reference floor " << escape(text_of(series_list[0], "floor"))
        << "</title></g>\n";
  }
  // The zero band: errors that are exactly 0 have no logarithm; they are drawn here.
  if (any_zero) {
    svg << "<g data-zero-band=\"1\"><title>errors that are exactly 0 have no logarithm: "
           "they are drawn in this band at the plot floor</title><line x1=\""
        << left << "\" y1=\"" << plot_bottom << "\" x2=\"" << right << "\" y2=\"" << plot_bottom
        << "\" stroke=\"#5b6576\" stroke-dasharray=\"5 3\"/><text x=\"" << left - 6 << "\" y=\""
        << fixed(zero_y + 4) << "\" text-anchor=\"end\" fill=\"#5b6576\">0</text></g>\n";
  }
  // Fitted lines and predicted slopes, clipped to the plot area.
  svg << "<g clip-path=\"url(#" << clip << ")\">\n";
  if (!tolerance_line.empty()) {
    std::string path;
    for (const auto& [x, y] : tolerance_line)
      path += (path.empty() ? "M" : " L") + fixed(px(x)) + " " + fixed(py(y));
    svg << "<path data-tolerance-line=\"1\" d=\"" << path
        << "\" fill=\"none\" stroke=\"#a40e26\" stroke-width=\"1.5\" stroke-dasharray=\"4 "
           "3\"><title>the tolerance "
           "at each h: a value above it fails</title></path>\n";
  }
  for (const auto& s : all) {
    if (!s.order || !s.log10_constant) continue;
    double low = 1e300, high = -1e300, sum = 0;
    int count = 0;
    for (const auto& p : s.points)
      if (p.status == "used") {
        low = std::min(low, p.x);
        high = std::max(high, p.x);
        sum += p.x;
        ++count;
      }
    if (count == 0) continue;
    low -= 0.08;
    high += 0.08;
    auto fit_y = [&](double x) { return *s.log10_constant + *s.order * x; };
    svg << "<line data-fit=\"1\" x1=\"" << fixed(px(low)) << "\" y1=\"" << fixed(py(fit_y(low)))
        << "\" x2=\"" << fixed(px(high)) << "\" y2=\"" << fixed(py(fit_y(high))) << "\" stroke=\""
        << s.color << "\" stroke-width=\"2\"><title>least-squares fit: slope "
        << format_number(*s.order, 4) << "</title></line>\n";
    if (s.predicted) {
      double centre = sum / count;
      auto predicted_y = [&](double x) { return fit_y(centre) + *s.predicted * (x - centre); };
      svg << "<line data-predicted=\"1\" x1=\"" << fixed(px(low)) << "\" y1=\""
          << fixed(py(predicted_y(low))) << "\" x2=\"" << fixed(px(high)) << "\" y2=\""
          << fixed(py(predicted_y(high))) << "\" stroke=\"" << s.color
          << "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\" opacity=\"0.7\"><title>predicted "
             "slope "
          << format_number(*s.predicted, 4) << "</title></line>\n";
    }
  }
  svg << "</g>\n";
  // Points, each with its values and, when dropped, the reason.
  for (const auto& s : all) {
    svg << "<g data-series-label=\"" << escape(s.label) << "\">";
    std::string path;
    for (const auto& p : s.points)
      if (p.y) path += (path.empty() ? "M" : " L") + fixed(px(p.x)) + " " + fixed(py(*p.y));
    if (!path.empty())
      svg << "<path d=\"" << path << "\" fill=\"none\" stroke=\"" << s.color
          << "\" stroke-width=\"0.8\" opacity=\"0.45\"/>";
    for (const auto& p : s.points) {
      std::string title = escape(s.label) + " — point " + std::to_string(p.index) +
                          ": h = " + escape(p.h) + ", error = " + escape(p.error);
      if (p.status == "used") title += " — used in the fit";
      if (p.status == "dropped") title += " — dropped from the fit: " + escape(p.reason);
      if (p.status == "zero")
        title += " — error is exactly 0, drawn at the plot floor" +
                 (p.reason.empty() ? std::string() : " (dropped: " + escape(p.reason) + ")");
      if (p.status == "measured") title += " — measured (no order fit)";
      double x = px(p.x);
      svg << "\n<g data-point=\"" << p.status << "\"><title>" << title << "</title>";
      if (p.status == "zero") {
        svg << "<path d=\"M" << fixed(x - 5) << " " << fixed(zero_y - 4) << " L" << fixed(x + 5)
            << " " << fixed(zero_y - 4) << " L" << fixed(x) << " " << fixed(zero_y + 5)
            << " Z\" fill=\"#fff\" stroke=\"" << s.color << "\" stroke-width=\"1.6\"/>";
      } else {
        double y = py(*p.y);
        bool filled = p.status == "used" || p.status == "measured";
        svg << "<circle cx=\"" << fixed(x) << "\" cy=\"" << fixed(y) << "\" r=\"4.2\" fill=\""
            << (filled ? s.color : "#fff") << "\" stroke=\"" << s.color
            << "\" stroke-width=\"1.6\"/>";
        if (p.status == "dropped")
          svg << "<line x1=\"" << fixed(x - 4) << "\" y1=\"" << fixed(y + 4) << "\" x2=\""
              << fixed(x + 4) << "\" y2=\"" << fixed(y - 4) << "\" stroke=\"" << s.color << "\"/>";
      }
      svg << "</g>";
    }
    svg << "</g>\n";
  }
  // Legend: the key to the markers (the series are listed in HTML after the SVG).
  std::ostringstream legend;
  legend << "<ul class=\"legend\" data-legend-for=\"" << escape(key) << "\">";
  bool any_predicted = false;
  for (const auto& s : all) {
    std::string fit = s.per_step ? std::string("judged against its tolerance at each h (no order)")
                      : s.order
                          ? "fitted order " + format_number(*s.order, 3)
                          : (s.fit_failure.empty() ? "no order fit" : "no fit: " + s.fit_failure);
    if (s.predicted)
      fit += (s.exact ? ", predicted " : ", predicted ≥ ") + format_number(*s.predicted, 3);
    any_predicted = any_predicted || s.predicted.has_value();
    if (s.holds) fit += *s.holds ? " — holds" : " — fails";
    legend << "<li><span class=\"swatch\" style=\"background:" << s.color << "\"></span>"
           << escape(s.label) << " <span class=\"small\">" << escape(fit) << "</span></li>";
  }
  if (!tolerance_line.empty())
    legend << "<li><span class=\"swatch\" style=\"background:#a40e26; border-radius:0; "
              "height:3px\"></span>"
              "the tolerance at each h (dashed): a value above it fails</li>";
  legend << "</ul>";
  svg << "<g data-legend=\"1\">\n";
  double row = legend_top;
  const bool any_fit =
      std::any_of(all.begin(), all.end(), [](const PlotSeries& s) { return s.order.has_value(); });
  const char* filled_key = any_fit ? "used in the fit" : "measured";
  svg << "<g fill=\"#5b6576\"><circle cx=\"" << left + 5 << "\" cy=\"" << row - 4
      << "\" r=\"4\" fill=\"#5b6576\"/><text x=\"" << left + 14 << "\" y=\"" << row << "\">"
      << filled_key << "</text><circle cx=\"" << left + 125 << "\" cy=\"" << row - 4
      << "\" r=\"4\" fill=\"#fff\" stroke=\"#5b6576\" stroke-width=\"1.4\"/><text x=\""
      << left + 134 << "\" y=\"" << row << "\">dropped (hover: reason)</text><path d=\"M"
      << left + 300 << " " << row - 8 << " L" << left + 310 << " " << row - 8 << " L" << left + 305
      << " " << row + 1 << " Z\" fill=\"#fff\" stroke=\"#5b6576\" stroke-width=\"1.4\"/><text x=\""
      << left + 316 << "\" y=\"" << row << "\">error = 0 (at the plot floor)</text></g>\n";
  row += 18;
  svg << "<g fill=\"#5b6576\">";
  if (any_fit)
    svg << "<line x1=\"" << left << "\" y1=\"" << row - 4 << "\" x2=\"" << left + 22 << "\" y2=\""
        << row - 4 << "\" stroke=\"#5b6576\" stroke-width=\"2\"/><text x=\"" << left + 30
        << "\" y=\"" << row << "\">least-squares fit over the used points</text>";
  // A predicted slope is drawn (and keyed) only for a series that predicts an order.
  if (any_predicted)
    svg << "<line x1=\"" << left + 300 << "\" y1=\"" << row - 4 << "\" x2=\"" << left + 322
        << "\" y2=\"" << row - 4 << "\" stroke=\"#5b6576\" stroke-dasharray=\"6 4\"/><text x=\""
        << left + 330 << "\" y=\"" << row << "\">predicted slope</text>";
  svg << "</g>\n";
  svg << "</g>\n</svg>" << legend.str();
  return svg.str();
}

// h_max against the speed |w| (evidence "h_max_by_speed" of existence-uniqueness).
std::string render_speed_map(const json& claim, const std::string& key) {
  struct MapPoint {
    double x = 0;             // log10 |w|
    std::optional<double> y;  // log10 h_max; empty for h_max = 0
    std::string speed, h_max;
  };
  std::vector<MapPoint> points;
  const json evidence = claim.value("evidence", json::object());
  const json map = evidence.is_object() ? evidence.value("h_max_by_speed", json::array())
                                        : json::array();
  for (const auto& row : map) {
    MapPoint point;
    point.speed = text_of(row, "speed");
    point.h_max = text_of(row, "h_max");
    auto x = log10_decimal(point.speed);
    if (!x) continue;  // a speed of 0 cannot be placed on a log axis
    point.x = *x;
    point.y = log10_decimal(point.h_max);
    points.push_back(point);
  }
  if (points.empty()) return "";
  std::optional<double> x_low, x_high, y_low, y_high;
  bool any_zero = false;
  for (const auto& p : points) {
    x_low = std::min(x_low.value_or(p.x), p.x);
    x_high = std::max(x_high.value_or(p.x), p.x);
    if (p.y) {
      y_low = std::min(y_low.value_or(*p.y), *p.y);
      y_high = std::max(y_high.value_or(*p.y), *p.y);
    } else {
      any_zero = true;
    }
  }
  if (!y_low) {  // every h_max is 0
    y_low = -3;
    y_high = 0;
  }
  auto widen = [](std::optional<double>& low, std::optional<double>& high, double minimum_span,
                  double padding) {
    double span = *high - *low;
    if (span < minimum_span) {
      double middle = (*high + *low) / 2;
      *low = middle - minimum_span / 2;
      *high = middle + minimum_span / 2;
      span = minimum_span;
    }
    *low -= padding * span;
    *high += padding * span;
  };
  widen(x_low, x_high, 0.6, 0.06);
  widen(y_low, y_high, 1.0, 0.08);

  const double width = 640, left = 72, right = width - 24, top = 14, plot_bottom = 214;
  const double zero_band = any_zero ? 36 : 0, axis_bottom = plot_bottom + zero_band;
  const double legend_top = axis_bottom + 50, height = legend_top + 10;
  auto px = [&](double x) { return left + (x - *x_low) / (*x_high - *x_low) * (right - left); };
  auto py = [&](double y) {
    return plot_bottom - (y - *y_low) / (*y_high - *y_low) * (plot_bottom - top);
  };
  const double zero_y = plot_bottom + 23;  // the markers sit below the band's label
  const std::string color = series_colors[0];

  std::ostringstream svg;
  svg << "<svg class=\"plot map\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width
      << "\" height=\"" << fixed(height) << "\" viewBox=\"0 0 " << width << " " << fixed(height)
      << "\" data-claim-map=\"" << escape(key) << "\" role=\"img\" aria-label=\"log-log map of "
      << "h_max against the speed |w| for " << escape(key) << "\">\n";
  svg << "<title>" << escape(key) << ": h_max against the speed |w| (log-log)</title>\n";
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left << "\" height=\""
      << axis_bottom - top << "\" fill=\"#fbfcfe\" stroke=\"#c5ccd8\"/>\n";
  svg << "<g class=\"tick\">\n";
  for (const auto& [x, label] : log_ticks(*x_low, *x_high)) {
    svg << "<line x1=\"" << fixed(px(x)) << "\" y1=\"" << top << "\" x2=\"" << fixed(px(x))
        << "\" y2=\"" << axis_bottom << "\" stroke=\"#e3e7ee\"/>";
    svg << "<text x=\"" << fixed(px(x)) << "\" y=\"" << axis_bottom + 17
        << "\" text-anchor=\"middle\">" << label << "</text>\n";
  }
  for (const auto& [y, label] : log_ticks(*y_low, *y_high)) {
    svg << "<line x1=\"" << left << "\" y1=\"" << fixed(py(y)) << "\" x2=\"" << right << "\" y2=\""
        << fixed(py(y)) << "\" stroke=\"#e3e7ee\"/>";
    svg << "<text x=\"" << left - 6 << "\" y=\"" << fixed(py(y) + 4) << "\" text-anchor=\"end\">"
        << label << "</text>\n";
  }
  svg << "</g>\n";
  svg << "<text x=\"" << (left + right) / 2 << "\" y=\"" << axis_bottom + 36
      << "\" text-anchor=\"middle\">speed |w|</text>\n";
  svg << "<text transform=\"translate(16 " << (top + plot_bottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">h_max</text>\n";
  // The zero band: h_max = 0 (no step works at that speed) has no logarithm.
  if (any_zero)
    svg << "<g data-zero-band=\"1\"><title>h_max = 0 (no step h &gt; 0 works at that speed) has "
           "no logarithm: such speeds are drawn in this band</title><rect x=\""
        << left << "\" y=\"" << plot_bottom << "\" width=\"" << right - left << "\" height=\""
        << zero_band << "\" fill=\"#fde2e5\" opacity=\"0.7\"/><line x1=\"" << left << "\" y1=\""
        << plot_bottom << "\" x2=\"" << right << "\" y2=\"" << plot_bottom
        << "\" stroke=\"#a40e26\" stroke-dasharray=\"5 3\"/><text x=\"" << left - 6 << "\" y=\""
        << fixed(zero_y + 4) << "\" text-anchor=\"end\" style=\"fill:#a40e26\">0</text><text x=\""
        << left + 6 << "\" y=\"" << plot_bottom + 11
        << "\" style=\"fill:#a40e26; font-size:10.5px\">h_max = 0: no step h &gt; 0 works at this "
           "speed</text></g>\n";
  // Points joined in order of speed; a zero breaks the line.
  std::vector<const MapPoint*> sorted;
  for (const auto& p : points) sorted.push_back(&p);
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const MapPoint* a, const MapPoint* b) { return a->x < b->x; });
  std::string path;
  bool pen_down = false;
  for (const MapPoint* p : sorted) {
    if (!p->y) {
      pen_down = false;
      continue;
    }
    path += (path.empty() ? "" : " ") + std::string(pen_down ? "L" : "M") + fixed(px(p->x)) + " " +
            fixed(py(*p->y));
    pen_down = true;
  }
  if (!path.empty())
    svg << "<path data-map-line=\"1\" d=\"" << path << "\" fill=\"none\" stroke=\"" << color
        << "\" stroke-width=\"1.6\"/>\n";
  for (const MapPoint* p : sorted) {
    double x = px(p->x);
    svg << "<g data-map-point=\"" << (p->y ? "positive" : "zero") << "\"><title>|w| = "
        << escape(p->speed) << ", h_max = " << escape(p->h_max)
        << (p->y ? "" : " — no step h > 0 works at this speed") << "</title>";
    if (p->y)
      svg << "<circle cx=\"" << fixed(x) << "\" cy=\"" << fixed(py(*p->y))
          << "\" r=\"4.2\" fill=\"" << color << "\" stroke=\"" << color
          << "\" stroke-width=\"1.6\"/>";
    else
      svg << "<path d=\"M" << fixed(x - 5) << " " << fixed(zero_y - 5) << " L" << fixed(x + 5)
          << " " << fixed(zero_y - 5) << " L" << fixed(x) << " " << fixed(zero_y + 4)
          << " Z\" fill=\"#fff\" stroke=\"#a40e26\" stroke-width=\"1.6\"/>";
    svg << "</g>\n";
  }
  // Legend.
  const double row = legend_top;
  svg << "<g data-legend=\"1\"><circle cx=\"" << left + 5 << "\" cy=\"" << row - 4
      << "\" r=\"4\" fill=\"" << color << "\"/><text x=\"" << left + 14 << "\" y=\"" << row
      << "\">largest step h with a critical point near the diagonal</text>";
  if (any_zero)
    svg << "<path d=\"M" << left + 380 << " " << row - 8 << " L" << left + 390 << " " << row - 8
        << " L" << left + 385 << " " << row + 1
        << " Z\" fill=\"#fff\" stroke=\"#a40e26\" stroke-width=\"1.4\"/><text x=\"" << left + 396
        << "\" y=\"" << row << "\">h_max = 0 (in the band)</text>";
  svg << "</g>\n";
  svg << "</svg>";
  return svg.str();
}

std::string render_time_plot(const json& claim, const std::string& key) {
  const json evidence = claim.value("evidence", json::object());
  const json runs = evidence.is_object() ? evidence.value("energy_error_against_t", json::array())
                                         : json::array();
  struct Line {
    std::string h, N;
    std::vector<std::pair<double, double>> points;  // (t, log10 |e|); |e| = 0 is left out
    std::size_t zeros = 0;
  };
  std::vector<Line> lines;
  std::optional<double> t_high, y_low, y_high;
  for (const auto& run : runs) {
    if (!run.is_object()) continue;
    Line line;
    line.h = text_of(run, "h");
    line.N = run.value("N", json()).dump();
    const json t = run.value("t", json::array()), error = run.value("error", json::array());
    for (std::size_t i = 0; i < t.size() && i < error.size(); ++i) {
      if (!t[i].is_string() || !error[i].is_string()) continue;
      const auto y = log10_decimal(error[i].get<std::string>());
      double time = 0;
      try {
        time = std::stod(t[i].get<std::string>());
      } catch (const std::exception&) {
        continue;
      }
      if (!std::isfinite(time)) continue;
      if (!y) {
        ++line.zeros;
        continue;
      }
      line.points.emplace_back(time, *y);
      t_high = std::max(t_high.value_or(time), time);
      y_low = std::min(y_low.value_or(*y), *y);
      y_high = std::max(y_high.value_or(*y), *y);
    }
    lines.push_back(line);
  }
  if (lines.empty() || !t_high || !(*t_high > 0)) return "";
  const std::string quantity =
      text_of(claim, "id") == "modified-energy" ? "|H̃_k − H̃_0|" : "|E_k − E_0|";
  if (*y_high - *y_low < 1) *y_low = *y_high - 1;
  const double pad = 0.06 * (*y_high - *y_low);
  *y_low -= pad;
  *y_high += pad;
  const double width = 640, left = 72, right = width - 24, top = 14, plot_bottom = 214;
  const double height = plot_bottom + 50;
  auto px = [&](double t) { return left + t / *t_high * (right - left); };
  auto py = [&](double y) {
    return plot_bottom - (y - *y_low) / (*y_high - *y_low) * (plot_bottom - top);
  };
  std::ostringstream svg;
  svg << "<svg class=\"plot time\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width
      << "\" height=\"" << fixed(height) << "\" viewBox=\"0 0 " << width << " " << fixed(height)
      << "\" data-claim-time-plot=\"" << escape(key)
      << "\" role=\"img\" aria-label=\"energy error against t for " << escape(key) << "\">\n";
  svg << "<title>" << escape(key) << ": " << quantity << " against t, one line per h</title>\n";
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left << "\" height=\""
      << plot_bottom - top << "\" fill=\"#fbfcfe\" stroke=\"#c5ccd8\"/>\n<g class=\"tick\">\n";
  for (int i = 0; i <= 4; ++i) {  // t axis: linear, 0 … T in quarters
    const double t = *t_high * i / 4;
    svg << "<line x1=\"" << fixed(px(t)) << "\" y1=\"" << top << "\" x2=\"" << fixed(px(t))
        << "\" y2=\"" << plot_bottom << "\" stroke=\"#e3e7ee\"/><text x=\"" << fixed(px(t))
        << "\" y=\"" << plot_bottom + 17 << "\" text-anchor=\"middle\">" << format_number(t, 3)
        << "</text>\n";
  }
  for (const auto& [y, label] : log_ticks(*y_low, *y_high))
    svg << "<line x1=\"" << left << "\" y1=\"" << fixed(py(y)) << "\" x2=\"" << right << "\" y2=\""
        << fixed(py(y)) << "\" stroke=\"#e3e7ee\"/><text x=\"" << left - 6 << "\" y=\""
        << fixed(py(y) + 4) << "\" text-anchor=\"end\">" << label << "</text>\n";
  svg << "</g>\n<text x=\"" << (left + right) / 2 << "\" y=\"" << plot_bottom + 36
      << "\" text-anchor=\"middle\">t</text>\n<text transform=\"translate(16 "
      << (top + plot_bottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << quantity
      << "</text>\n";
  std::ostringstream legend;
  legend << "<ul class=\"legend\" data-legend-for-time=\"" << escape(key) << "\">";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string color = series_colors[i % series_colors.size()];
    std::string path;
    for (const auto& [t, y] : lines[i].points)
      path += (path.empty() ? "M" : " L") + fixed(px(t)) + " " + fixed(py(y));
    if (!path.empty())
      svg << "<path data-time-line=\"" << escape(lines[i].h) << "\" d=\"" << path
          << "\" fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1.3\"/>\n";
    legend << "<li><span class=\"swatch\" style=\"background:" << color
           << "\"></span>h = " << escape(lines[i].h) << " (N = " << escape(lines[i].N) << ")"
           << (lines[i].zeros ? " <span class=\"small\">" + std::to_string(lines[i].zeros) +
                                    " samples at exactly 0 left out</span>"
                              : std::string())
           << "</li>";
  }
  legend << "</ul>";
  svg << "</svg>";
  return svg.str() + legend.str();
}

std::string render_work_precision(const json& cases, const json& run, bool wall_time) {
  const json run_seconds =
      run.is_object() ? run.value("run_seconds", json::object()) : json::object();
  // Cases of one system, parameters, initial state and T: their global errors are comparable.
  struct Line {
    std::string name, discretization, order;
    std::vector<std::tuple<double, double, std::string>>
        points;  // log10 evaluations, log10 error, title
    std::optional<double> floor;
  };
  std::map<std::string, std::vector<Line>> groups;
  for (const auto& c : cases) {
    if (!c.is_object()) continue;
    const json file = c.value("case_file", json::object());
    const std::string group = text_of(c, "system") + " " + c.value("parameters", json()).dump() +
                              " " + c.value("initial", json()).dump() +
                              " T = " + c.value("T", json()).dump();
    // The cost of each N's run, log10: its evaluations of L, or its wall time.
    std::map<int, double> evaluations;
    if (!wall_time) {
      for (const auto& row : c.value("cost", json::array()))
        if (row.is_object() && row.value("L_evaluations", 0L) > 0)
          evaluations[row.value("N", 0)] =
              std::log10(static_cast<double>(row.value("L_evaluations", 0L)));
    } else if (run_seconds.is_object()) {
      for (const auto& row : run_seconds.value(text_of(c, "name"), json::array()))
        if (row.is_object() && row.value("seconds", 0.0) > 0)
          evaluations[row.value("N", 0)] = std::log10(row.value("seconds", 0.0));
    }
    if (evaluations.empty()) continue;
    for (const auto& claim : c.value("claims", json::array())) {
      if (text_of(claim, "id") != "global-order" || claim.value("series", json::array()).empty())
        continue;
      const json& s = claim["series"][0];
      Line line;
      line.name = text_of(c, "name");
      line.discretization =
          file.is_object() && file.contains("discretization") && file["discretization"].is_object()
              ? text_of(file["discretization"], "kind") + text_of(file["discretization"], "stepper")
              : "";
      line.order = s.value("observed_order", json()).is_number()
                       ? format_number(s["observed_order"].get<double>(), 3)
                       : "—";
      line.floor = log10_decimal(text_of(s, "floor"));
      const std::vector<int> steps =
          c.value("sweep", json::object()).value("steps_used", std::vector<int>{});
      const json h = s.value("h", json::array()), error = s.value("error", json::array());
      for (std::size_t i = 0; i < error.size() && i < steps.size(); ++i) {
        const auto e =
            error[i].is_string() ? log10_decimal(error[i].get<std::string>()) : std::nullopt;
        if (!e || !evaluations.count(steps[i])) continue;
        line.points.emplace_back(evaluations[steps[i]], *e,
                                 "N = " + std::to_string(steps[i]) + ": error " +
                                     error[i].get<std::string>().substr(0, 12) + ", 10^" +
                                     format_number(evaluations[steps[i]], 3) + " evaluations of L");
      }
      if (line.points.size() >= 2) groups[group].push_back(line);
    }
  }
  std::ostringstream out;
  int figure = 0;
  for (const auto& [group, lines] : groups) {
    if (lines.size() < 2) continue;  // one method alone is no comparison
    std::optional<double> x_low, x_high, y_low, y_high, floor;
    for (const auto& line : lines) {
      for (const auto& [x, y, title] : line.points) {
        x_low = std::min(x_low.value_or(x), x), x_high = std::max(x_high.value_or(x), x);
        y_low = std::min(y_low.value_or(y), y), y_high = std::max(y_high.value_or(y), y);
      }
      if (line.floor) floor = std::max(floor.value_or(*line.floor), *line.floor);
    }
    if (*x_high - *x_low < 0.5) *x_high = *x_low + 0.5;
    if (*y_high - *y_low < 1) *y_low = *y_high - 1;
    if (floor && *floor > *y_low - 1 && *floor < *y_high) *y_low = std::min(*y_low, *floor - 0.5);
    const double px_pad = 0.05 * (*x_high - *x_low), py_pad = 0.06 * (*y_high - *y_low);
    *x_low -= px_pad, *x_high += px_pad, *y_low -= py_pad, *y_high += py_pad;
    const double width = 640, left = 72, right = width - 24, top = 14, bottom = 244,
                 height = bottom + 50;
    auto px = [&](double x) { return left + (x - *x_low) / (*x_high - *x_low) * (right - left); };
    auto py = [&](double y) { return bottom - (y - *y_low) / (*y_high - *y_low) * (bottom - top); };
    out << "<figure class=\"work-precision\"><svg class=\"plot wp\" "
           "xmlns=\"http://www.w3.org/2000/svg\" width=\""
        << width << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " " << height
        << "\" data-work-precision=\"" << (wall_time ? "seconds-" : "evaluations-") << figure++
        << "\" role=\"img\" aria-label=\"work-precision diagram\">\n"
        << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left
        << "\" height=\"" << bottom - top << "\" fill=\"#fbfcfe\" stroke=\"#c5ccd8\"/>\n";
    if (floor && *floor > *y_low)
      out << "<rect data-floor=\"1\" x=\"" << left << "\" y=\""
          << fixed(py(std::min(*floor, *y_high))) << "\" width=\"" << right - left << "\" height=\""
          << fixed(bottom - py(std::min(*floor, *y_high)))
          << "\" fill=\"#e9ecf2\"><title>below the floor: errors here cannot be told from rounding "
             "or the "
             "reference's own error</title></rect>\n";
    out << "<g class=\"tick\">";
    for (const auto& [x, label] : log_ticks(*x_low, *x_high))
      out << "<line x1=\"" << fixed(px(x)) << "\" y1=\"" << top << "\" x2=\"" << fixed(px(x))
          << "\" y2=\"" << bottom << "\" stroke=\"#e3e7ee\"/><text x=\"" << fixed(px(x))
          << "\" y=\"" << bottom + 17 << "\" text-anchor=\"middle\">" << label << "</text>";
    for (const auto& [y, label] : log_ticks(*y_low, *y_high))
      out << "<line x1=\"" << left << "\" y1=\"" << fixed(py(y)) << "\" x2=\"" << right
          << "\" y2=\"" << fixed(py(y)) << "\" stroke=\"#e3e7ee\"/><text x=\"" << left - 6
          << "\" y=\"" << fixed(py(y) + 4) << "\" text-anchor=\"end\">" << label << "</text>";
    out << "</g>\n<text x=\"" << (left + right) / 2 << "\" y=\"" << bottom + 36
        << "\" text-anchor=\"middle\">"
        << (wall_time ? "wall time of the run, s (this machine)"
                      : "evaluations of L (the run's cost, counted)")
        << "</text>\n<text "
           "transform=\"translate(16 "
        << (top + bottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">|q_N − q(T)|</text>\n";
    std::ostringstream legend;
    legend << "<ul class=\"legend\">";
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string color = series_colors[i % series_colors.size()];
      std::string path;
      for (const auto& [x, y, title] : lines[i].points)
        path += (path.empty() ? "M" : " L") + fixed(px(x)) + " " + fixed(py(y));
      out << "<path data-wp-line=\"" << escape(lines[i].name) << "\" d=\"" << path
          << "\" fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1.6\"/>";
      for (const auto& [x, y, title] : lines[i].points)
        out << "<circle cx=\"" << fixed(px(x)) << "\" cy=\"" << fixed(py(y))
            << "\" r=\"3.5\" fill=\"" << color << "\"><title>"
            << escape(lines[i].name + ", " + title) << "</title></circle>";
      out << "\n";
      legend << "<li><span class=\"swatch\" style=\"background:" << color << "\"></span>"
             << escape(lines[i].name) << " <span class=\"small\">"
             << escape(lines[i].discretization) << ", fitted order " << lines[i].order
             << "</span></li>";
    }
    legend << "</ul>";
    out << "</svg>" << legend.str() << "<figcaption>" << escape(group)
        << ": the global error against "
        << (wall_time ? "the wall time of each run on the machine that ran it"
                      : "the evaluations of L each run made (the same on any machine)")
        << " (log-log; shaded: below the floor). Lower and further left is "
           "better.</figcaption></figure>\n";
  }
  return out.str();
}

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
  // A passing claim's plot, series and evidence are collapsed (the findings row says what it
  // showed; the default suite then prints in a few dozen pages, not 139); a claim that needs
  // attention opens with them.
  const bool collapsed = verdict == "pass" || verdict == "xfail";
  out << "<details class=\"claim-details\"" << (collapsed ? "" : " open")
      << "><summary>plot, series, points and "
      << "evidence</summary>\n";
  out << "<div class=\"claim-body\"><div>" << render_claim_plot(claim, key);
  bool any_zero = false;
  for (const auto& s : claim.value("series", json::array()))
    for (const auto& e : s.value("error", json::array()))
      any_zero = any_zero || (e.is_string() && !log10_decimal(e.get<std::string>()));
  if (any_zero)
    out << "<p class=\"note\">Errors that are exactly 0 have no logarithm: they are drawn on the "
           "dashed line at the bottom of the plot (the plot floor), not at their value.</p>";
  out << speed_map_figure(claim, key);
  if (const std::string time_plot = render_time_plot(claim, key); !time_plot.empty())
    out << "<figure class=\"time\">" << time_plot << "<figcaption>"
        << (text_of(claim, "id") == "modified-energy" ? "The modified energy's" : "The energy")
        << " error against t at each h (the largest in each of about 200 runs of steps): a drift "
           "grows "
           "with t, a symplectic method's error stays in a band that shrinks with "
           "h.</figcaption></figure>";
  out << "</div><div>\n<dl class=\"facts\"><dt>prediction</dt><dd>" << predicted_html(claim)
      << " — " << escape(text_of(claim, "prediction")) << "</dd><dt>observed</dt><dd>"
      << observed_html(claim) << "</dd><dt>verdict</dt><dd>" << verdict_badge(verdict) << " "
      << escape(text_of(claim, "explanation")) << "</dd>";
  if (!text_of(claim, "detection_limit").empty())
    out << "<dt>detection limit</dt><dd>" << escape(text_of(claim, "detection_limit")) << "</dd>";
  out << "</dl>\n";
  out << series_table(claim) << "\n";
  out << "<details><summary>points: h, error, used or dropped</summary>" << points_table(claim)
      << "</details>\n";
  out << "<details><summary>evidence</summary>"
      << value_html(claim.value("evidence", json::object())) << "</details>\n";
  out << "</div></div></details></section>\n";
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
  if (!refused.empty()) {
    counts += ", " + std::to_string(refused.size()) + " refused";
    badges += "<a class=\"verdict v-error\" data-count=\"refused\" href=\"#attention\">" +
              std::to_string(refused.size()) + " refused</a>";
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
    attention << "<li data-attention=\"refused\"><span class=\"verdict v-error\">refused</span> <b>"
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
    const json series = claim->value("series", json::array());
    const std::size_t decisive = claim->value("decisive_series", 0);
    attention << "<li data-attention=\"" << escape(verdict) << "\" data-attention-claim=\""
              << escape(key) << "\">" << verdict_badge(verdict) << " <a href=\"#" << anchor << "\">"
              << escape(key) << "</a>";
    if (decisive < series.size())
      attention << " <span class=\"small\">decided by "
                << escape(text_of(series[decisive], "label")) << "</span>";
    attention << ": " << escape(text_of(*claim, "explanation")) << "</li>\n";
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
  page << "<table class=\"findings\"><colgroup><col style=\"width:13%\"><col style=\"width:11%\">"
          "<col style=\"width:11%\"><col style=\"width:25%\"><col style=\"width:11%\">"
          "<col style=\"width:7%\"><col style=\"width:22%\"></colgroup>"
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
