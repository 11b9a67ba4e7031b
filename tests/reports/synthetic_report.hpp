// A small synthetic report (schema vivv-report/4) for the renderer tests:
// two cases, three claims — a passing order claim with a dropped point, a
// failing order claim, and a claim without an order whose errors are all 0;
// synthetic_report_with_map() adds an existence-uniqueness claim with its map
// of h_max against |w|.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "reports/report.hpp"

namespace vivv::testing {

inline nlohmann::json synthetic_series(const char* label, std::vector<std::string> error,
                                       nlohmann::json used, nlohmann::json dropped,
                                       nlohmann::json observed, nlohmann::json predicted,
                                       nlohmann::json holds) {
  return {
      {"label", label},
      {"h", {"1.000000000000000000000000000000000000000e-01", "5.0e-02", "2.5e-02", "1.25e-02"}},
      {"error", error},
      {"floor", "1.0e-30"},
      {"observed_order", observed},
      {"predicted_order", predicted},
      {"exact_order", true},
      {"holds", holds},
      {"explanation",
       holds.is_boolean() && !holds.get<bool>() ? "observed order 1 outside 2 ± 0.2: fails" : ""},
      {"error_constant_log", observed.is_number() ? nlohmann::json(0.0) : nlohmann::json()},
      {"order_standard_error", 0.01},
      {"order_confidence_95", {0.9, 1.1}},
      {"pairwise_orders", {1.0, 1.0, 1.0}},
      {"fit_points", {{"used", used}, {"dropped", dropped}}}};
}

inline nlohmann::json synthetic_claim(const char* id, const char* verdict, nlohmann::json series) {
  nlohmann::json claim = {
      {"id", id},
      {"source", "paper Thm 5.5"},
      {"prediction", "O(h^r)"},
      {"verdict", verdict},
      {"explanation",
       std::string(verdict) == "pass" ? "every prediction holds" : "the order is too low: 1 < 2"},
      {"evidence",
       {{"note", "synthetic"}, {"value", "1.234567890123456789012345678901234567890e-05"}}},
      {"series", series}};
  for (const char* key : {"h", "error", "observed_order", "predicted_order", "exact_order",
                          "order_confidence_95", "pairwise_orders", "fit_points", "floor"})
    claim[key] = series[0][key];
  return claim;
}

inline nlohmann::json synthetic_case(const char* name, nlohmann::json claims) {
  return {{"name", name},
          {"file", std::string(name) + ".json"},
          {"case_file", {{"name", name}}},
          {"system", "pendulum"},
          {"parameters", {{"k", "1"}}},
          {"initial", {{"q", {"1.1"}}, {"w", {"0.25"}}}},
          {"T", "1"},
          {"steps", {10, 20, 40, 80}},
          {"labels", nlohmann::json::array()},
          {"precision",
           {{"scalar", "mpfr"},
            {"digits", 40},
            {"bits", 134},
            {"smallest_error", "1e-4"},
            {"guard_bits", 100.0},
            {"rule", "bits >= ..."}}},
          {"reference",
           {{"method", "closed form"},
            {"tolerance", "1e-35"},
            {"cross_check", "none"},
            {"error_estimate_at_T", "0"}}},
          {"seconds", 0.25},
          {"claims", claims}};
}

inline nlohmann::json synthetic_report() {
  using nlohmann::json;
  json passing = synthetic_claim(
      "global-order", "pass",
      json::array({synthetic_series(
          "|q_N − q(T)|", {"1.0e-01", "2.6e-02", "6.3e-03", "1.6e-03"}, {1, 2, 3},
          json::array({{{"index", 0}, {"reason", "pre-asymptotic"}}}), 2.0, 2.0, true)}));
  json failing = synthetic_claim(
      "lagrangian-order", "fail",
      json::array({synthetic_series("|L_d − L_d^E|", {"1.0e-01", "5.0e-02", "2.5e-02", "1.25e-02"},
                                    {0, 1, 2, 3}, json::array(), 1.0, 2.0, false)}));
  json zeros = synthetic_claim(
      "twin-term-invariance", "pass",
      json::array(
          {synthetic_series("max_k |q_k(a) − q_k(0)|", {"0", "0.0e+00", "0", "0"}, json::array(),
                            json::array({{{"index", 0}, {"reason", "zero error"}},
                                         {{"index", 1}, {"reason", "zero error"}},
                                         {{"index", 2}, {"reason", "zero error"}},
                                         {{"index", 3}, {"reason", "zero error"}}}),
                            json(), json(), true)}));
  return assemble_report(
      {synthetic_case("alpha", {passing, failing}), synthetic_case("beta", {zeros})},
      {"vivv run synthetic", "vivv test"});
}

// An existence-uniqueness claim whose evidence carries the map h_max against
// |w|: six speeds, h_max halving with each doubling, 0 at the fastest.
inline nlohmann::json synthetic_existence_claim() {
  using nlohmann::json;
  json claim = synthetic_claim(
      "existence-uniqueness", "fail",
      json::array({synthetic_series("|F_h(v) − v|", {"1.0e-01", "5.0e-02", "2.5e-02", "1.25e-02"},
                                    {0, 1, 2, 3}, json::array(), 1.0, 1.0, false)}));
  json map = json::array();
  const char* speeds[] = {"2.5e-01", "5.0e-01", "1", "2", "4", "8"};
  const char* h_max[] = {"4.0", "2.0", "1.0", "5.0e-01", "2.5e-01", "0.0e+00"};
  for (int i = 0; i < 6; ++i) map.push_back({{"speed", speeds[i]}, {"h_max", h_max[i]}});
  claim["source"] = "paper Thm 4.2";
  claim["evidence"] = {{"h_max_by_speed", map}, {"h_max_search", "largest h = T·2^-j"}};
  return claim;
}

// synthetic_report() with a third case holding synthetic_existence_claim().
inline nlohmann::json synthetic_report_with_map() {
  nlohmann::json report = synthetic_report();
  std::vector<nlohmann::json> cases(report["cases"].begin(), report["cases"].end());
  cases.push_back(synthetic_case("gamma", {synthetic_existence_claim()}));
  return assemble_report(cases, {"vivv run synthetic", "vivv test"});
}

// How often `needle` occurs in `text` (overlapping occurrences counted).
inline int count(const std::string& text, const std::string& needle) {
  int n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
    ++n;
  return n;
}

}  // namespace vivv::testing
