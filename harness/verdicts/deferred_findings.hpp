// Findings one claim defers to another (docs/claims.md, "Evidence of a defect never passes").
// precision-leak judges precision only: a lower-order term that is no narrower format's rounding
// is an order defect of the method, which it leaves to local-order and passes. That finding must
// reach a verdict: when local-order is not listed, precision-leak does not pass; when local-order
// is listed but its own steps never reached the h where the defect shows (its grid or floor stops
// short: a 1/24 written as 0.04166666667 showed from h = 6.18e-5 down), local-order fails on
// precision-leak's finding. Applied once a case's claims are all measured.
#pragma once

#include <string>
#include <vector>

#include "reports/results.hpp"

namespace vivv {

inline void settle_deferred_findings(std::vector<ClaimResult>& claims) {
  ClaimResult* leak = nullptr;
  ClaimResult* local = nullptr;
  for (ClaimResult& claim : claims) {
    if (claim.id == "precision-leak") leak = &claim;
    if (claim.id == "local-order") local = &claim;
  }
  if (!leak || leak->verdict != "pass" || !leak->evidence.value("order_defect", false)) return;
  std::string finding = leak->explanation;
  const std::string deferral = "no precision leak (order defect: see local-order): ";
  if (finding.rfind(deferral, 0) == 0) finding.erase(0, deferral.size());
  if (!local) {
    leak->verdict = "fail";
    leak->decisive_series = leak->series.empty() ? 0 : static_cast<int>(leak->series.size()) - 1;
    leak->explanation = "an order defect, and local-order, which judges it, is not among the claims run: " +
                        finding + "; evidence of a defect does not pass (list local-order to have it judged)";
    leak->evidence["deferred_to"] = "local-order (not listed): precision-leak fails on its finding";
    return;
  }
  leak->evidence["deferred_to"] = "local-order";
  if (local->verdict != "pass") return;
  local->verdict = "fail";
  local->explanation = "precision-leak's profile, which halves h further than this claim's steps, found an "
                       "order defect: " + finding + "; this claim's own steps did not reach it";
  local->evidence["deferred_from_precision_leak"] = finding;
}

}  // namespace vivv
