// The work-precision diagram: error against cost (evaluations of L, or wall time) over the cases.
#include "reports/html_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
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

// "(1, 2, 3, … 7 values)": a list of numbers in words, the first three of a long one.
std::string numbers_in_words(const std::vector<std::string>& values) {
  std::string list;
  const std::size_t shown = values.size() > 6 ? 3 : values.size();
  for (std::size_t i = 0; i < shown; ++i) list += (i ? ", " : "") + values[i];
  if (shown < values.size()) list += ", … " + std::to_string(values.size()) + " values";
  return "(" + list + ")";
}

std::string number_in_words(const json& value) {
  return value.is_string() ? short_decimal(value.get<std::string>(), 6) : value.dump();
}

// "pendulum (k = 1), q = (1.1), w = (0.25), T = 4": the problem a group of cases shares. A family
// of parameters (m[1] … m[7]) reads "m = (1, 2, 3, … 7 values)", and so does a long state.
std::string problem_in_words(const json& c) {
  std::string text = text_of(c, "system");
  const json parameters = c.value("parameters", json());
  if (parameters.is_object() && !parameters.empty()) {
    // In the report's (sorted) order of names; a family's members by their index: an array as the
    // case writes it, or (a report of an earlier vivv) keys m[1], m[2], … (m[2] before m[10]).
    std::vector<std::pair<std::string, std::vector<std::pair<long, std::string>>>> named;
    for (const auto& [name, value] : parameters.items()) {
      if (value.is_array()) {
        named.push_back({name, {}});
        for (std::size_t i = 0; i < value.size(); ++i)
          named.back().second.push_back({static_cast<long>(i + 1), number_in_words(value[i])});
        continue;
      }
      const std::size_t bracket = name.find('[');
      const std::string family = name.substr(0, bracket);
      if (named.empty() || named.back().first != family || bracket == std::string::npos) named.push_back({family, {}});
      const long index = bracket == std::string::npos ? 0 : std::strtol(name.c_str() + bracket + 1, nullptr, 10);
      named.back().second.push_back({index, number_in_words(value)});
    }
    std::string list;
    for (auto& [name, members] : named) {
      std::stable_sort(members.begin(), members.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      std::vector<std::string> values;
      for (const auto& member : members) values.push_back(member.second);
      list += (list.empty() ? "" : ", ") + name + " = " + (values.size() == 1 ? values[0] : numbers_in_words(values));
    }
    text += " (" + list + ")";
  }
  const json initial = c.value("initial", json());
  for (const char* key : {"q", "w"})
    if (initial.is_object() && initial.contains(key) && initial[key].is_array()) {
      std::vector<std::string> values;
      for (const auto& value : initial[key]) values.push_back(number_in_words(value));
      text += std::string(", ") + key + " = " + numbers_in_words(values);
    }
  const json T = c.value("T", json());
  text += ", T = " + number_in_words(T);
  return text;
}

}  // namespace

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
  // Per group: its caption (the problem in words), how many cases have a global error to draw,
  // and those whose cost is not known (a program's map: its evaluations of L are not counted).
  std::map<std::string, std::string> captions;
  std::map<std::string, int> members;
  std::map<std::string, std::vector<std::string>> uncounted;
  // Per group: the programs whose own count of evaluations (protocol extension "evaluations")
  // is their cost, by name.
  std::map<std::string, std::vector<std::string>> self_counted;
  for (const auto& c : cases) {
    if (!c.is_object()) continue;
    const json file = c.value("case_file", json::object());
    const std::string group = text_of(c, "system") + " " + c.value("parameters", json()).dump() +
                              " " + c.value("initial", json()).dump() +
                              " T = " + c.value("T", json()).dump();
    const json claims = c.value("claims", json::array());
    if (std::none_of(claims.begin(), claims.end(), [](const json& claim) {
          return text_of(claim, "id") == "global-order" && !claim.value("series", json::array()).empty();
        }))
      continue;
    ++members[group];
    captions[group] = problem_in_words(c);
    // The cost of each N's run, log10: its evaluations of L, or its wall time.
    std::map<int, double> evaluations;
    bool program_counted = false;
    if (!wall_time) {
      for (const auto& row : c.value("cost", json::array())) {
        if (!row.is_object()) continue;
        if (row.contains("L_evaluations") && row["L_evaluations"].is_number() &&
            row["L_evaluations"].get<double>() > 0)
          evaluations[row.value("N", 0)] = std::log10(row["L_evaluations"].get<double>());
        else if (row.contains("program_evaluations") && row["program_evaluations"].is_number() &&
                 row["program_evaluations"].get<double>() > 0) {
          evaluations[row.value("N", 0)] = std::log10(row["program_evaluations"].get<double>());
          program_counted = true;
        }
      }
      if (program_counted) self_counted[group].push_back(text_of(c, "name"));
    } else if (run_seconds.is_object()) {
      for (const auto& row : run_seconds.value(text_of(c, "name"), json::array()))
        if (row.is_object() && row.value("seconds", 0.0) > 0)
          evaluations[row.value("N", 0)] = std::log10(row.value("seconds", 0.0));
    }
    if (evaluations.empty()) {
      uncounted[group].push_back(text_of(c, "name"));
      continue;
    }
    for (const auto& claim : claims) {
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
        const double cost = std::pow(10.0, evaluations[steps[i]]);
        line.points.emplace_back(
            evaluations[steps[i]], *e,
            "N = " + std::to_string(steps[i]) + ": error " + short_decimal(error[i].get<std::string>(), 4) +
                ", " + (wall_time ? format_number(cost, 3) + " s of wall time"
                                  : std::to_string(std::llround(cost)) +
                                        (program_counted ? " evaluations, as the program counts them"
                                                         : " evaluations of L")));
      }
      if (line.points.size() >= 2) groups[group].push_back(line);
    }
  }
  std::ostringstream out;
  int figure = 0;
  for (const auto& [group, lines] : groups) {
    // One method alone is no comparison; a second whose cost is unknown still makes one, named
    // in the caption.
    if (members[group] < 2 || lines.empty()) continue;
    std::optional<double> x_low, x_high, y_low, y_high, floor;
    for (const auto& line : lines) {
      for (const auto& [x, y, title] : line.points) {
        extend(x_low, x_high, x);
        extend(y_low, y_high, y);
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
    const PlotAxes axes{left, right, top, bottom, bottom, *x_low, *x_high, *y_low, *y_high};
    out << "<figure class=\"work-precision\"><svg class=\"plot wp\" "
           "xmlns=\"http://www.w3.org/2000/svg\" width=\""
        << width << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " " << height
        << "\" data-work-precision=\"" << (wall_time ? "seconds-" : "evaluations-") << figure++
        << "\" role=\"img\" aria-label=\"work-precision diagram\">\n";
    write_background(out, axes);
    if (floor && *floor > *y_low)
      out << "<rect data-floor=\"1\" x=\"" << left << "\" y=\""
          << fixed(axes.py(std::min(*floor, *y_high))) << "\" width=\"" << right - left << "\" height=\""
          << fixed(bottom - axes.py(std::min(*floor, *y_high)))
          << "\" fill=\"#e9ecf2\"><title>below the floor: errors here cannot be told from rounding "
             "or the "
             "reference's own error</title></rect>\n";
    write_grid(out, axes, log_ticks(*x_low, *x_high), log_ticks(*y_low, *y_high), "");
    const bool any_self_counted = !self_counted[group].empty();
    write_axis_titles(out, axes,
                      wall_time          ? "wall time of the run, s (this machine)"
                      : any_self_counted ? "evaluations (of L by vivv; a program's as it reports them)"
                                         : "evaluations of L (the run's cost, counted)",
                      "|q_N − q(T)|");
    std::ostringstream legend;
    legend << "<ul class=\"legend\">";
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string color = series_colors[i % series_colors.size()];
      std::string path;
      for (const auto& [x, y, title] : lines[i].points)
        path += (path.empty() ? "M" : " L") + fixed(axes.px(x)) + " " + fixed(axes.py(y));
      out << "<path data-wp-line=\"" << escape(lines[i].name) << "\" d=\"" << path
          << "\" fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1.6\"/>";
      for (const auto& [x, y, title] : lines[i].points)
        out << "<circle cx=\"" << fixed(axes.px(x)) << "\" cy=\"" << fixed(axes.py(y))
            << "\" r=\"3.5\" fill=\"" << color << "\"><title>"
            << escape(lines[i].name + ", " + title) << "</title></circle>";
      out << "\n";
      legend << "<li><span class=\"swatch\" style=\"background:" << color << "\"></span>"
             << escape(lines[i].name) << " <span class=\"small\">"
             << escape(lines[i].discretization) << ", fitted order " << lines[i].order
             << "</span></li>";
    }
    legend << "</ul>";
    std::string missing, reported;
    for (const auto& name : uncounted[group]) missing += (missing.empty() ? "" : ", ") + name;
    for (const auto& name : self_counted[group]) reported += (reported.empty() ? "" : ", ") + name;
    out << "</svg>" << legend.str() << "<figcaption>" << escape(captions[group])
        << ": the global error against "
        << (wall_time ? "the wall time of each run on the machine that ran it"
                      : "the evaluations of L each run made (the same on any machine)")
        << " (log-log; shaded: below the floor). Lower and further left is better."
        << (reported.empty() ? std::string()
                             : " The cost of " + escape(reported) +
                                   " is the evaluations its program reports (protocol extension "
                                   "\"evaluations\": its forces, or L, counted by the program).")
        << (missing.empty() ? std::string()
                            : " Not drawn, its cost unknown (a program's map: vivv does not count "
                              "its evaluations of L, and the program does not report them through "
                              "the protocol's extension \"evaluations\"): " + escape(missing) + ".")
        << "</figcaption></figure>\n";
  }
  return out.str();
}

}  // namespace vivv
