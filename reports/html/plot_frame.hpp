// What the report page and its plots share (reports/html_report.cpp, reports/html/*.cpp): a
// report's strings, escaping, the series colours, and the frame of a plot — its points, its
// series, its decade ticks and its axes (the box, the grid with its tick labels, the titles).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/report_text.hpp"

namespace vivv::html {

using nlohmann::json;

inline const std::vector<std::string> series_colors = {"#1565c0", "#e07b00", "#7b1fa2",
                                                "#00897b", "#6d4c41", "#c2185b"};

inline std::string text_of(const json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_string()
             ? object[key].get<std::string>()
             : "";
}

inline std::string escape(const std::string& text) { return xml_escape(text); }

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
  bool inconclusive = false;  // holds is false because the evidence cannot decide
  std::string fit_failure;
  // A value judged against its own tolerance at each h (an identity, a conserved quantity): no
  // order is fitted or drawn for it.
  bool per_step = false;
};

// The steps at which a series' value was not measured, only recorded as 0: energy-behaviour's
// drift where the run had too few returns of the motion ("short") or its energy error sat at the
// rounding floor ("floor") — evidence.per_step's status. Such a point is not drawn (a 0 there is no
// measurement of a drift of 0); the page says so under the plot.
inline std::set<std::string> unmeasured_steps(const json& claim, const json& series) {
  std::set<std::string> steps;
  if (text_of(series, "rule") != "energy-drift") return steps;
  const json evidence = claim.value("evidence", json::object());
  if (!evidence.is_object()) return steps;
  for (const auto& row : evidence.value("per_step", json::array()))
    if (row.is_object() && (text_of(row, "status") == "short" || text_of(row, "status") == "floor"))
      steps.insert(text_of(row, "h"));
  return steps;
}

inline PlotSeries plot_series(const json& series, const std::string& color,
                              const std::set<std::string>& unmeasured = {}) {
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
    if (unmeasured.count(point.h)) continue;  // not measured: no point, not a 0
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
  out.inconclusive = series.value("inconclusive", false);
  out.fit_failure = text_of(series, "fit_failure");
  return out;
}

// Tick positions (log10) over [low, high]: decades, thinned to at most ~7,
// with 2 and 5 multiples added when fewer than two decades fall in range.
// A report may hold any decimal ("1e-20000000000" is 2·10¹⁰ decades below 1): the step and the
// decades are 64-bit, so the count stays at most ~8 whatever the range.
inline std::vector<std::pair<double, std::string>> log_ticks(double low, double high) {
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

inline std::string identifier(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return out;
}

inline std::string fixed(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", x);
  return buffer;
}

// --- The axes every plot draws ---------------------------------------------

// A plot's box on the page and the ranges of its axes (log10 values on a log axis): data at
// (x, y) is drawn at (px(x), py(y)). The background and the vertical grid lines reach down to
// axis_bottom, which lies below plot_bottom when a band (values that have no logarithm) sits
// under the data.
struct PlotAxes {
  double left = 0, right = 0, top = 0, plot_bottom = 0, axis_bottom = 0;
  double x_low = 0, x_high = 1, y_low = 0, y_high = 1;
  double px(double x) const { return left + (x - x_low) / (x_high - x_low) * (right - left); }
  double py(double y) const {
    return plot_bottom - (y - y_low) / (y_high - y_low) * (plot_bottom - top);
  }
};

using Ticks = std::vector<std::pair<double, std::string>>;

// [low, high] extended to take in v (both empty before the first value).
inline void extend(std::optional<double>& low, std::optional<double>& high, double v) {
  low = std::min(low.value_or(v), v);
  high = std::max(high.value_or(v), v);
}

// [low, high] widened to at least `minimum_span` about its middle, then padded by `padding`
// times its span on each side (log10 units on a log axis).
inline void widen(std::optional<double>& low, std::optional<double>& high, double minimum_span,
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
}

// The plot's background.
inline void write_background(std::ostream& svg, const PlotAxes& axes) {
  svg << "<rect x=\"" << axes.left << "\" y=\"" << axes.top << "\" width=\"" << axes.right - axes.left
      << "\" height=\"" << axes.axis_bottom - axes.top << "\" fill=\"#fbfcfe\" stroke=\"#c5ccd8\"/>\n";
}

// The grid with its tick labels, x below the box and y to its left; `between` follows each tick
// ("\n" keeps the page's source readable, "" keeps a figure's source on few lines).
inline void write_grid(std::ostream& svg, const PlotAxes& axes, const Ticks& x_ticks,
                       const Ticks& y_ticks, const char* between) {
  svg << "<g class=\"tick\">" << between;
  for (const auto& [x, label] : x_ticks)
    svg << "<line x1=\"" << fixed(axes.px(x)) << "\" y1=\"" << axes.top << "\" x2=\""
        << fixed(axes.px(x)) << "\" y2=\"" << axes.axis_bottom << "\" stroke=\"#e3e7ee\"/><text x=\""
        << fixed(axes.px(x)) << "\" y=\"" << axes.axis_bottom + 17 << "\" text-anchor=\"middle\">"
        << label << "</text>" << between;
  for (const auto& [y, label] : y_ticks)
    svg << "<line x1=\"" << axes.left << "\" y1=\"" << fixed(axes.py(y)) << "\" x2=\"" << axes.right
        << "\" y2=\"" << fixed(axes.py(y)) << "\" stroke=\"#e3e7ee\"/><text x=\"" << axes.left - 6
        << "\" y=\"" << fixed(axes.py(y) + 4) << "\" text-anchor=\"end\">" << label << "</text>"
        << between;
  svg << "</g>\n";
}

// The axes' titles: x centred below the tick labels, y turned along the left edge.
inline void write_axis_titles(std::ostream& svg, const PlotAxes& axes, const std::string& x_title,
                              const std::string& y_title) {
  svg << "<text x=\"" << (axes.left + axes.right) / 2 << "\" y=\"" << axes.axis_bottom + 36
      << "\" text-anchor=\"middle\">" << x_title << "</text>\n<text transform=\"translate(16 "
      << (axes.top + axes.plot_bottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << y_title
      << "</text>\n";
}

}  // namespace vivv::html
