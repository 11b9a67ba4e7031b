#include "reports/report.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cases/case_file.hpp"
#include "reports/html_report.hpp"
#include "reports/junit_report.hpp"
#include "reports/report_text.hpp"
#include "reports/schema_check.hpp"
#include "core/platform/signals.hpp"
#include "core/platform/text.hpp"

namespace vivv {

namespace {

// A double in JSON, or null when it is not finite (JSON has no NaN/∞).
nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

nlohmann::json series_json(const Series& series) {
  nlohmann::json out = {
      {"label", series.label}, {"h", series.h}, {"error", series.error}, {"floor", series.floor}};
  out["predicted_order"] =
      series.predicted_order ? nlohmann::json(*series.predicted_order) : nlohmann::json();
  out["exact_order"] = series.exact_order;
  out["holds"] = series.holds ? nlohmann::json(*series.holds) : nlohmann::json();
  out["rule"] = series.rule;
  out["inconclusive"] = series.inconclusive;
  if (series.inconclusive) out["to_decide"] = series.to_decide;
  out["explanation"] = series.explanation;
  out["detection_limit"] = series.detection_limit;
  if (!series.rounding_floor.empty()) out["rounding_floor"] = series.rounding_floor;
  if (!series.reference_floor.empty()) out["reference_floor"] = series.reference_floor;
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
    nlohmann::json finest = nlohmann::json::array();
    for (double p : fit.finest_orders) finest.push_back(number(p));
    out["finest_pairwise_orders"] = finest;
    nlohmann::json dropped = nlohmann::json::array();
    for (const auto& [index, reason] : fit.dropped)
      dropped.push_back({{"index", index}, {"reason", reason}});
    out["fit_points"] = {{"used", fit.used}, {"dropped", dropped}};
    if (!fit.ok) out["fit_failure"] = fit.reason;
  }
  return out;
}

}  // namespace

// Each run's L evaluations, by N (deterministic: in the case); its wall time goes to the run block.
// A program's map evaluates L, if at all, where vivv does not count: unknown (null), not 0; its
// own count beside it where it reports one.
nlohmann::json run_cost(const CaseResult& result) {
  nlohmann::json out = nlohmann::json::array();
  const bool counted = result.spec.discretization.kind != "process";
  for (const auto& [N, cost] : result.run_costs) {
    nlohmann::json row = {{"N", N},
                          {"L_evaluations", counted ? nlohmann::json(cost.lagrangian_evaluations) : nlohmann::json()}};
    // What the program says its steps evaluated (protocol extension "evaluations").
    if (cost.program_evaluations) row["program_evaluations"] = *cost.program_evaluations;
    out.push_back(row);
  }
  return out;
}
nlohmann::json run_seconds(const CaseResult& result) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [N, cost] : result.run_costs)
    out.push_back({{"N", N}, {"seconds", cost.seconds}});
  return out;
}

