// report.html: one self-contained page (no network, no external fonts or
// scripts) that reads like an audit (STYLE.md): a findings table — case,
// claim, source, prediction, observed, verdict, why they differ — then per
// claim a log-log plot in inline SVG (every series of the claim, its fitted
// line, points used for the fit marked apart from dropped ones with the
// reason as a tooltip), a log-log map of h_max against |w| where the claim
// has one (existence-uniqueness), the pairwise orders and the evidence.
//
// Hooks for tests and scripts: every findings row is a <tr data-claim-row="CASE/CLAIM">,
// every plot an <svg data-claim-plot="CASE/CLAIM">, every verdict carries
// data-verdict="pass|fail|error", every plotted point data-point="used|dropped|zero|measured",
// every map of h_max against |w| an <svg data-claim-map="CASE/CLAIM"> with its
// points data-map-point="positive|zero".
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace vivv {

// The page for a report of schema report_schema.
std::string render_html(const nlohmann::json& report);

// The one sentence "Needs attention" shows for a claim that did not pass (plain text): its own
// conclusion, what would decide it, or the decisive series' first clause (reports/html/attention.cpp).
std::string attention_sentence(const nlohmann::json& claim);

// One <li> of "Needs attention" for a claim that did not pass: its badge and link, observed against
// predicted, attention_sentence, and the whole explanation folded under "why".
std::string attention_line(const nlohmann::json& claim, const std::string& key, const std::string& anchor);

// The log-log plot of one claim (its "series"), as an <svg> element.
std::string render_claim_plot(const nlohmann::json& claim, const std::string& key);

// The log-log map of h_max against the speed |w| from the claim's evidence
// "h_max_by_speed" ([{"speed", "h_max"}, ...], existence-uniqueness), as an
// <svg data-claim-map="CASE/CLAIM">; h_max = 0 is drawn in a band below the
// axis. "" when the claim has no such evidence.
std::string render_speed_map(const nlohmann::json& claim, const std::string& key);

// |E_k − E_0| against t (log error, linear t) for each h, from the claim's evidence
// "energy_error_against_t" ([{"h", "N", "t": [...], "error": [...]}], energy-behaviour and
// modified-energy: per h the largest error in each of ~200 runs of steps), as an
// <svg data-claim-time-plot="CASE/CLAIM"> with an HTML legend; "" without such evidence.
std::string render_time_plot(const nlohmann::json& claim, const std::string& key);

// Work-precision diagrams: for each group of cases with one system, parameters, initial state and
// T (two or more with a global-order claim and counted costs), |q_N − q(T)| against the
// evaluations of L of each run (or, with `wall_time`, its seconds from the run block), one line
// per case; "" when there is no such group.
std::string render_work_precision(const nlohmann::json& cases, const nlohmann::json& run,
                                  bool wall_time);

}  // namespace vivv
