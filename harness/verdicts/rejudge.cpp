#include "harness/verdicts/rejudge.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "core/numerics/scalar.hpp"
#include "harness/verdicts/order_fit.hpp"
#include "reports/report.hpp"

namespace vivv {

namespace {

// Enough digits to compare every recorded error with its floor as the run did (the decimals carry
// the working precision's digits) and to take logarithms far below a double's range.
constexpr unsigned rejudge_digits = 60;

std::string where(const std::string& path, std::size_t i, std::size_t k, std::size_t j,
                  const nlohmann::json& c) {
  return path + ": cases[" + std::to_string(i) + "] (" + c.value("name", std::string("?")) +
         ").claims[" + std::to_string(k) + "] (" +
         c["claims"][k].value("id", std::string("?")) + ").series[" + std::to_string(j) + "]";
}

// A decimal the report records, as MPFR rounds it: a report may hold any decimal (an error of
// 1e-20000000000 is schema-valid), and one beyond MPFR's exponent range becomes 0 or infinity,
// which the fit drops as it would have dropped it in the run.
mpfr_real recorded_value(const std::string& text) {
  try {
    return from_decimal<mpfr_real>(text);
  } catch (const std::out_of_range&) {
    return mpfr_real(text);
  }
}

std::string listed(const std::set<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

std::string listed(const std::vector<int>& indices) {
  std::string text = "[";
  for (std::size_t i = 0; i < indices.size(); ++i)
    text += (i ? ", " : "") + std::to_string(indices[i]);
  return text + "]";
}

// Every index a series' fit_points name (used, dropped) is one of its errors and its step sizes,
// whether or not the series was fitted: a baseline's points are read by index (--baseline).
void check_fit_point_indices(const nlohmann::json& s, const std::string& at, const std::string& edited) {
  const std::size_t errors = s.value("error", nlohmann::json::array()).size();
  const std::size_t steps = s.value("h", nlohmann::json::array()).size();
  for (const char* list : {"used", "dropped"}) {
    if (!s["fit_points"].contains(list)) continue;
    for (const auto& entry : s["fit_points"][list]) {
      const nlohmann::json index = entry.is_object() ? entry.value("index", nlohmann::json()) : entry;
      const bool inside = index.is_number_integer() && index.get<long long>() >= 0 &&
                          static_cast<unsigned long long>(index.get<long long>()) < std::min(errors, steps);
      if (!inside)
        throw ReportError(at + "." + list + ": index " + index.dump() + " names no point of the series (it has " +
                          std::to_string(steps) + " step sizes and " + std::to_string(errors) + " errors)" + edited);
    }
  }
}

}  // namespace

void check_series_follow_from_errors(const nlohmann::json& report, const std::string& path,
                                     const ClaimSeriesRules& rules) {
  PrecisionGuard guard(rejudge_digits);
  using T = mpfr_real;
  const std::string edited = ": the report was edited or damaged after vivv wrote it";
  const nlohmann::json& cases = report.at("cases");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const nlohmann::json& c = cases[i];
    const nlohmann::json& recorded_tolerance = c.at("order_tolerance");
    const double tolerance = recorded_tolerance.is_string() ? std::stod(recorded_tolerance.get<std::string>())
                                                            : recorded_tolerance.get<double>();
    FitOptions options;
    if (c.at("sweep").value("refine", false)) options.asymptote_tolerance = tolerance / 4;
    for (std::size_t k = 0; k < c.at("claims").size(); ++k) {
      const nlohmann::json& claim = c["claims"][k];
      const std::string id = claim.at("id").get<std::string>();
      const std::string at_claim = path + ": cases[" + std::to_string(i) + "] (" +
                                   c.value("name", std::string("?")) + ").claims[" +
                                   std::to_string(k) + "] (" + id + ")";
      const auto known = rules.find(id);
      if (known == rules.end())
        throw ReportError(at_claim + ": no claim of this vivv has that id, so its verdict cannot be "
                                     "judged again");
      const std::set<std::string>& allowed = known->second;
      const nlohmann::json series_list = claim.value("series", nlohmann::json::array());
      bool judged = false;  // a series decided by a rule other than "none"
      for (std::size_t j = 0; j < series_list.size(); ++j) {
        const nlohmann::json& s = series_list[j];
        const bool fitted = s.contains("observed_order") && s.contains("fit_points") &&
                            s.contains("predicted_order") && !s["predicted_order"].is_null();
        // The rule comes from the claim: one the report names must be among the claim's; a
        // report written before vivv recorded rules (or one whose rule was removed) has its
        // fitted series judged by the order rule when the claim fits orders at all.
        std::string rule;
        if (s.contains("rule")) {
          rule = s["rule"].get<std::string>();
          if (!allowed.count(rule))
            throw ReportError(where(path, i, k, j, c) + ": rule \"" + rule + "\", which " + id +
                              " never uses (its series are decided by " + listed(allowed) + ")" +
                              edited);
        } else {
          rule = fitted && allowed.count("order") ? "order" : allowed == std::set<std::string>{"none"}
                                                                  ? "none"
                                                                  : "unrecorded";
        }
        judged = judged || rule != "none";
        if (rule == "none" && !s.value("holds", nlohmann::json()).is_null())
          throw ReportError(where(path, i, k, j, c) + ": rule \"none\" (not judged) with holds " +
                            s["holds"].dump() + edited);
        if (rule == "order" && !fitted)
          throw ReportError(
              where(path, i, k, j, c) +
              ": rule \"order\" without its fit (observed_order, fit_points and predicted_order)" +
              edited);
        if (s.contains("fit_points")) check_fit_point_indices(s, where(path, i, k, j, c) + ".fit_points", edited);
        if (!fitted) continue;
        if (s.at("h").size() != s.at("error").size())
          throw ReportError(where(path, i, k, j, c) + ": " + std::to_string(s["h"].size()) +
                            " step sizes and " + std::to_string(s["error"].size()) + " errors" +
                            edited);
        std::vector<T> h, error;
        for (const auto& x : s.at("h")) h.push_back(recorded_value(x.get<std::string>()));
        for (const auto& e : s.at("error")) error.push_back(recorded_value(e.get<std::string>()));
        const OrderFit fit = fit_order(h, error, recorded_value(s.at("floor").get<std::string>()), options);
        const std::vector<int> used = s["fit_points"].at("used").get<std::vector<int>>();
        const double recorded = s["observed_order"].is_number() ? s["observed_order"].get<double>() : NAN;
        const bool same_order = (std::isnan(recorded) && std::isnan(fit.order)) ||
                                std::abs(recorded - fit.order) <= 1e-9 * std::max(1.0, std::abs(fit.order));
        if (used != fit.used || !same_order)
          throw ReportError(where(path, i, k, j, c) + ": the recorded fit (order " + s["observed_order"].dump() +
                            " from points " + listed(used) + ") is not what its h and errors give (order " +
                            format_scalar(fit.order, 6) + " from points " + listed(fit.used) + ")" +
                            edited);
        // Judged by the order rule only with two or more errors above the floor (make_series),
        // by the floor rule otherwise: the errors decide which, not the report.
        const T floor = recorded_value(s.at("floor").get<std::string>());
        const auto above = std::count_if(error.begin(), error.end(), [&](const T& e) { return e > floor; });
        if ((rule == "order" && above < 2) || (rule == "floor" && above >= 2))
          throw ReportError(where(path, i, k, j, c) + ": rule \"" + rule + "\" with " +
                            std::to_string(above) + " of " + std::to_string(error.size()) +
                            " errors above the floor (the order rule decides a series with two or "
                            "more, the floor rule one with fewer)" +
                            edited);
        // Only the verdicts of the order rule itself: a claim may judge a fitted series by another
        // rule (lagrangian-order's signed leading coefficient against its own error bar).
        if (s.value("holds", nlohmann::json()) != nlohmann::json(true) || rule != "order") continue;
        const OrderVerdict verdict =
            judge_order(fit, s["predicted_order"].get<double>(), s.value("exact_order", false), tolerance);
        if (!verdict.holds)
          throw ReportError(where(path, i, k, j, c) + ": recorded as holding, but judged again from its errors it " +
                            (verdict.inconclusive ? "is inconclusive" : "fails") + " (" + verdict.explanation +
                            ")" + edited);
      }
      // A claim that decides by its series cannot pass on series that nothing judged.
      const std::string verdict = claim.value("verdict", std::string());
      if ((verdict == "pass" || verdict == "xpass") && !series_list.empty() && !judged &&
          allowed != std::set<std::string>{"none"})
        throw ReportError(at_claim + ": \"" + verdict + "\" while every series is marked \"none\" "
                                     "(not judged)" + edited);
    }
  }
}

nlohmann::json read_judged_report(const std::string& path, const ClaimSeriesRules& rules) {
  nlohmann::json report = read_report(path);
  check_series_follow_from_errors(report, path, rules);
  return report;
}

}  // namespace vivv
