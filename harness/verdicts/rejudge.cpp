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

std::string listed(const std::vector<int>& indices) {
  std::string text = "[";
  for (std::size_t i = 0; i < indices.size(); ++i)
    text += (i ? ", " : "") + std::to_string(indices[i]);
  return text + "]";
}

}  // namespace

void check_series_follow_from_errors(const nlohmann::json& report, const std::string& path) {
  PrecisionGuard guard(rejudge_digits);
  using T = mpfr_real;
  const nlohmann::json& cases = report.at("cases");
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const nlohmann::json& c = cases[i];
    const nlohmann::json& recorded_tolerance = c.at("order_tolerance");
    const double tolerance = recorded_tolerance.is_string() ? std::stod(recorded_tolerance.get<std::string>())
                                                            : recorded_tolerance.get<double>();
    FitOptions options;
    if (c.at("sweep").value("refine", false)) options.asymptote_tolerance = tolerance / 4;
    for (std::size_t k = 0; k < c.at("claims").size(); ++k) {
      const nlohmann::json& claims = c["claims"][k];
      const nlohmann::json series_list = claims.value("series", nlohmann::json::array());
      for (std::size_t j = 0; j < series_list.size(); ++j) {
        const nlohmann::json& s = series_list[j];
        // The rule that decided the series (absent in reports written before vivv recorded it:
        // the order rule's explanations begin with "observed order").
        const std::string rule =
            s.contains("rule") ? s["rule"].get<std::string>()
            : s.value("explanation", std::string()).rfind("observed order", 0) == 0 ? "order"
                                                                                    : "unrecorded";
        if (rule == "none" && !s.value("holds", nlohmann::json()).is_null())
          throw ReportError(where(path, i, k, j, c) + ": rule \"none\" (not judged) with holds " +
                            s["holds"].dump() +
                            ": the report was edited or damaged after vivv wrote it");
        if (rule == "order" && (!s.contains("observed_order") || !s.contains("fit_points") ||
                                !s.contains("predicted_order") || s["predicted_order"].is_null()))
          throw ReportError(
              where(path, i, k, j, c) +
              ": rule \"order\" without its fit (observed_order, fit_points and predicted_order): "
              "the report was edited or damaged after vivv wrote it");
        if (!s.contains("observed_order") || !s.contains("fit_points") ||
            !s.contains("predicted_order") || s["predicted_order"].is_null())
          continue;
        std::vector<T> h, error;
        for (const auto& x : s.at("h")) h.push_back(from_decimal<T>(x.get<std::string>()));
        for (const auto& e : s.at("error")) error.push_back(from_decimal<T>(e.get<std::string>()));
        const OrderFit fit = fit_order(h, error, from_decimal<T>(s.at("floor").get<std::string>()), options);
        const std::vector<int> used = s["fit_points"].at("used").get<std::vector<int>>();
        const double recorded = s["observed_order"].is_number() ? s["observed_order"].get<double>() : NAN;
        const bool same_order = (std::isnan(recorded) && std::isnan(fit.order)) ||
                                std::abs(recorded - fit.order) <= 1e-9 * std::max(1.0, std::abs(fit.order));
        if (used != fit.used || !same_order)
          throw ReportError(where(path, i, k, j, c) + ": the recorded fit (order " + s["observed_order"].dump() +
                            " from points " + listed(used) + ") is not what its h and errors give (order " +
                            format_scalar(fit.order, 6) + " from points " + listed(fit.used) +
                            "): the report was edited or damaged after vivv wrote it");
        // Judged by the order rule only with two or more errors above the floor (make_series).
        const T floor = from_decimal<T>(s.at("floor").get<std::string>());
        const auto above = std::count_if(error.begin(), error.end(), [&](const T& e) { return e > floor; });
        // Only the verdicts of the order rule itself: a claim may judge a fitted series by another
        // rule (lagrangian-order's signed leading coefficient against its own error bar).
        if (s.value("holds", nlohmann::json()) != nlohmann::json(true) || above < 2 ||
            rule != "order")
          continue;
        const OrderVerdict verdict =
            judge_order(fit, s["predicted_order"].get<double>(), s.value("exact_order", false), tolerance);
        if (!verdict.holds)
          throw ReportError(where(path, i, k, j, c) + ": recorded as holding, but judged again from its errors it " +
                            (verdict.inconclusive ? "is inconclusive" : "fails") + " (" + verdict.explanation +
                            "): the report was edited or damaged after vivv wrote it");
      }
    }
  }
}

}  // namespace vivv
