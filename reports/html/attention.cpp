// "Needs attention": one line per claim that did not pass — what was observed against what was
// predicted and the one sentence that matters — with the whole explanation a click away. A claim's
// explanation is the decisive series' statistics (all its failing series', label: why; …) and then
// what the claim concludes from them (local-order: "one step … is not of order 3: an order
// defect …"); the line shows that conclusion, or for an inconclusive claim what would decide it,
// and the decisive series' first clause only where the claim adds nothing.
#include <string>

#include "reports/html/plot_frame.hpp"
#include "reports/html/verdict_text.hpp"
#include "reports/html_report.hpp"
#include "reports/report_text.hpp"

namespace vivv {

using namespace html;

namespace {

// At most `limit` characters, cut at a word.
std::string clipped(const std::string& text, std::size_t limit) {
  if (text.size() <= limit) return text;
  std::size_t cut = text.rfind(' ', limit);
  if (cut == std::string::npos || cut < limit / 2) cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
  return text.substr(0, cut) + " …";
}

// The first clause of `text`: up to "; " (or the end).
std::string first_clause(const std::string& text) {
  const std::size_t end = text.find("; ");
  return end == std::string::npos ? text : text.substr(0, end);
}

}  // namespace

std::string attention_sentence(const json& claim) {
  const std::string verdict = text_of(claim, "verdict"), explanation = text_of(claim, "explanation");
  const json series = claim.value("series", json::array());
  const std::size_t decisive = claim.value("decisive_series", 0);
  if (verdict == "inconclusive" && decisive < series.size() && !text_of(series[decisive], "to_decide").empty())
    return clipped("to decide: " + text_of(series[decisive], "to_decide"), 240);
  // What conclude() wrote from the failing series; what follows it is the claim's own conclusion.
  std::string statistics;
  for (const auto& s : series)
    if (s.value("holds", json()) == json(false) && !s.value("inconclusive", false))
      statistics += (statistics.empty() ? "" : "; ") + text_of(s, "label") + ": " + text_of(s, "explanation");
  // A claim may say something before them too ("judged on the runs that finished (N = …)"): its
  // first clause follows the conclusion.
  const std::size_t at = statistics.empty() ? std::string::npos : explanation.find(statistics);
  if (at != std::string::npos && explanation.size() > at + statistics.size() + 2) {
    std::string conclusion = explanation.substr(at + statistics.size());
    while (!conclusion.empty() && (conclusion[0] == ';' || conclusion[0] == '.' || conclusion[0] == ' '))
      conclusion.erase(0, 1);
    const std::string before = at > 0 ? first_clause(explanation.substr(0, at)) : std::string();
    if (!conclusion.empty())
      return clipped(conclusion, 320) + (before.empty() ? std::string() : " — " + clipped(before, 120));
  }
  if (decisive < series.size() && !text_of(series[decisive], "explanation").empty())
    return clipped(first_clause(text_of(series[decisive], "explanation")), 240);
  return clipped(first_clause(explanation), 240);
}

std::string attention_line(const json& claim, const std::string& key, const std::string& anchor) {
  const std::string verdict = text_of(claim, "verdict");
  const json series = claim.value("series", json::array());
  const std::size_t decisive = claim.value("decisive_series", 0);
  std::string line = "<li data-attention=\"" + escape(verdict) + "\" data-attention-claim=\"" + escape(key) + "\">" +
                     verdict_badge(verdict) + " <a href=\"#" + anchor + "\">" + escape(key) + "</a>";
  if (decisive < series.size() && series[decisive].value("observed_order", json()).is_number())
    line += " <span class=\"small\">observed " + order_html(series[decisive]["observed_order"], 3) + " against " +
            predicted_html(series[decisive]) + "</span>";
  else if (decisive < series.size())
    line += " <span class=\"small\">" + escape(text_of(series[decisive], "label")) + "</span>";
  return line + ": " + escape(attention_sentence(claim)) + " <details class=\"why\"><summary>why</summary>" +
         escape(text_of(claim, "explanation")) + "</details></li>\n";
}

}  // namespace vivv
