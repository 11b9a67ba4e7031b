// The energy error against t for each h: a drift, a bounded oscillation and their envelope.
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


namespace {

// Ticks 0, s, 2s, … on [0, high] with s one of 1, 2, 2.5, 5 times a power of ten and four to
// eight intervals, the last tick at or past high: T = 10 sampled to 9.99 reads 0, 2, 4, …, 10,
// not 0, 2.5, 4.99, 7.49, 9.99. Returns the ticks and the axis' end (the last tick).
std::pair<Ticks, double> time_ticks(double high) {
  const double magnitude = std::pow(10.0, std::floor(std::log10(high / 4)));
  double step = 10 * magnitude;
  for (const double factor : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (high / (factor * magnitude) <= 8.0 + 1e-9) {
      step = factor * magnitude;
      break;
    }
  const int intervals = static_cast<int>(std::ceil(high / step - 1e-9));
  Ticks ticks;
  for (int i = 0; i <= intervals; ++i) ticks.push_back({i * step, format_number(i * step, 4)});
  return {ticks, intervals * step};
}

}  // namespace

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
      extend(y_low, y_high, *y);
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
  // t on a linear axis from 0, the error on a log axis.
  const auto [t_ticks, t_end] = time_ticks(*t_high);
  const PlotAxes axes{left, right, top, plot_bottom, plot_bottom, 0, t_end, *y_low, *y_high};
  std::ostringstream svg;
  svg << "<svg class=\"plot time\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width
      << "\" height=\"" << fixed(height) << "\" viewBox=\"0 0 " << width << " " << fixed(height)
      << "\" data-claim-time-plot=\"" << escape(key)
      << "\" role=\"img\" aria-label=\"energy error against t for " << escape(key) << "\">\n";
  svg << "<title>" << escape(key) << ": " << quantity << " against t, one line per h</title>\n";
  write_background(svg, axes);
  write_grid(svg, axes, t_ticks, log_ticks(*y_low, *y_high), "\n");
  write_axis_titles(svg, axes, "t", quantity);
  std::ostringstream legend;
  legend << "<ul class=\"legend\" data-legend-for-time=\"" << escape(key) << "\">";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string color = series_colors[i % series_colors.size()];
    std::string path;
    for (const auto& [t, y] : lines[i].points)
      path += (path.empty() ? "M" : " L") + fixed(axes.px(t)) + " " + fixed(axes.py(y));
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

}  // namespace vivv
