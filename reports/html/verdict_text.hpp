// How the page writes a verdict, an order and a decimal: the badge, "order ≥ 2", a shortened number
// with all its digits on hover. Shared by the page (reports/html_report.cpp) and its "Needs
// attention" lines (reports/html/attention.cpp).
#pragma once

#include <string>

#include "reports/html/plot_frame.hpp"
#include "reports/report_text.hpp"

namespace vivv::html {

// A decimal string shortened, with the full value as a tooltip.
inline std::string decimal_html(const std::string& decimal) {
  std::string shown = short_decimal(decimal);
  if (shown == decimal) return escape(decimal);
  return "<span class=\"num\" title=\"" + escape(decimal) + "\">" + escape(shown) + "</span>";
}

inline std::string verdict_badge(const std::string& verdict) {
  std::string mark = verdict == "pass"           ? "&#10003; pass"
                     : verdict == "fail"         ? "&#10007; FAIL"
                     : verdict == "xfail"        ? "&#8856; xfail"
                     : verdict == "xpass"        ? "&#10007; XPASS"
                     : verdict == "inconclusive" ? "&#63; inconclusive"
                                                 : "&#9888; ERROR";
  return "<span class=\"verdict v-" + escape(verdict) + "\" data-verdict=\"" + escape(verdict) +
         "\">" + mark + "</span>";
}

inline std::string order_html(const json& value, int digits = 4) {
  return value.is_number() ? format_number(value.get<double>(), digits) : "&#8212;";
}

// "≥ 2" for a lower bound, "= 2 (exact)" for an exact order, "—" for none.
inline std::string predicted_html(const json& claim) {
  const json predicted = claim.value("predicted_order", json());
  if (!predicted.is_number()) return "<span class=\"small\">(no order)</span>";
  return "order " + std::string(claim.value("exact_order", false) ? "= " : "&#8805; ") +
         format_number(predicted.get<double>(), 4) +
         (claim.value("exact_order", false) ? " <span class=\"small\">(exact)</span>" : "");
}

}  // namespace vivv::html
