// existence-uniqueness's map of the largest working step h_max against the speed |w|.
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
    extend(x_low, x_high, p.x);
    if (p.y) extend(y_low, y_high, *p.y);
    any_zero = any_zero || !p.y;
  }
  if (!y_low) {  // every h_max is 0
    y_low = -3;
    y_high = 0;
  }
  widen(x_low, x_high, 0.6, 0.06);
  widen(y_low, y_high, 1.0, 0.08);

  const double width = 640, left = 72, right = width - 24, top = 14, plot_bottom = 214;
  const double zero_band = any_zero ? 36 : 0, axis_bottom = plot_bottom + zero_band;
  const double legend_top = axis_bottom + 50, height = legend_top + 10;
  const PlotAxes axes{left, right, top, plot_bottom, axis_bottom, *x_low, *x_high, *y_low, *y_high};
  const double zero_y = plot_bottom + 23;  // the markers sit below the band's label
  const std::string color = series_colors[0];

  std::ostringstream svg;
  svg << "<svg class=\"plot map\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width
      << "\" height=\"" << fixed(height) << "\" viewBox=\"0 0 " << width << " " << fixed(height)
      << "\" data-claim-map=\"" << escape(key) << "\" role=\"img\" aria-label=\"log-log map of "
      << "h_max against the speed |w| for " << escape(key) << "\">\n";
  svg << "<title>" << escape(key) << ": h_max against the speed |w| (log-log)</title>\n";
  write_background(svg, axes);
  write_grid(svg, axes, log_ticks(*x_low, *x_high), log_ticks(*y_low, *y_high), "\n");
  write_axis_titles(svg, axes, "speed |w|", "h_max");
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
    path += (path.empty() ? "" : " ") + std::string(pen_down ? "L" : "M") + fixed(axes.px(p->x)) + " " +
            fixed(axes.py(*p->y));
    pen_down = true;
  }
  if (!path.empty())
    svg << "<path data-map-line=\"1\" d=\"" << path << "\" fill=\"none\" stroke=\"" << color
        << "\" stroke-width=\"1.6\"/>\n";
  for (const MapPoint* p : sorted) {
    double x = axes.px(p->x);
    svg << "<g data-map-point=\"" << (p->y ? "positive" : "zero") << "\"><title>|w| = "
        << escape(p->speed) << ", h_max = " << escape(p->h_max)
        << (p->y ? "" : " — no step h > 0 works at this speed") << "</title>";
    if (p->y)
      svg << "<circle cx=\"" << fixed(x) << "\" cy=\"" << fixed(axes.py(*p->y))
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

}  // namespace vivv