nlohmann::json case_json(const CaseResult& result) {
  const CaseSpec& spec = result.spec;
  // A number the case file wrote as a formula ("pi/4") is recorded as written (under "written")
  // and as used: its decimal rounded to the digits that carry the working precision.
  std::map<std::string, std::string> written(spec.written.begin(), spec.written.end());
  const int used_digits =
      result.precision_bits > 0 ? static_cast<int>(std::ceil(result.precision_bits * std::log10(2.0))) + 1 : 40;
  const auto as_used = [&](const std::string& field, const std::string& text) {
    return written.count(field) ? rounded_decimal(text, used_digits) : text;
  };
  const nlohmann::json parameters = parameters_as_written(
      spec.parameters, [&](const std::string& name, const std::string& value) { return as_used("system.params." + name, value); });
  nlohmann::json initial = {{"q", nlohmann::json::array()}, {"w", nlohmann::json::array()}};
  for (std::size_t i = 0; i < spec.q.size(); ++i) {
    initial["q"].push_back(as_used("initial.q[" + std::to_string(i) + "]", spec.q[i]));
    initial["w"].push_back(as_used("initial.w[" + std::to_string(i) + "]", spec.w[i]));
  }
  nlohmann::json claims = nlohmann::json::array();
  nlohmann::json claim_seconds = nlohmann::json::object();
  for (const auto& claim : result.claims) {
    nlohmann::json c = {{"id", claim.id},
                        {"source", claim.source},
                        {"prediction", claim.prediction},
                        {"verdict", claim.verdict},
                        {"explanation", claim.explanation},
                        {"detection_limit", claim.detection_limit},
                        {"decisive_series", claim.decisive_series},
                        {"evidence", claim.evidence}};
    if (!claim.xfail_reason.empty()) c["xfail_reason"] = claim.xfail_reason;
    if (!claim.weakness.empty()) c["weakness"] = claim.weakness;
    claim_seconds[claim.id] = claim.seconds;  // to the run block (assemble_report)
    nlohmann::json all_series = nlohmann::json::array();
    for (const auto& series : claim.series) all_series.push_back(series_json(series));
    c["series"] = all_series;
    // The decisive series' fields at claim level (docs/case-files.md): the main series for a pass,
    // the series that failed or could not decide otherwise.
    if (!claim.series.empty()) {
      const nlohmann::json& main = all_series[std::min<std::size_t>(
          static_cast<std::size_t>(claim.decisive_series), all_series.size() - 1)];
      for (const char* key : {"h", "error", "observed_order", "predicted_order", "exact_order",
                              "order_standard_error", "order_confidence_95", "pairwise_orders",
                              "finest_pairwise_orders", "fit_points", "floor"})
        if (main.contains(key)) c[key] = main[key];
    }
    claims.push_back(c);
  }
  nlohmann::json out = {{"name", spec.name},
          {"file", spec.file},
          {"case_file", spec.source},
          {"system", spec.system},
          {"system_implementation", result.implementation},
          {"lagrangian_formula", result.formula},
          {"parameters", parameters},
          {"initial", initial},
          {"T", as_used("T", spec.final_time)},
          {"steps", spec.steps},
          {"order_tolerance", spec.order_tolerance},
          {"sweep",
           {{"refine", result.sweep.refine},
            {"requested_steps", result.sweep.requested_steps},
            {"steps_used", spec.steps},
            {"stopped", result.sweep.stopped},
            {"budget", result.sweep.refine
                           ? "at most " + std::to_string(SweepRecord::max_refinements) +
                                 " halvings of h, N <= " + std::to_string(SweepRecord::max_steps)
                           : ""}}},
          {"labels", spec.labels},
          {"precision",
           {{"scalar", result.scalar},
            {"digits", result.digits},
            {"bits", result.precision_bits},
            {"smallest_error", result.smallest_error},
            {"guard_bits", result.guard_bits},
            {"rule", "bits >= -log2(smallest error) + guard (docs/theory.md, observed orders)"}}},
          {"reference",
           {{"method", result.reference_method},
            {"tolerance", result.reference_tolerance},
            {"cross_check", result.reference_cross_check},
            {"error_estimate_at_T", result.reference_error_estimate},
            {"error_estimate_allowed", result.reference_check.allowed},
            {"within_tolerance", result.reference_check.holds},
            {"derivative_free_check",
             {{"method",
               "central differences of L and L_d values, no jets: the reference flow's "
               "Euler–Lagrange residual at "
               "t = 0 and T, and one DEL step's residual at the coarsest and finest h (Q×Q cases)"},
              {"euler_lagrange_residual", result.derivative_check.euler_lagrange_residual},
              {"euler_lagrange_allowed", result.derivative_check.euler_lagrange_allowed},
              {"del_residual", result.derivative_check.del_residual},
              {"del_allowed", result.derivative_check.del_allowed},
              {"holds", result.derivative_check.holds}}}}},
          {"seconds", result.seconds},
          {"claim_seconds", claim_seconds},
          {"run_seconds", run_seconds(result)},
          {"cost", run_cost(result)},
          {"claims", claims}};
  // An L that depends on time: the initial time, as used (the run covers [t0, t0 + T]).
  if (spec.formula && spec.formula->time_dependent) out["t0"] = as_used("t0", spec.start_time);
  if (!written.empty()) out["written"] = written;
  if (!spec.warnings.empty()) out["warnings"] = spec.warnings;
  return out;
}

const std::vector<std::string>& verdict_names() {
  static const std::vector<std::string> names = {"pass",  "fail",  "inconclusive",
                                                 "error", "xfail", "xpass"};
  return names;
}

bool run_succeeded(const nlohmann::json& summary) {
  return summary.value("fail", 0) + summary.value("inconclusive", 0) + summary.value("error", 0) +
             summary.value("xpass", 0) ==
         0;
}

