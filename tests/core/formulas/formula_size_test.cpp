// What a formula costs before it is expanded (core/formulas/formula_size.hpp), index arithmetic
// that cannot wrap (core/formulas/formula.hpp), and the ceiling under which a recording stops
// (core/autodiff/tape.hpp): the three guards that refuse a formula before it costs.
#include <gtest/gtest.h>

#include <string>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_size.hpp"
#include "core/formulas/formula_system.hpp"

namespace vivv {
namespace {

double operations_of(const std::string& text, double stop_above = 1e18) {
  return formula_operations(parse_formula(text), stop_above);
}

// The count is an upper bound on the recording, within a small factor, and never zero.
TEST(FormulaSize, BoundsTheRecordedOperations) {
  const std::string pairs =
      "sum(i = 1..30, sum(j = i+1..30, 1/((x[i] - x[j])^2 + 1)))";  // 435 pairs of 4 to 5 operations
  const double written = operations_of(pairs);
  FormulaSystemDefinition definition;
  definition.lagrangian = parse_formula(pairs);
  for (int i = 1; i <= 30; ++i)
    definition.coordinates.push_back("x[" + std::to_string(i) + "]"),
        definition.velocities.push_back("v[" + std::to_string(i) + "]");
  const double recorded = static_cast<double>(record_lagrangian<double>(definition, 30).nodes.size());
  EXPECT_GE(written, recorded);
  EXPECT_LE(written, 3 * recorded);
  EXPECT_GE(operations_of("q"), 1);
}

// A sum of 10^12 terms is counted from its bounds at once, not term by term.
TEST(FormulaSize, CountsFromTheBoundsWithoutExpanding) {
  EXPECT_DOUBLE_EQ(operations_of("sum(i = 1..1000000000000, x[i]*x[i])"), 1e12 * 4);
  EXPECT_DOUBLE_EQ(operations_of("sum(i = 3..2, x[i])"), 1);
  // A nested sum whose inner bound depends on the outer index: the triangle, N(N−1)/2 terms.
  // (the empty inner sum at i = 100 counts one).
  EXPECT_DOUBLE_EQ(operations_of("sum(i = 1..100, sum(j = i+1..100, x[i]*x[j]))"), 1 + 4950 * 4 + 99 + 2);
  // The walk stops once past the limit: 10^6 outer indices are not all visited.
  EXPECT_GT(operations_of("sum(i = 1..1000000, sum(j = 1..i, x[j]))", 1e6), 1e6);
}

// Index arithmetic refuses what would wrap in 64 bits, at the operation that overflows.
TEST(FormulaSize, IndexArithmeticCannotWrap) {
  for (const std::string text : {"sum(i = 1..4294967296*4294967296 + 3, x[i])",
                                 "sum(i = 1..(0 - 1099511627776) * 1099511627776 + 2, x[i])",
                                 "sum(i = 1..1099511627777, x[i])", "sum(i = 1..18446744073709551617, x[i])"}) {
    try {
      operations_of(text);
      ADD_FAILURE() << text << " was read";
    } catch (const FormulaError& error) {
      EXPECT_NE(std::string(error.what()).find("beyond ±2^40"), std::string::npos) << error.what();
    }
  }
  EXPECT_DOUBLE_EQ(operations_of("sum(i = 1..1099511627776 - 1099511627775, x[i])"), 2);
}

TEST(FormulaSize, SummationIndexCannotBeReserved) {
  FormulaSystemDefinition definition;
  definition.lagrangian = parse_formula("sum(pi = 1..2, v[pi]^2)");
  definition.coordinates = {"x[1]", "x[2]"}, definition.velocities = {"v[1]", "v[2]"};
  EXPECT_THROW(record_lagrangian<double>(definition, 2), FormulaError);
}

// Under a ceiling a recording stops when it passes it; without one, the same formula records.
TEST(FormulaSize, RecordingStopsAtItsCeiling) {
  FormulaSystemDefinition definition;
  definition.lagrangian = parse_formula("sum(i = 1..200, sum(j = i+1..200, x[i]*x[j]))");
  for (int i = 1; i <= 200; ++i)
    definition.coordinates.push_back("x[" + std::to_string(i) + "]"),
        definition.velocities.push_back("v[" + std::to_string(i) + "]");
  {
    const TapeCeiling ceiling(1000);
    try {
      record_lagrangian<double>(definition, 200);
      ADD_FAILURE() << "recorded past its ceiling";
    } catch (const TapeCeilingReached& reached) {
      EXPECT_EQ(reached.nodes, 1000u);
    }
  }
  EXPECT_GT(record_lagrangian<double>(definition, 200).nodes.size(), 19900u);
}

}  // namespace
}  // namespace vivv
