#include "reports/report.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace vivv {

namespace {

// A double in JSON, or null when it is not finite (JSON has no NaN/∞).
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

nlohmann::json series_json(const Series& series) {
  nlohmann::json out = {{"label", series.label}, {"h", series.h}, {"error", series.error},
                        {"floor", series.floor}};
  out["predicted_order"] = series.predicted_order ? nlohmann::json(*series.predicted_order) : nlohmann::json();
  out["exact_order"] = series.exact_order;
  out["holds"] = series.holds ? nlohmann::json(*series.holds) : nlohmann::json();
  out["explanation"] = series.explanation;
  if (series.fit) {
    const OrderFit& fit = *series.fit;
    out["fit_ok"] = fit.ok;
    out["observed_order"] = fit.ok ? number(fit.order) : nlohmann::json();
    out["order_standard_error"] = number(fit.standard_error);
    out["order_confidence_95"] = {number(fit.confidence_low), number(fit.confidence_high)};
    out["error_constant_log"] = number(fit.log_constant);
    nlohmann::json pairwise = nlohmann::json::array();
    for (double p : fit.pairwise_orders) pairwise.push_back(number(p));
    out["pairwise_orders"] = pairwise;
    nlohmann::json dropped = nlohmann::json::array();
    for (const auto& [index, reason] : fit.dropped) dropped.push_back({{"index", index}, {"reason", reason}});
    out["fit_points"] = {{"used", fit.used}, {"dropped", dropped}};
    if (!fit.ok) out["fit_failure"] = fit.reason;
  }
  return out;
}

}  // namespace

nlohmann::json case_json(const CaseResult& result) {
  const CaseSpec& spec = result.spec;
  nlohmann::json parameters = nlohmann::json::object();
  for (const auto& [name, value] : spec.parameters) parameters[name] = value;
  nlohmann::json claims = nlohmann::json::array();
  for (const auto& claim : result.claims) {
    nlohmann::json c = {{"id", claim.id},
                        {"source", claim.source},
                        {"prediction", claim.prediction},
                        {"verdict", claim.verdict},
                        {"explanation", claim.explanation},
                        {"evidence", claim.evidence}};
    nlohmann::json all_series = nlohmann::json::array();
    for (const auto& series : claim.series) all_series.push_back(series_json(series));
    c["series"] = all_series;
    // The main series' fields at claim level (DESIGN §3).
    if (!claim.series.empty()) {
      const nlohmann::json& main = all_series[0];
      for (const char* key : {"h", "error", "observed_order", "predicted_order", "exact_order",
                              "order_standard_error", "order_confidence_95", "pairwise_orders",
                              "fit_points", "floor"})
        if (main.contains(key)) c[key] = main[key];
    }
    claims.push_back(c);
  }
  return {{"name", spec.name},
          {"file", spec.file},
          {"case_file", spec.source},
          {"system", spec.system},
          {"parameters", parameters},
          {"initial", {{"q", spec.q}, {"w", spec.w}}},
          {"T", spec.final_time},
          {"steps", spec.steps},
          {"labels", spec.labels},
          {"precision",
           {{"scalar", result.scalar},
            {"digits", result.digits},
            {"bits", result.precision_bits},
            {"smallest_error", result.smallest_error},
            {"guard_bits", result.guard_bits},
            {"rule", "bits >= -log2(smallest error) + guard (DESIGN 1.6)"}}},
          {"reference",
           {{"method", result.reference_method},
            {"tolerance", result.reference_tolerance},
            {"cross_check", result.reference_cross_check},
            {"error_estimate_at_T", result.reference_error_estimate}}},
          {"seconds", result.seconds},
          {"claims", claims}};
}

nlohmann::json verdict_counts(const nlohmann::json& cases) {
  nlohmann::json counts = {{"pass", 0}, {"fail", 0}, {"error", 0}};
  for (const auto& c : cases)
    for (const auto& claim : c["claims"]) counts[claim["verdict"].get<std::string>()] = counts[claim["verdict"].get<std::string>()].get<int>() + 1;
  return counts;
}

nlohmann::json assemble_report(const std::vector<nlohmann::json>& cases, const RunInfo& run) {
  return {{"schema", report_schema},
          {"run", {{"command_line", run.command_line}, {"versions", run.versions}}},
          {"summary", verdict_counts(cases)},
          {"cases", cases}};
}

void write_atomically(const std::string& path, const std::string& content) {
  std::string temporary = path + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + temporary);
  }
  std::filesystem::rename(temporary, path);
}

void print_claims_table(std::ostream& out, const nlohmann::json& report) {
  struct Row {
    std::string name, claim, verdict, observed, predicted;
  };
  std::vector<Row> rows{{"case", "claim", "verdict", "observed", "predicted"}};
  auto order_text = [](const nlohmann::json& value, int decimals) {
    if (!value.is_number()) return std::string("-");
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << value.get<double>();
    return s.str();
  };
  for (const auto& c : report["cases"])
    for (const auto& claim : c["claims"])
      rows.push_back({c["name"], claim["id"], claim["verdict"],
                      order_text(claim.value("observed_order", nlohmann::json()), 2),
                      order_text(claim.value("predicted_order", nlohmann::json()), 0) +
                          (claim.value("exact_order", false) ? " (exact)" : "")});
  std::size_t widths[4] = {0, 0, 0, 0};
  for (const auto& row : rows) {
    widths[0] = std::max(widths[0], row.name.size());
    widths[1] = std::max(widths[1], row.claim.size());
    widths[2] = std::max(widths[2], row.verdict.size());
    widths[3] = std::max(widths[3], row.observed.size());
  }
  for (const auto& row : rows) {
    out << std::left << std::setw(widths[0] + 2) << row.name << std::setw(widths[1] + 2) << row.claim
        << std::setw(widths[2] + 2) << row.verdict << std::right << std::setw(widths[3]) << row.observed
        << "  " << row.predicted << "\n";
  }
  const auto& summary = report["summary"];
  out << "claims: " << summary["pass"] << " pass, " << summary["fail"] << " fail, "
      << summary["error"] << " error\n";
}

}  // namespace vivv