std::string summary_text(const nlohmann::json& summary) {
  std::string text;
  for (const auto& verdict : verdict_names())
    text += (text.empty() ? "" : ", ") + std::to_string(summary.value(verdict, 0)) + " " + verdict;
  return text;
}

bool default_tolerance(const std::string& tolerance) {
  if (tolerance.empty()) return true;
  try {  // a merged report may carry anything here: what does not parse is shown, not trusted
    std::size_t used = 0;
    const long double value = std::stold(tolerance, &used);
    return used == tolerance.size() && value == std::stold(default_order_tolerance);
  } catch (const std::exception&) {
    return false;
  }
}

nlohmann::json verdict_counts(const nlohmann::json& cases) {
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& verdict : verdict_names()) counts[verdict] = 0;
  for (const auto& c : cases)
    for (const auto& claim : c["claims"])
      counts[claim["verdict"].get<std::string>()] =
          counts[claim["verdict"].get<std::string>()].get<int>() + 1;
  return counts;
}

// The run block of a report assembled now (report_reading.cpp's merge starts from one too).
nlohmann::json run_block(const RunInfo& run) {
  return {{"command_line", run.command_line},
          {"versions", run.versions},
          {"case_seconds", nlohmann::json::object()}};
}

nlohmann::json assemble_report(std::vector<nlohmann::json> cases, const RunInfo& run) {
  nlohmann::json run_json = run_block(run);
  for (auto& c : cases) {
    if (c.contains("seconds")) {
      run_json["case_seconds"][c["name"].get<std::string>()] = c["seconds"];
      c.erase("seconds");
    }
    if (c.contains("claim_seconds")) {
      if (!c["claim_seconds"].empty()) run_json["claim_seconds"][c["name"].get<std::string>()] = c["claim_seconds"];
      c.erase("claim_seconds");
    }
    if (c.contains("run_seconds")) {
      if (!c["run_seconds"].empty())
        run_json["run_seconds"][c["name"].get<std::string>()] = c["run_seconds"];
      c.erase("run_seconds");
    }
  }
  return {{"schema", report_schema},
          {"run", run_json},
          {"summary", verdict_counts(cases)},
          {"cases", cases}};
}


