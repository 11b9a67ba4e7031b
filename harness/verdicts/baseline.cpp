#include "harness/verdicts/baseline.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "reports/report_text.hpp"

namespace vivv {

namespace {

// log10 of a decimal string "m.mmme-N" without leaving a double's range (an MPFR error may be
// 1e-5000); nullopt for 0, a negative or what does not parse.
std::optional<double> log10_of_decimal(const std::string& text) {
  try {
    const auto e = text.find_first_of("eE");
    const long double mantissa = std::stold(text.substr(0, e));
    const long exponent = e == std::string::npos ? 0 : std::stol(text.substr(e + 1));
    if (!(mantissa > 0)) return std::nullopt;
    return static_cast<double>(std::log10(mantissa)) + static_cast<double>(exponent);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::string order_text(double x) { return format_number(x, 4); }

struct SeriesComparison {
  nlohmann::json row;
  std::string status;  // "regressed", "improved", "unchanged", "not compared"
  std::string text;
};

SeriesComparison compare_series(const nlohmann::json& now, const nlohmann::json& before, double order_tolerance,
                                double constant_tolerance) {
  SeriesComparison out;
  const std::string label = now.value("label", std::string());
  out.row = {{"label", label}};
  const auto fitted = [](const nlohmann::json& s) {
    return s.value("fit_ok", false) && s.value("observed_order", nlohmann::json()).is_number() &&
           s.contains("fit_points") && s["fit_points"].contains("used");
  };
  if (!fitted(now) || !fitted(before)) {
    out.status = "not compared";
    out.text = label + ": no fitted order " + (fitted(now) ? "in the baseline" : "in this run");
    out.row["status"] = out.status;
    return out;
  }
  const double order = now["observed_order"].get<double>(), old_order = before["observed_order"].get<double>();
  out.row["observed_order"] = order;
  out.row["baseline_order"] = old_order;
  // The baseline's points, for the claim's plot to draw beside this run's.
  if (before.contains("h") && before["h"].is_array() && before.contains("error") &&
      before["error"].is_array() && before["h"].size() == before["error"].size()) {
    out.row["baseline_h"] = before["h"];
    out.row["baseline_error"] = before["error"];
  }
  // The errors at the step sizes both fits used.
  std::vector<double> log_ratios;
  for (int i : now["fit_points"]["used"].get<std::vector<int>>()) {
    const auto h = log10_of_decimal(now["h"].at(i).get<std::string>());
    const auto e = log10_of_decimal(now["error"].at(i).get<std::string>());
    if (!h || !e) continue;
    for (int j : before["fit_points"]["used"].get<std::vector<int>>()) {
      const auto h_before = log10_of_decimal(before["h"].at(j).get<std::string>());
      const auto e_before = log10_of_decimal(before["error"].at(j).get<std::string>());
      if (h_before && e_before && std::abs(*h - *h_before) <= 1e-9) log_ratios.push_back(*e - *e_before);
    }
  }
  out.row["common_points"] = log_ratios.size();
  const bool order_dropped = old_order - order > order_tolerance;
  const bool order_rose = order - old_order > order_tolerance;
  std::string constant;
  bool grew = false, shrank = false;
  if (!log_ratios.empty()) {
    double mean = 0;
    for (double r : log_ratios) mean += r;
    mean /= static_cast<double>(log_ratios.size());
    const double ratio = std::pow(10.0, mean);
    out.row["constant_ratio"] = std::isfinite(ratio) ? nlohmann::json(ratio) : nlohmann::json();
    grew = !(ratio <= 1 + constant_tolerance);
    shrank = ratio < 1 / (1 + constant_tolerance);
    constant = "error ×" + format_number(ratio, 4) + " the baseline's at the " + std::to_string(log_ratios.size()) +
               " step size" + (log_ratios.size() == 1 ? "" : "s") + " both fits used (allowed ×" +
               format_number(1 + constant_tolerance, 4) + ")";
  } else {
    constant = "the error constant not compared: no step size used by both fits";
  }
  out.status = order_dropped || grew ? "regressed" : order_rose || shrank ? "improved" : "unchanged";
  out.row["status"] = out.status;
  out.text = label + ": order " + order_text(order) + " (baseline " + order_text(old_order) +
             (order_dropped ? ", dropped by more than the order tolerance " + format_number(order_tolerance, 3) : "") +
             "), " + constant;
  return out;
}

}  // namespace

void compare_with_baseline(nlohmann::json& report, const nlohmann::json& baseline, const std::string& baseline_path,
                           double constant_tolerance) {
  // (case, claim) -> the baseline's claim
  std::map<std::pair<std::string, std::string>, const nlohmann::json*> before;
  for (const auto& c : baseline.at("cases"))
    for (const auto& claim : c.at("claims")) before[{c.at("name"), claim.at("id")}] = &claim;
  std::map<std::string, int> counts = {{"regressed", 0}, {"improved", 0}, {"unchanged", 0}, {"not compared", 0}};
  nlohmann::json new_claims = nlohmann::json::array();
  std::map<std::pair<std::string, std::string>, bool> seen;
  for (auto& c : report.at("cases")) {
    const std::string name = c.at("name");
    const nlohmann::json& recorded = c.at("order_tolerance");
    const double tolerance =
        recorded.is_string() ? std::stod(recorded.get<std::string>()) : recorded.get<double>();
    for (auto& claim : c.at("claims")) {
      const std::string id = claim.at("id");
      const auto found = before.find({name, id});
      if (found == before.end()) {
        new_claims.push_back(name + "/" + id);
        continue;
      }
      seen[{name, id}] = true;
      const nlohmann::json old_series = found->second->value("series", nlohmann::json::array());
      nlohmann::json rows = nlohmann::json::array();
      std::string regressed, improved, unchanged;
      for (const auto& s : claim.value("series", nlohmann::json::array())) {
        // Only series the order rule judged have an order and a constant to compare: another
        // rule's series (lagrangian-order's distance of a coefficient from E_(r+1), a drift) is
        // a distance near its own noise, whose ratio between two runs says nothing.
        if (s.value("rule", std::string()) != "order") continue;
        for (const auto& old : old_series) {
          if (old.value("label", std::string()) != s.value("label", std::string())) continue;
          const SeriesComparison comparison = compare_series(s, old, tolerance, constant_tolerance);
          rows.push_back(comparison.row);
          std::string& list = comparison.status == "regressed"  ? regressed
                              : comparison.status == "improved" ? improved
                                                                : unchanged;
          list += (list.empty() ? "" : "; ") + comparison.text;
          break;
        }
      }
      // A pass that became weak (a program's answers now carry noise far above a double's
      // rounding, ClaimResult::weakness) has lost what it could catch, whatever its series show.
      if (claim.contains("weakness") && !found->second->contains("weakness")) {
        regressed += (regressed.empty() ? "" : "; ") + std::string("weak now, not in the baseline: ") +
                     claim["weakness"].get<std::string>();
        rows.push_back({{"label", "weakness"}, {"status", "regressed"}});
      }
      const bool compared = std::any_of(rows.begin(), rows.end(),
                                        [](const nlohmann::json& row) { return row["status"] != "not compared"; });
      const std::string status = !regressed.empty() ? "regressed"
                                 : !improved.empty() ? "improved"
                                 : compared          ? "unchanged"
                                                     : "not compared";
      ++counts[status];
      std::string explanation = status == "regressed" ? regressed
                                : status == "improved" ? improved
                                                       : unchanged;
      const auto judged_by_order = [](const nlohmann::json& series) {
        return std::any_of(series.begin(), series.end(), [](const nlohmann::json& s) {
          return s.value("rule", std::string()) == "order";
        });
      };
      if (status == "not compared" && rows.empty())
        explanation =
            !judged_by_order(claim.value("series", nlohmann::json::array()))
                ? "no series of this claim is judged by the order rule: it has no order and "
                  "constant to "
                  "compare"
                : "no series judged by the order rule has a label the baseline's claim has";
      claim["baseline"] = {{"status", status}, {"explanation", explanation}, {"series", rows}};
    }
  }
  nlohmann::json missing = nlohmann::json::array();
  for (const auto& [key, claim] : before)
    if (!seen.count(key)) missing.push_back(key.first + "/" + key.second);
  report["run"]["baseline"] = {{"report", baseline_path},
                               {"constant_tolerance", constant_tolerance},
                               {"regressed", counts["regressed"]},
                               {"improved", counts["improved"]},
                               {"unchanged", counts["unchanged"]},
                               {"not_compared", counts["not compared"]},
                               {"not_in_baseline", new_claims},
                               {"not_in_this_run", missing}};
}

int regressed_claims(const nlohmann::json& report) {
  int regressed = 0;
  for (const auto& c : report.at("cases"))
    for (const auto& claim : c.at("claims"))
      regressed += claim.contains("baseline") && claim["baseline"].value("status", std::string()) == "regressed";
  return regressed;
}

}  // namespace vivv
