// report.html: one self-contained page (no network, no external fonts or
// scripts) that reads like an audit (STYLE.md): a findings table — case,
// claim, source, prediction, observed, verdict, why they differ — then per
// claim a log-log plot in inline SVG (every series of the claim, its fitted
// line, points used for the fit marked apart from dropped ones with the
// reason as a tooltip), the pairwise orders and the evidence.
//
// Hooks for tests and scripts: every findings row is a <tr data-claim-row="CASE/CLAIM">,
// every plot an <svg data-claim-plot="CASE/CLAIM">, every verdict carries
// data-verdict="pass|fail|error", every plotted point data-point="used|dropped|zero|measured".
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace vivv {

// The page for a report of schema report_schema.
std::string render_html(const nlohmann::json& report);

// The log-log plot of one claim (its "series"), as an <svg> element.
std::string render_claim_plot(const nlohmann::json& claim, const std::string& key);

}  // namespace vivv