namespace {

// Writes `content` to all of fd; false on a write error.
bool write_all(int fd, const std::string& content) {
  std::size_t written = 0;
  while (written < content.size()) {
    const ssize_t n = ::write(fd, content.data() + written, content.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    written += static_cast<std::size_t>(n);
  }
  return true;
}

// A new temporary file beside `path` (PATH.XXXXXX: unpredictable, created exclusively, so never
// through a planted link) holding `content`, mode 0644; its name. Throws ReportError, leaving
// nothing behind.
std::string write_temporary(const std::string& path, const std::string& content) {
  std::string temporary = path + ".XXXXXX";
  const int fd = mkstemp(temporary.data());
  if (fd < 0) throw ReportError("cannot create a temporary file beside " + path + ": " + std::strerror(errno));
  const bool ok = fchmod(fd, 0644) == 0 && write_all(fd, content) && fsync(fd) == 0;
  const bool closed = close(fd) == 0;
  if (!ok || !closed) {
    std::remove(temporary.c_str());
    throw ReportError("cannot write " + temporary);
  }
  return temporary;
}

}  // namespace

namespace {

// A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// A text cell (case, claim, series) that a spreadsheet would read as a formula — its first
// character '=', '+', '-', '@', a tab or a carriage return (OWASP's CSV injection rule) — gets a
// leading apostrophe, which spreadsheets show as text and do not evaluate. Numeric columns never
// pass through here: "-2.5e-3" stays a number.
std::string csv_text(const std::string& text) {
  const bool formula = !text.empty() && std::string("=+-@\t\r").find(text.front()) != std::string::npos;
  return csv_field(formula ? "'" + text : text);
}

}  // namespace

std::string render_csv(const nlohmann::json& report) {
  std::ostringstream out;
  out << "case,claim,series,h,N,error,floor,L_evaluations,seconds\n";
  const nlohmann::json run_seconds =
      report.value("run", nlohmann::json::object()).value("run_seconds", nlohmann::json::object());
  for (const auto& c : report.value("cases", nlohmann::json::array())) {
    const std::string name = c.value("name", std::string());
    const std::vector<int> steps = c.value("sweep", nlohmann::json::object())
                                       .value("steps_used", c.value("steps", std::vector<int>{}));
    std::map<int, std::string> evaluations, seconds;
    for (const auto& row : c.value("cost", nlohmann::json::array()))
      if (row.contains("L_evaluations") && row["L_evaluations"].is_number())  // unknown: empty
        evaluations[row.value("N", 0)] = row["L_evaluations"].dump();
    for (const auto& row : run_seconds.value(name, nlohmann::json::array()))
      seconds[row.value("N", 0)] = row.value("seconds", nlohmann::json()).dump();
    for (const auto& claim : c.value("claims", nlohmann::json::array()))
      for (const auto& s : claim.value("series", nlohmann::json::array())) {
        const nlohmann::json h = s.value("h", nlohmann::json::array()),
                             error = s.value("error", nlohmann::json::array());
        for (std::size_t i = 0; i < h.size() && i < error.size(); ++i) {
          // A series has one point per step count of the sweep, in order (per-step claims too).
          const int N = h.size() == steps.size() ? steps[i] : 0;
          out << csv_text(name) << "," << csv_text(claim.value("id", std::string())) << ","
              << csv_text(s.value("label", std::string())) << "," << h[i].get<std::string>() << ","
              << (N ? std::to_string(N) : std::string()) << "," << error[i].get<std::string>()
              << "," << s.value("floor", std::string()) << ","
              << (N && evaluations.count(N) ? evaluations[N] : "") << ","
              << (N && seconds.count(N) ? seconds[N] : "") << "\n";
        }
      }
  }
  return out.str();
}

std::vector<std::string> write_report_directory(const std::string& directory,
                                                const nlohmann::json& computed) {
  namespace fs = std::filesystem;
  // Text that is not UTF-8 — a program's output, a path's bytes — never ends a run after every
  // case has computed: such bytes become U+FFFD in every file, and nothing else changes.
  const nlohmann::json report =
      nlohmann::json::parse(computed.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  const std::vector<std::pair<std::string, std::string>> files = {
      {"report.json", report.dump(2) + "\n"},
      {"report.html", render_html(report)},
      {"junit.xml", render_junit(report)},
      {"report.csv", render_csv(report)}};
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) throw ReportError("cannot create " + directory + ": " + error.message());
  std::vector<std::string> paths, temporaries;
  // Every temporary first, then the renames: a write error leaves no final file changed and no
  // temporary behind; an interruption waits until the four files are in place.
  DeferInterrupts defer;
  try {
    for (const auto& [name, content] : files) {
      paths.push_back((fs::path(directory) / name).string());
      temporaries.push_back(write_temporary(paths.back(), content));
    }
  } catch (...) {
    for (const auto& temporary : temporaries) std::remove(temporary.c_str());
    throw;
  }
  for (std::size_t i = 0; i < paths.size(); ++i) fs::rename(temporaries[i], paths[i]);
  return paths;
}

void write_atomically(const std::string& path, const std::string& content) {
  DeferInterrupts defer;
  std::filesystem::rename(write_temporary(path, content), path);
}

void write_exclusively(const std::string& path, const std::string& content) {
  DeferInterrupts defer;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) throw ReportError("cannot create " + path + ": " + std::strerror(errno));
  const bool ok = write_all(fd, content);
  if (close(fd) != 0 || !ok) {
    std::remove(path.c_str());
    throw ReportError("cannot write " + path);
  }
}

// The table and its notes as print_claims_table prints them, before the terminal's escaping.
static void write_claims_table(std::ostream& out, const nlohmann::json& report, ConsoleDetail detail);

void print_claims_table(std::ostream& terminal, const nlohmann::json& report, ConsoleDetail detail) {
  // Names, messages and a program's quoted output reach the console: control characters shown
  // escaped, never sent to the terminal as escape sequences (core/platform/text.hpp).
  std::ostringstream out;
  write_claims_table(out, report, detail);
  terminal << terminal_safe(out.str());
}

