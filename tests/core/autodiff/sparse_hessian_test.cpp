// Sparse derivatives by edge pushing (core/autodiff/sparse_hessian.hpp), in double, long double,
// float128 and MPFR, at n = 1, 2, 7 and 64 coordinates of a Lagrangian that uses every
// operation of the tape (a non-separable kinetic term, sines, exponentials, logarithms, roots,
// arc tangents, quotients, powers, products of different and equal operands):
//   - edge_push in T and the recorded SecondDerivativeTape give a dense jet's value, gradient
//     and Hessian, to a few ulps (at 64 coordinates in MPFR, the gradient against a first-order
//     jet and the Hessian against a first-order jet of the recorded gradient);
//   - every nonzero of the dense Hessian is in the pattern, and the pattern grows like the
//     problem: O(n) entries for a nearest-neighbour chain, not n².
#include "core/autodiff/sparse_hessian.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(SparseHessianTest, AllScalars);

// A chain of n coordinates whose L uses every operation the tape has.
FormulaSystemDefinition every_operation_chain(int n) {
  std::vector<std::string> q, w;
  std::string text;
  for (int i = 1; i <= n; ++i) q.push_back("q" + std::to_string(i)), w.push_back("w" + std::to_string(i));
  for (int i = 0; i < n; ++i) {
    const std::string& qi = q[i];
    const std::string& wi = w[i];
    const std::string& qj = q[(i + 1) % n];
    const std::string& wj = w[(i + 1) % n];
    text += (i ? " + " : "") + wi + "^2/2*(1 + " + qi + "^2/4) - cos(" + qi + " - " + qj + ") + exp(" + qi +
            "/3)*" + wj + " - log(2 + " + qi + "*" + qi + ") + sqrt(3 + " + wi + "^2) + atan(" + qi + "*" + wi +
            ") - " + qi + "/(2 + " + qj + "^2) - (" + qi + " + 2)^(3/2) + sin(" + wi + ")*" + qi + "^3 - 1/(3 - " +
            qi + ")";
  }
  return {"every-operation", text, parse_formula(text), q, w, {}, {}, nullptr};
}

// A point exact in every scalar: q_i = (i mod 5 − 2)/10, w_i = (i mod 3 − 1)/4.
template <class T>
std::vector<T> exact_point(int n) {
  std::vector<T> x(2 * n);
  for (int i = 0; i < n; ++i) x[i] = T(i % 5 - 2) / 10, x[n + i] = T(i % 3 - 1) / 4;
  return x;
}

template <class T>
T relative_difference(const T& a, const T& b) {
  using std::abs, std::max;
  return abs(T(a - b)) / max(T(1), T(abs(b)));
}

// The dense Hessian as a map (row, column) → value, row >= column, of a sparse result.
template <class T>
std::map<std::pair<int, int>, T> as_map(const std::vector<std::pair<int, int>>& pattern, const std::vector<T>& entries) {
  std::map<std::pair<int, int>, T> map;
  for (std::size_t e = 0; e < pattern.size(); ++e) {
    EXPECT_GE(pattern[e].first, pattern[e].second);
    EXPECT_TRUE(map.emplace(pattern[e], entries[e]).second) << "entry listed twice";
  }
  return map;
}

