// What every claim shares, so that a claim states only its own formula,
// source, measurement, prediction and verdict (docs/claims.md, "Adding a claim").
//
// A claim is a type deriving from Claim<itself> with
//   static constexpr const char* id, source, prediction;
//   template <LagrangianSystem System> static ClaimResult evaluate(const CaseContext<System>&);
// and, if it predicts an order, theorem_order(context) returning it (the
// default predicts none: an identity, exactness or an inconsistency). It is
// listed once in harness/claims.hpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/case_context.hpp"
#include "harness/series.hpp"

namespace vivv {

template <class Derived>
struct Claim {
  // No order: the claim predicts an identity, exactness or an inconsistency.
  template <LagrangianSystem System>
  static std::optional<int> theorem_order(const CaseContext<System>&) {
    return std::nullopt;
  }

  // An empty result carrying the claim's id, source and prediction.
  static ClaimResult result() { return claim_result_for(Derived::id, Derived::source, Derived::prediction); }

  // The prediction for the claim's main series: the theorem's order, or the
  // exact order the case declares for this claim.
  template <LagrangianSystem System>
  static OrderPrediction predicted(const CaseContext<System>& context) {
    return context.predict(Derived::id, *Derived::theorem_order(context));
  }
};

// `measure(h)` at every h of the sweep, reporting "<what> at h = …" as it goes.
template <LagrangianSystem System, class Measure>
std::vector<typename System::Scalar> measure_each_step(const CaseContext<System>& context, const std::string& what,
                                                       Measure&& measure) {
  using T = typename System::Scalar;
  std::vector<T> values;
  for (const T& h : context.steps()) {
    context.report(what + " at h = " + to_decimal<T>(h, 6));
    values.push_back(measure(h));
  }
  return values;
}

// A series over the case's sweep, fitted with its floor and options and judged
// against `predicted` (none: fitted and shown, not judged).
template <LagrangianSystem System>
Series sweep_series(const CaseContext<System>& context, const std::string& label,
                    const std::vector<typename System::Scalar>& error,
                    std::optional<OrderPrediction> predicted) {
  return make_series(label, context.steps(), error, context.floor(),
                     predicted ? std::optional<double>(predicted->order) : std::nullopt,
                     predicted && predicted->exact, context.order_tolerance, context.fit_options);
}

// An identity checked at each h against its own tolerance: the measured values
// as a series (not fitted against a prediction), the verdict `holds` stated
// in words, and a row per h in the evidence under "per_step".
template <class T>
struct PerStepCheck {
  std::vector<T> values;
  bool holds = true;
  nlohmann::json rows = nlohmann::json::array();

  // Records `value` at h against `tolerance`; `row` may carry more columns, and
  // `also` a further condition the step must meet (its columns in `row`).
  bool add(const T& h, const T& value, const T& tolerance, nlohmann::json row = nlohmann::json::object(),
           bool also = true) {
    const bool ok = value <= tolerance && also;
    holds = holds && ok;
    values.push_back(value);
    row["h"] = to_decimal<T>(h);
    row["measured"] = to_decimal<T>(value);
    row["tolerance"] = to_decimal<T>(tolerance);
    row["holds"] = ok;
    rows.push_back(std::move(row));
    return ok;
  }

  // Adds the series and the per-step evidence to `claim` and concludes it.
  template <LagrangianSystem System>
  void conclude_claim(ClaimResult& claim, const CaseContext<System>& context, const std::string& label,
                      const std::string& held, const std::string& failed) const {
    claim.evidence["per_step"] = rows;
    Series series = sweep_series(context, label, values, std::nullopt);
    series.holds = holds;
    series.explanation = holds ? held : failed;
    claim.series.push_back(series);
    conclude(claim);
  }
};

}  // namespace vivv
