// The memory estimate of a case (cases/memory_estimate.hpp): the reference orders it restates are
// the reference flow's own in every scalar, and its parts follow what the case computes. Its
// agreement with measured peaks is the ctest scale/memory-estimate-* (bench/memory_table.py).
#include "cases/memory_estimate.hpp"

#include <gtest/gtest.h>

#include "cases/systems.hpp"
#include "harness/context/case_context.hpp"
#include "references/taylor_reference.hpp"

namespace vivv {
namespace {

// The orders the estimate counts coefficients for are those TaylorReference takes at the tolerance
// a case of that scalar asks (reference_tolerance_for), flow and cross-check.
template <class T>
void expect_the_reference_orders(const std::string& scalar, int digits, bool double_program) {
  const TaylorReference<Pendulum<T>> reference(Pendulum<T>{}, reference_tolerance_for<T>(digits, double_program));
  const ReferenceOrders orders = reference_orders(scalar, digits, double_program);
  EXPECT_EQ(orders.flow, reference.order()) << scalar << " at " << digits << " digits";
  EXPECT_EQ(orders.check, reference.check_order()) << scalar << " at " << digits << " digits";
}

TEST(MemoryEstimate, ReferenceOrdersAreTheReferencesOwn) {
  expect_the_reference_orders<double>("double", 0, false);
  expect_the_reference_orders<long double>("long double", 0, false);
  expect_the_reference_orders<quad>("float128", 0, false);
  expect_the_reference_orders<quad>("float128", 0, true);  // a double program, judged in float128
  for (int digits : {20, 30, 60, 200}) {
    const PrecisionGuard guard(static_cast<unsigned>(digits));
    expect_the_reference_orders<mpfr_real>("mpfr", digits, false);
  }
}

// A chain of n coordinates, read as a case file would be.
CaseSpec chain_case(int n, const nlohmann::json& discretization, const std::vector<std::string>& claims,
                    const std::vector<int>& steps = {400, 800, 1600, 3200}) {
  std::vector<std::string> q, w;
  for (int i = 0; i < n; ++i) q.push_back("0.1"), w.push_back("0");
  nlohmann::json json = {
      {"name", "chain"},
      {"system",
       {{"name", "chain"},
        {"coordinates", {{{"x", {n}}}}},
        {"velocities", {{{"v", {n}}}}},
        {"lagrangian", "sum(i = 1..n, v[i]^2)/2 - sum(i = 1..n - 1, (x[i+1] - x[i])^2)/2 - sum(i = 1..n, x[i]^4)/4"}}},
      {"initial", {{"q", q}, {"w", w}}},
      {"T", "1"},
      {"steps", steps},
      {"scalar", "double"},
      {"discretization", discretization},
      {"claims", claims}};
  std::string text = json.dump();
  for (std::size_t at; (at = text.find("..n")) != std::string::npos;) text.replace(at, 3, ".." + std::to_string(n));
  return parse_case(nlohmann::json::parse(text), "chain.json");
}

// (The sweeps are long enough that computing, not recording L, is the larger phase: the estimate
// then lists the computing's parts.)
TEST(MemoryEstimate, ItsPartsFollowWhatTheCaseComputes) {
  const nlohmann::json midpoint = {{"kind", "midpoint"}};
  const nlohmann::json galerkin = {{"kind", "galerkin"}, {"degree", 2}, {"quadrature", "gauss"}, {"nodes", 2}};
  const MemoryEstimate global = estimate_memory(chain_case(64, midpoint, {"global-order"}), "double", 0);
  ASSERT_NE(global.part("reference flow"), nullptr);
  ASSERT_NE(global.part("sweep"), nullptr);
  EXPECT_EQ(global.part("symplecticity's Jacobians"), nullptr);
  EXPECT_EQ(global.part("dense second derivatives"), nullptr);
  EXPECT_EQ(global.parts.front().name, "the process");
  // Above 16 coordinates symplecticity walks the sweep with its probes (more vectors a step) and
  // keeps no Jacobian; at 16 it keeps a dense one a step.
  const MemoryEstimate probes =
      estimate_memory(chain_case(64, midpoint, {"global-order", "symplecticity"}), "double", 0);
  EXPECT_GT(probes.part("sweep")->bytes, global.part("sweep")->bytes);
  EXPECT_EQ(probes.part("symplecticity's Jacobians"), nullptr);
  const MemoryEstimate dense = estimate_memory(chain_case(16, midpoint, {"symplecticity"}), "double", 0);
  ASSERT_NE(dense.part("symplecticity's Jacobians"), nullptr);
  EXPECT_DOUBLE_EQ(dense.part("symplecticity's Jacobians")->bytes, 3200.0 * 4 * 16 * 16 * 8);
  // Galerkin differentiates L in dense second-order jets.
  EXPECT_NE(estimate_memory(chain_case(8, galerkin, {"global-order"}), "double", 0).part("dense second derivatives"),
            nullptr);
  // The reference's coefficients grow with the scalar's size and its orders.
  const CaseSpec spec = chain_case(64, midpoint, {"global-order"});
  EXPECT_GT(estimate_memory(spec, "float128", 0).part("reference flow")->bytes,
            2 * global.part("reference flow")->bytes);
  EXPECT_GT(estimate_memory(spec, "mpfr", 60).part("reference flow")->bytes,
            estimate_memory(spec, "mpfr", 30).part("reference flow")->bytes);
  // The total is the sum of the parts.
  double sum = 0;
  for (const auto& part : probes.parts) sum += part.bytes;
  EXPECT_DOUBLE_EQ(probes.total(), sum);
}

}  // namespace
}  // namespace vivv
