// The claim registry: each claim is a small type measuring one quantity,
// stating one prediction and returning one verdict with its evidence
// (DESIGN §1.5). Adding a claim = writing its type and listing it here.
#pragma once

#include <string>
#include <tuple>
#include <vector>

#include "harness/claims/exact_discretization.hpp"
#include "harness/claims/global_order.hpp"
#include "harness/claims/local_consistency.hpp"
#include "harness/claims/past_future_symmetry.hpp"
#include "harness/claims/tq_claims.hpp"
#include "harness/claims/twin_term.hpp"

namespace vivv {

using ClaimRegistry =
    std::tuple<GlobalOrderClaim, LagrangianOrderClaim, LegendreOrderClaim, TwinTermInvarianceClaim,
               MismatchedLegendreClaim, LocalOrderClaim, ContactOrderClaim, QxQTQEquivalenceClaim,
               ExistenceUniquenessClaim, ExactDiscretizationClaim, PastFutureSymmetryClaim>;

struct ClaimInfo {
  std::string id, source, prediction;
};

// id, source and prediction of every registered claim.
inline std::vector<ClaimInfo> registered_claims() {
  std::vector<ClaimInfo> info;
  std::apply([&](auto... claim) { (info.push_back({claim.id, claim.source, claim.prediction}), ...); },
             ClaimRegistry{});
  return info;
}

// Evaluates the registered claim `id` on a case.
template <LagrangianSystem System>
ClaimResult evaluate_claim(const std::string& id, const CaseContext<System>& context) {
  std::optional<ClaimResult> result;
  std::apply(
      [&](auto... claim) {
        ((!result && id == claim.id ? (result = claim.evaluate(context), 0) : 0), ...);
      },
      ClaimRegistry{});
  if (!result) throw std::invalid_argument("no claim '" + id + "' is registered");
  return *result;
}

}  // namespace vivv
