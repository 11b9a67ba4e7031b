// A claim's log-log plot of error against h: every series, the floor, the fitted lines.
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
#include "reports/html/plot_frame.hpp"

namespace vivv {

using namespace html;

std::string render_claim_plot(const json& claim, const std::string& key) {
  std::vector<PlotSeries> all;
  const json series_list = claim.value("series", json::array());
  for (std::size_t i = 0; i < series_list.size(); ++i)
    all.push_back(plot_series(series_list[i], series_colors[i % series_colors.size()],
                              unmeasured_steps(claim, series_list[i])));

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

  // --baseline: the baseline report's points of each compared series (claim.baseline.series[k]
  // .baseline_h / baseline_error), drawn hollow and dashed beside this run's.
  struct BaselinePoints {
    std::string label, color;
    std::vector<std::tuple<double, double, std::string>> points;  // log10 h, log10 error, title
  };
  std::vector<BaselinePoints> baselines;
  const json baseline = claim.value("baseline", json::object());
  if (baseline.is_object())
    for (const auto& row : baseline.value("series", json::array())) {
      if (!row.is_object() || !row.contains("baseline_h") || !row.contains("baseline_error")) continue;
      BaselinePoints b;
      b.label = text_of(row, "label");
      for (std::size_t i = 0; i < series_list.size(); ++i)
        if (text_of(series_list[i], "label") == b.label) b.color = series_colors[i % series_colors.size()];
      if (b.color.empty()) continue;
      const json h = row["baseline_h"], error = row["baseline_error"];
      const auto at = [](const json& values, std::size_t i) {
        return values.is_array() && i < values.size() && values[i].is_string() ? values[i].get<std::string>()
                                                                               : std::string();
      };
      for (std::size_t i = 0; h.is_array() && i < h.size(); ++i) {
        const auto x = log10_decimal(at(h, i)), y = log10_decimal(at(error, i));
        if (x && y)
          b.points.emplace_back(*x, *y, "baseline: h = " + short_decimal(at(h, i), 6) +
                                            ", error = " + short_decimal(at(error, i), 4));
      }
      if (!b.points.empty()) baselines.push_back(std::move(b));
    }

  // Ranges in log10.
  std::optional<double> x_low, x_high, y_low, y_high;
  for (const auto& [x, y] : tolerance_line) extend(y_low, y_high, y);
  for (const auto& b : baselines)
    for (const auto& [x, y, title] : b.points) extend(x_low, x_high, x), extend(y_low, y_high, y);
  bool any_zero = false;
  for (const auto& s : all)
    for (const auto& p : s.points) {
      extend(x_low, x_high, p.x);
      if (p.y) extend(y_low, y_high, *p.y);
      any_zero = any_zero || !p.y;
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
  widen(x_low, x_high, 0.6, 0.06);
  widen(y_low, y_high, 1.0, 0.08);

  // Geometry: plot area, then the zero band below it, axis labels and legend.
  const double width = 640, left = 72, right = width - 24, top = 14, plot_bottom = 264;
  const double zero_band = any_zero ? 26 : 0, axis_bottom = plot_bottom + zero_band;
  // The marker key in the SVG (two rows of fixed text); the series' legend, whose labels and fit
  // notes can be long, is HTML below the plot, where it wraps instead of being clipped.
  std::size_t legend_rows = 2;
  const double legend_top = axis_bottom + 50, height = legend_top + 18.0 * legend_rows + 6;
  const PlotAxes axes{left, right, top, plot_bottom, axis_bottom, *x_low, *x_high, *y_low, *y_high};
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
  write_background(svg, axes);
  write_grid(svg, axes, log_ticks(*x_low, *x_high), log_ticks(*y_low, *y_high), "\n");
  write_axis_titles(svg, axes, "step h", "error");
  // The stated floor of the main series, when it falls inside the plotted range.
  if (std::isfinite(floor_log) && floor_log > *y_low && floor_log < *y_high) {
    svg << "<g data-floor=\"1\"><line x1=\"" << left << "\" y1=\"" << fixed(axes.py(floor_log))
        << "\" x2=\"" << right << "\" y2=\"" << fixed(axes.py(floor_log))
        << "\" stroke=\"#98a2b3\" stroke-dasharray=\"2 3\"/><text x=\"" << right - 4 << "\" y=\""
        << fixed(axes.py(floor_log) - 4) << "\" text-anchor=\"end\" fill=\"#5b6576\">floor "
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
      path += (path.empty() ? "M" : " L") + fixed(axes.px(x)) + " " + fixed(axes.py(y));
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
    svg << "<line data-fit=\"1\" x1=\"" << fixed(axes.px(low)) << "\" y1=\"" << fixed(axes.py(fit_y(low)))
        << "\" x2=\"" << fixed(axes.px(high)) << "\" y2=\"" << fixed(axes.py(fit_y(high))) << "\" stroke=\""
        << s.color << "\" stroke-width=\"2\"><title>least-squares fit: slope "
        << format_number(*s.order, 4) << "</title></line>\n";
    if (s.predicted) {
      double centre = sum / count;
      auto predicted_y = [&](double x) { return fit_y(centre) + *s.predicted * (x - centre); };
      svg << "<line data-predicted=\"1\" x1=\"" << fixed(axes.px(low)) << "\" y1=\""
          << fixed(axes.py(predicted_y(low))) << "\" x2=\"" << fixed(axes.px(high)) << "\" y2=\""
          << fixed(axes.py(predicted_y(high))) << "\" stroke=\"" << s.color
          << "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\" opacity=\"0.7\"><title>predicted "
             "slope "
          << format_number(*s.predicted, 4) << "</title></line>\n";
    }
  }
  svg << "</g>\n";
  // The baseline's points: hollow squares on a dashed line, in their series' colour.
  for (const auto& b : baselines) {
    std::string path;
    for (const auto& [x, y, title] : b.points)
      path += (path.empty() ? "M" : " L") + fixed(axes.px(x)) + " " + fixed(axes.py(y));
    svg << "<g data-baseline-series=\"" << escape(b.label) << "\"><path d=\"" << path
        << "\" fill=\"none\" stroke=\"" << b.color
        << "\" stroke-width=\"1\" stroke-dasharray=\"3 3\" opacity=\"0.7\"/>";
    for (const auto& [x, y, title] : b.points)
      svg << "<rect data-baseline-point=\"1\" x=\"" << fixed(axes.px(x) - 3.5) << "\" y=\""
          << fixed(axes.py(y) - 3.5) << "\" width=\"7\" height=\"7\" fill=\"#fff\" stroke=\"" << b.color
          << "\" stroke-width=\"1.4\"><title>" << escape(b.label + " — " + title) << "</title></rect>";
    svg << "</g>\n";
  }
  // Points, each with its values and, when dropped, the reason.
  for (const auto& s : all) {
    svg << "<g data-series-label=\"" << escape(s.label) << "\">";
    std::string path;
    for (const auto& p : s.points)
      if (p.y) path += (path.empty() ? "M" : " L") + fixed(axes.px(p.x)) + " " + fixed(axes.py(*p.y));
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
      double x = axes.px(p.x);
      svg << "\n<g data-point=\"" << p.status << "\"><title>" << title << "</title>";
      if (p.status == "zero") {
        svg << "<path d=\"M" << fixed(x - 5) << " " << fixed(zero_y - 4) << " L" << fixed(x + 5)
            << " " << fixed(zero_y - 4) << " L" << fixed(x) << " " << fixed(zero_y + 5)
            << " Z\" fill=\"#fff\" stroke=\"" << s.color << "\" stroke-width=\"1.6\"/>";
      } else {
        double y = axes.py(*p.y);
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
  // global-order draws its global series and the one step it includes on one axis: each says
  // which it is (a one-step error is one order higher than the global one).
  const auto one_step = [](const PlotSeries& s) { return s.label.rfind("one step: ", 0) == 0; };
  const bool mixed = std::any_of(all.begin(), all.end(), one_step) &&
                     !std::all_of(all.begin(), all.end(), one_step);
  for (const auto& s : all) {
    std::string fit = s.per_step ? std::string("judged against its tolerance at each h (no order)")
                      : s.order
                          ? "fitted order " + format_number(*s.order, 3)
                          : (s.fit_failure.empty() ? "no order fit" : "no fit: " + s.fit_failure);
    if (s.predicted)
      fit += (s.exact ? ", predicted " : ", predicted ≥ ") + format_number(*s.predicted, 3);
    any_predicted = any_predicted || s.predicted.has_value();
    if (s.holds) fit += *s.holds ? " — holds" : s.inconclusive ? " — inconclusive" : " — fails";
    legend << "<li><span class=\"swatch\" style=\"background:" << s.color << "\"></span>"
           << (!mixed      ? std::string()
               : one_step(s) ? std::string("<b>one step</b> (the local error from a state of the orbit): ")
                             : std::string("<b>global</b> (the error after N steps, at T): "))
           << escape(s.label) << " <span class=\"small\">" << escape(fit) << "</span></li>";
  }
  if (!baselines.empty())
    legend << "<li><span class=\"swatch\" style=\"background:#fff; border:1.4px solid #5b6576; "
              "border-radius:0\"></span>the baseline report's errors (hollow squares, dashed), "
              "beside this run's</li>";
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

}  // namespace vivv