template <class T>
void expect_dense_jets_numbers(int n) {
  const auto system = make_formula_system<T, any_size>(every_operation_chain(n));
  const Tape<T>& tape = *system.program;
  const std::vector<T> x = exact_point<T>(n);
  const int m = 2 * n;
  using J = Jet<T, any_size>;
  std::vector<J> jets;
  for (int k = 0; k < m; ++k) jets.push_back(J::variable(x[k], k, m));
  const J dense = with_size(J(tape.evaluate_first(jets.data())), m);
  const EdgePushed<T> pushed = edge_push(tape, x.data());
  const SecondDerivativeTape<T> recorded(tape);
  const EdgePushed<T> evaluated = recorded.evaluate(x.data());
  const EdgePushed<T> gradient_only = recorded.evaluate_gradient(x.data());
  const T tolerance = 64 * epsilon<T>();
  EXPECT_LE(relative_difference(pushed.value, dense.value), tolerance);
  EXPECT_EQ(evaluated.value, pushed.value);
  EXPECT_EQ(gradient_only.value, pushed.value);
  ASSERT_EQ(static_cast<int>(pushed.gradient.size()), m);
  for (int k = 0; k < m; ++k) {
    EXPECT_LE(relative_difference(pushed.gradient[k], dense.gradient[k]), tolerance) << k;
    EXPECT_LE(relative_difference(evaluated.gradient[k], dense.gradient[k]), tolerance) << k;
    EXPECT_EQ(gradient_only.gradient[k], evaluated.gradient[k]) << k;
  }
  const auto pushed_entries = as_map(pushed.pattern, pushed.hessian);
  const auto recorded_entries = as_map(recorded.pattern, evaluated.hessian);
  for (int r = 0; r < m; ++r)
    for (int c = 0; c <= r; ++c) {
      const auto found = pushed_entries.find({r, c});
      const T sparse = found == pushed_entries.end() ? T(0) : found->second;
      if (found == pushed_entries.end()) {
        EXPECT_EQ(dense.second(r, c), 0) << r << ", " << c << " missing";
      }
      EXPECT_LE(relative_difference(sparse, dense.second(r, c)), tolerance) << r << ", " << c;
      const auto again = recorded_entries.find({r, c});
      const T from_tape = again == recorded_entries.end() ? T(0) : again->second;
      EXPECT_LE(relative_difference(from_tape, dense.second(r, c)), tolerance) << r << ", " << c;
    }
}

TYPED_TEST(SparseHessianTest, GivesTheDenseJetsDerivativesAtOneTwoAndSevenCoordinates) {
  for (int n : {1, 2, 7}) expect_dense_jets_numbers<TypeParam>(n);
}

// At 64 coordinates (128 inputs): the gradient against a first-order jet, and each Hessian
// entry against the first-order jet of the recorded gradient program (forward mode on it).
TYPED_TEST(SparseHessianTest, SixtyFourCoordinatesAgreeWithForwardMode) {
  using T = TypeParam;
  const int n = 64, m = 2 * n;
  const auto system = make_formula_system<T, any_size>(every_operation_chain(n));
  const std::vector<T> x = exact_point<T>(n);
  using J = Jet<T, any_size, 1>;
  std::vector<J> jets;
  for (int k = 0; k < m; ++k) jets.push_back(J::variable(x[k], k, m));
  const J forward = with_size(J(system.program->evaluate_first(jets.data())), m);
  const SecondDerivativeTape<T> recorded(*system.program);
  const EdgePushed<T> evaluated = recorded.evaluate(x.data());
  const T tolerance = 64 * epsilon<T>();
  for (int k = 0; k < m; ++k) EXPECT_LE(relative_difference(evaluated.gradient[k], forward.gradient[k]), tolerance) << k;
  const std::vector<J> gradient = recorded.gradient_program.evaluate(jets);
  const auto entries = as_map(recorded.pattern, evaluated.hessian);
  for (int r = 0; r < m; ++r)
    for (int c = 0; c <= r; ++c) {
      const auto found = entries.find({r, c});
      const T sparse = found == entries.end() ? T(0) : found->second;
      EXPECT_LE(relative_difference(sparse, with_size(gradient[1 + r], m).gradient[c]), tolerance) << r << ", " << c;
    }
  // Each q_i meets q_{i±1}, w_i, w_{i+1}; each w_i meets w_i, q_i, q_{i−1}: a bounded number of
  // entries per coordinate, where a dense Hessian has 2n² + n.
  EXPECT_LE(recorded.pattern.size(), static_cast<std::size_t>(8 * n));
}

// A negative control of the comparison itself: an entry moved off its place is seen.
TYPED_TEST(SparseHessianTest, AWrongEntryIsSeen) {
  using T = TypeParam;
  const int n = 2, m = 4;
  const auto system = make_formula_system<T, any_size>(every_operation_chain(n));
  const std::vector<T> x = exact_point<T>(n);
  using J = Jet<T, any_size>;
  std::vector<J> jets;
  for (int k = 0; k < m; ++k) jets.push_back(J::variable(x[k], k, m));
  const J dense = with_size(J(system.program->evaluate_first(jets.data())), m);
  EdgePushed<T> pushed = edge_push(*system.program, x.data());
  pushed.hessian.front() *= 1 + T(1) / 1000;
  const auto& [r, c] = pushed.pattern.front();
  EXPECT_GT(relative_difference(pushed.hessian.front(), dense.second(r, c)), 64 * epsilon<T>());
}

}  // namespace
}  // namespace vivv
