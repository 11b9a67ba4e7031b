// The claim registry: each claim is a small type measuring one quantity,
// stating one prediction and returning one verdict with its evidence
// (docs/claims.md). Adding a claim = writing its type and listing it here.
#pragma once

#include <iterator>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "harness/claims/discrete_noether.hpp"
#include "harness/claims/energy_balance.hpp"
#include "harness/claims/energy_behaviour.hpp"
#include "harness/claims/exact_discretization.hpp"
#include "harness/claims/global_order.hpp"
#include "harness/claims/local_consistency.hpp"
#include "harness/claims/map_local_order.hpp"
#include "harness/claims/modified_energy.hpp"
#include "harness/claims/past_future_symmetry.hpp"
#include "harness/claims/precision_leak.hpp"
#include "harness/claims/symplecticity.hpp"
#include "harness/claims/tq_claims.hpp"
#include "harness/claims/twin_term.hpp"
#include "harness/verdicts/rejudge.hpp"

namespace vivv {

using ClaimRegistry =
    std::tuple<GlobalOrderClaim, LagrangianOrderClaim, LegendreOrderClaim, TwinTermInvarianceClaim,
               MismatchedLegendreClaim, LocalOrderClaim, ContactOrderClaim, QxQTQEquivalenceClaim,
               ExistenceUniquenessClaim, ExactDiscretizationClaim, PastFutureSymmetryClaim,
               SymplecticityClaim, DiscreteNoetherClaim, EnergyBehaviourClaim, EnergyBalanceClaim,
               ModifiedEnergyClaim, PrecisionLeakClaim, MapLocalOrderClaim>;

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

// Every registered claim's id with the rules its series may be decided by (series_rules): what
// re-judging a report takes from the claims rather than from the report (harness/verdicts/rejudge.hpp).
inline ClaimSeriesRules registered_series_rules() {
  ClaimSeriesRules rules;
  std::apply(
      [&](auto... claim) {
        ((rules[claim.id] = std::set<std::string>(std::begin(claim.series_rules),
                                                  std::end(claim.series_rules))),
         ...);
      },
      ClaimRegistry{});
  return rules;
}

// The order the theorem behind claim `id` predicts for the case's main series;
// none for a claim that predicts an identity, exactness or inconsistency.
template <LagrangianSystem System>
std::optional<int> theorem_order(const std::string& id, const CaseContext<System>& context) {
  std::optional<int> order;
  bool found = false;
  std::apply([&](auto... claim) { ((!found && id == claim.id ? (found = true, order = claim.theorem_order(context), 0) : 0), ...); },
             ClaimRegistry{});
  if (!found) throw std::invalid_argument("no claim '" + id + "' is registered");
  return order;
}

// A case may sharpen a theorem's prediction, never weaken it: every order in
// "expect" must be at least the theorem's order for the case's discretization,
// and only claims that predict an order take one. Throws CaseError naming
// expect.<claim>, the declared and the theorem's order.
template <LagrangianSystem System>
void check_declared_orders(const CaseContext<System>& context) {
  for (const auto& [id, declared] : context.spec.expect) {
    const std::string field = "expect." + id;
    std::optional<int> theorem = theorem_order(id, context);
    if (!theorem)
      throw CaseError(context.spec.file, field,
                      id + " predicts no order for this case (an identity, exactness or an "
                           "inconsistency), so there is none to declare");
    if (declared < *theorem)
      throw CaseError(context.spec.file, field,
                      "declared order " + std::to_string(declared) + " is below the theorem's order " +
                          std::to_string(*theorem) + " for this discretization: a case may sharpen a "
                          "prediction, never weaken it");
  }
}

// A known failure states what it expects (cases/case_file.hpp, ExpectedFailure): a claim that
// predicts an order fails in a range of observed orders, which the case must give; one that
// predicts none takes no range. Throws CaseError naming xfail.<claim>.
template <LagrangianSystem System>
void check_expected_failures(const CaseContext<System>& context) {
  for (const auto& [id, expected] : context.spec.xfail) {
    const std::string field = "xfail." + id;
    bool fails_by_order = true;
    std::apply(
        [&](auto... claim) {
          ((id == claim.id ? (fails_by_order = claim.fails_by_order, 0) : 0), ...);
        },
        ClaimRegistry{});
    const bool ordered = fails_by_order && theorem_order(id, context).has_value();
    if (ordered && !expected.observed_order)
      throw CaseError(context.spec.file, field,
                      id + " predicts an order for this case, so its known failure must say which: "
                           "{\"reason\": \"...\", \"observed_order\": [\"low\", \"high\"]}, the "
                           "range its fitted "
                           "order falls in (any other failure then fails the run)");
    if (!ordered && expected.observed_order)
      throw CaseError(
          context.spec.file, field + ".observed_order",
          "a failure of " + id +
              " in this case is not an observed order (an identity, exactness, "
              "an inconsistency or a precision leak), so there is no observed order to expect");
  }
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