static void write_claims_table(std::ostream& out, const nlohmann::json& report, ConsoleDetail detail) {
  const bool verbose = detail == ConsoleDetail::verbose;
  int passes_left_out = 0;
  struct Row {
    std::string name, claim, verdict, observed, predicted, note;
  };
  std::vector<Row> rows{{"case", "claim", "verdict", "observed", "predicted", "note"}};
  auto order_text = [](const nlohmann::json& value, int decimals) {
    if (!value.is_number()) return std::string("-");
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << value.get<double>();
    return s.str();
  };
  for (const auto& c : report["cases"]) {
    const std::string tolerance = c.value("order_tolerance", std::string());
    for (const auto& claim : c["claims"]) {
      const bool ordered = claim.value("predicted_order", nlohmann::json()).is_number();
      std::string note;
      if (ordered && !default_tolerance(tolerance)) note = "order tolerance " + tolerance;
      if (claim.contains("xfail_reason"))
        note += (note.empty() ? "" : "; ") + std::string("xfail: ") + claim["xfail_reason"].get<std::string>();
      // A claim that did not pass names the series that decided it (its numbers are the row's).
      const nlohmann::json series = claim.value("series", nlohmann::json::array());
      const std::size_t decisive = claim.value("decisive_series", 0);
      if (claim.value("verdict", "") != "pass" && series.size() > 1 && decisive < series.size())
        note += (note.empty() ? "" : "; ") + series[decisive].value("label", std::string());
      // A claim that regressed against --baseline says so in the verdict column: it fails the run
      // (exit 1, a JUnit failure), whatever its own verdict.
      const bool regressed =
          claim.value("baseline", nlohmann::json::object()).value("status", std::string()) ==
          "regressed";
      // A weak pass is listed: it is weaker than its precision promises (its line below says why).
      const bool weak = claim.contains("weakness");
      if (weak) note += (note.empty() ? "" : "; ") + std::string("weak: see below");
      if (!verbose && !regressed && !weak && claim.value("verdict", "") == "pass") {
        ++passes_left_out;
        continue;
      }
      rows.push_back({c["name"], claim["id"],
                      // A pass that regressed reads "regressed"; any other verdict keeps its
                      // word beside it ("inconclusive, regressed"): neither hides the other.
                      regressed ? (claim["verdict"] == "pass" ? std::string("regressed")
                                                              : claim["verdict"].get<std::string>() + ", regressed")
                                : claim["verdict"].get<std::string>(),
                      // An observed order only beside a predicted one: an identity claim's fitted
                      // defect order is in its explanation and the report, not an order verdict.
                      order_text(ordered ? claim.value("observed_order", nlohmann::json())
                                         : nlohmann::json(),
                                 2),
                      order_text(claim.value("predicted_order", nlohmann::json()), 0) +
                          (claim.value("exact_order", false) ? " (exact)" : ""),
                      note});
    }
  }
  std::size_t widths[5] = {0, 0, 0, 0, 0};
  for (const auto& row : rows) {
    widths[0] = std::max(widths[0], row.name.size());
    widths[1] = std::max(widths[1], row.claim.size());
    widths[2] = std::max(widths[2], row.verdict.size());
    widths[3] = std::max(widths[3], row.observed.size());
    widths[4] = std::max(widths[4], row.predicted.size());
  }
  if (rows.size() == 1) rows.clear();  // nothing but the header: no table
  for (const auto& row : rows) {
    std::ostringstream line;
    line << std::left << std::setw(widths[0] + 2) << row.name << std::setw(widths[1] + 2)
         << row.claim << std::setw(widths[2] + 2) << row.verdict << std::right
         << std::setw(widths[3]) << row.observed << "  " << std::left << std::setw(widths[4] + 2)
         << row.predicted << row.note;
    std::string text = line.str();
    text.erase(text.find_last_not_of(' ') + 1);
    out << text << "\n";
  }
  // Why each claim that did not pass (or xfail) did not: its explanation, with what would
  // decide an inconclusive one, so that the console alone says what to do next.
  for (const auto& c : report["cases"])
    for (const auto& claim : c["claims"]) {
      const std::string verdict = claim.value("verdict", "");
      if (verdict == "pass" || verdict == "xfail") continue;
      out << c.value("name", std::string()) << " / " << claim.value("id", std::string()) << ": "
          << verdict << ": " << claim.value("explanation", std::string());
      // An error voids what the claim could have caught: it says so, not nothing.
      if (verdict == "error")
        out << "; detection limit: "
            << claim.value("detection_limit", std::string("none: the measurement cannot be trusted"));
      out << "\n";
    }
  // A pass weaker than its precision promises: why, and what it could still have caught.
  for (const auto& c : report["cases"])
    for (const auto& claim : c["claims"]) {
      if (!claim.contains("weakness") || claim.value("verdict", "") != "pass") continue;
      out << c.value("name", std::string()) << " / " << claim.value("id", std::string())
          << ": pass, but weak: " << claim.value("weakness", std::string()) << "; detection limit: "
          << claim.value("detection_limit", std::string()) << "\n";
    }
  // What each pass could have caught: a pass is only as strong as its detection limit.
  if (passes_left_out > 0)
    out << passes_left_out << " passing claim" << (passes_left_out == 1 ? "" : "s")
        << " not listed (--verbose lists each with its detection limit)\n";
  for (const auto& c : report["cases"])
    if (verbose)
    for (const auto& claim : c["claims"]) {
      const std::string limit = claim.value("detection_limit", std::string());
      if (claim.value("verdict", "") != "pass" || limit.empty() || claim.contains("weakness")) continue;
      out << c.value("name", std::string()) << " / " << claim.value("id", std::string())
          << ": pass; detection limit: " << limit << "\n";
    }
  for (const auto& c : report["cases"]) {
    const nlohmann::json sweep = c.value("sweep", nlohmann::json::object());
    if (!sweep.value("refine", false)) continue;
    // Read through value(): a const json's operator[] on a missing key is undefined behaviour.
    auto range = [](const nlohmann::json& steps) {
      if (!steps.is_array() || steps.empty() || !steps.front().is_number_integer() ||
          !steps.back().is_number_integer())
        return std::string("-");
      return std::to_string(steps.front().get<long long>()) + " … " +
             std::to_string(steps.back().get<long long>());
    };
    out << "sweep of " << c.value("name", std::string())
        << ": N = " << range(sweep.value("steps_used", nlohmann::json::array())) << " (requested "
        << range(sweep.value("requested_steps", nlohmann::json::array()))
        << "); stopped: " << sweep.value("stopped", std::string()) << "\n";
  }
  // --baseline: every claim that regressed or improved, with both runs' numbers.
  for (const auto& c : report["cases"])
    for (const auto& claim : c["claims"]) {
      const nlohmann::json baseline = claim.value("baseline", nlohmann::json::object());
      const std::string status = baseline.value("status", std::string());
      if (status != "regressed" && status != "improved") continue;
      out << c.value("name", std::string()) << " / " << claim.value("id", std::string()) << ": "
          << status << " against the baseline: " << baseline.value("explanation", std::string())
          << "\n";
    }
  // Cases recorded as refused: bad input --keep-going recorded (the run exits 2), or a map
  // program that failed while its case ran (could not run, exit 4): what stopped each.
  const nlohmann::json refused = report.value("refused", nlohmann::json::array());
  std::size_t not_run = 0;
  for (const auto& entry : refused) {
    not_run += could_not_run(entry);
    out << entry.value("name", std::string()) << (could_not_run(entry) ? ": could not run: " : ": refused: ")
        << entry.value("message", std::string()) << "\n";
  }
  const nlohmann::json run = report.value("run", nlohmann::json::object());
  // Cases --claims skipped: none of their claims was selected.
  const nlohmann::json skipped = run.value("skipped_cases", nlohmann::json::array());
  for (const auto& entry : skipped) {
    std::string claims;
    for (const auto& id : entry.value("claims", nlohmann::json::array()))
      claims += (claims.empty() ? "" : ", ") + id.get<std::string>();
    out << entry.value("name", std::string()) << ": skipped: --claims selects none of its claims ("
        << claims << ")\n";
  }
  out << "claims: " << summary_text(report["summary"]);
  if (run.contains("baseline") && run["baseline"].is_object()) {
    const nlohmann::json& b = run["baseline"];
    out << "; against the baseline: " << b.value("regressed", 0) << " regressed, "
        << b.value("improved", 0) << " improved, " << b.value("unchanged", 0) << " unchanged, "
        << b.value("not_compared", 0) << " not compared";
  }
  if (refused.size() > not_run)
    out << "; " << refused.size() - not_run << " case" << (refused.size() - not_run == 1 ? "" : "s")
        << " refused (exit 2)";
  if (not_run > 0)
    out << "; " << not_run << " case" << (not_run == 1 ? "" : "s") << " could not run"
        << (refused.size() > not_run ? "" : " (exit 4)");
  if (!skipped.empty())
    out << "; " << skipped.size() << " case" << (skipped.size() == 1 ? "" : "s") << " skipped (--claims)";
  out << "\n";
}

}  // namespace vivv
