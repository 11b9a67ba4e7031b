// The sparse path of systems sized at run time (core/qxq/sparse_legendre.hpp, the sparse
// branches of core/lagrangian/lagrangian.hpp, core/lagrangian/euler_lagrange_tape.hpp,
// core/structure/energy.hpp and core/numerics/linear_solve.hpp), against the dense jets the same
// system is differentiated in when its sparse derivatives are taken away, in double, long double,
// float128 and MPFR, at 1, 2 and 7 coordinates of a non-separable chain with a gyroscopic term:
//   - every Q × Q rule that is a sum of L on the segment, and an expression L_d, with and without
//     a twin term: L_d, both Legendre transforms and all four Hessian blocks, to a few ulps;
//   - a DEL step and a start from the momentum: the same q_{k+1}, in as many Newton iterations;
//   - L's derivatives, the momentum, the energy, the Euler–Lagrange acceleration, its tape, and
//     the inverse Legendre transform;
//   - the sparse solve refuses a singular matrix, structurally and numerically, as the dense one;
//   - the Euler–Lagrange tape of a regular L whose d²L/dw² has identically zero diagonal entries
//     (L = w1 w2 + ... − V) gives the acceleration of a pivoting solve at 2, 3 and 8 coordinates,
//     sparse and dense, and one with an identically zero column is refused.
#include "core/qxq/sparse_legendre.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_discretization.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/lagrangian/euler_lagrange_tape.hpp"
#include "core/lagrangian/state.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/qxq/discrete_lagrangian.hpp"
#include "core/structure/energy.hpp"
#include "tests/chain_formula.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(SparseLegendreTest, AllScalars);

// L = Σ w_i²/2·(1 + q_i²/4) + Σ (q_i w_{i+1} − q_{i+1} w_i)/2 − Σ (q_{i+1} − q_i)²/2 − Σ cos q_i.
FormulaSystemDefinition gyroscopic_chain(int n) {
  std::vector<std::string> q, w;
  for (int i = 1; i <= n; ++i) q.push_back("q" + std::to_string(i)), w.push_back("w" + std::to_string(i));
  std::string text;
  for (int i = 0; i < n; ++i) {
    text += (i ? " + " : "") + w[i] + "^2/2*(1 + " + q[i] + "^2/4) - cos(" + q[i] + ")";
    if (i + 1 < n)
      text += " + (" + q[i] + "*" + w[i + 1] + " - " + q[i + 1] + "*" + w[i] + ")/2 - (" + q[i + 1] + " - " + q[i] +
              ")^2/2";
  }
  return {"gyroscopic-chain", text, parse_formula(text), q, w, {}, {}, nullptr};
}

// The chain's state (tests/chain_formula.hpp), exact in every scalar.
template <class T>
State<T, any_size> gyroscopic_state(int n) {
  return testing::chain_state<T, any_size>(n);
}

using testing::distance;

template <class T>
std::vector<QxQDiscretization<T>> rules(const FormulaSystem<T, any_size>& system) {
  std::vector<QxQDiscretization<T>> all;
  for (QxQRule rule : {QxQRule::left_rectangle, QxQRule::right_rectangle, QxQRule::midpoint, QxQRule::alpha,
                       QxQRule::trapezoid, QxQRule::weighted}) {
    QxQDiscretization<T> d;
    d.rule = rule;
    d.parameter = T(3) / 10;
    all.push_back(d);
  }
  const std::string text = "h*L((qb + qe)/2, (qe - qb)/h) + h^3*(qe[1] - qb[1])^2";
  all.push_back(expression_discretization(system, text, parse_formula(text), {}, 2));
  const int n = system.size();
  for (std::size_t k = 0, count = all.size(); k < count; ++k) {
    QxQDiscretization<T> twinned = all[k];
    std::vector<T> a(n);
    for (int i = 0; i < n; ++i) a[i] = T(i + 1) / 7;
    twinned.twin = TwinTerm<T>{a, 2};
    all.push_back(twinned);
  }
  return all;
}

template <class T>
void expect_dense_numbers(int n) {
  const auto sparse = make_formula_system<T, any_size>(gyroscopic_chain(n));
  auto dense = sparse;
  dense.derivatives = nullptr;
  const State<T, any_size> x = gyroscopic_state<T>(n);
  const T h = T(1) / 8;
  const Vector<T, any_size> x1 = x.q + h * x.w;
  const T tolerance = 256 * epsilon<T>();
  for (QxQDiscretization<T> rule : rules(sparse)) {
    SCOPED_TRACE(rule_name(rule.rule) + (rule.twin ? " with a twin term" : ""));
    ASSERT_TRUE(sparse_path_applies(sparse, rule));
    ASSERT_FALSE(sparse_path_applies(dense, rule));
    auto dense_rule = rule;
    dense_rule.expression_derivatives = nullptr;
    const auto a = discrete_legendre(sparse, rule, x.q, x1, h);
    const auto b = discrete_legendre(dense, dense_rule, x.q, x1, h);
    using std::abs;
    EXPECT_LE(abs(T(a.value - b.value)), tolerance);
    EXPECT_LE(distance(a.p_begin, b.p_begin), tolerance);
    EXPECT_LE(distance(a.p_end, b.p_end), tolerance);
    EXPECT_LE(distance(a.dp_begin_dq_b, b.dp_begin_dq_b), tolerance / h);
    EXPECT_LE(distance(a.dp_begin_dq_e, b.dp_begin_dq_e), tolerance / h);
    EXPECT_LE(distance(a.dp_end_dq_b, b.dp_end_dq_b), tolerance / h);
    EXPECT_LE(distance(a.dp_end_dq_e, b.dp_end_dq_e), tolerance / h);
    const auto momenta = discrete_momenta(sparse, rule, x.q, x1, h);
    EXPECT_LE(distance(momenta.p_begin, b.p_begin), tolerance);
    EXPECT_LE(distance(momenta.p_end, b.p_end), tolerance);
    const auto block = sparse_begin_momentum(sparse, rule, x.q, x1, h);
    EXPECT_LE(distance(Matrix<T, any_size, any_size>(block.dp_begin_dq_e), b.dp_begin_dq_e), tolerance / h);

    const auto [y2, sparse_report] = del_step(sparse, matched_scheme(rule), x.q, x1, h);
    const auto [z2, dense_report] = del_step(dense, matched_scheme(dense_rule), x.q, x1, h);
    ASSERT_TRUE(sparse_report.converged && dense_report.converged);
    EXPECT_EQ(sparse_report.iterations, dense_report.iterations);
    EXPECT_LE(distance(y2, z2), 16 * tolerance);
    EXPECT_LE(distance(start_from_momentum(sparse, rule, x.q, x.w, h), start_from_momentum(dense, dense_rule, x.q, x.w, h)),
              16 * tolerance);
  }

  const auto c = lagrangian_derivatives(sparse, x.q, x.w);
  const auto d = lagrangian_derivatives(dense, x.q, x.w);
  EXPECT_LE(distance(c.dL_dq, d.dL_dq), tolerance);
  EXPECT_LE(distance(c.dL_dw, d.dL_dw), tolerance);
  EXPECT_LE(distance(c.d2L_dw2, d.d2L_dw2), tolerance);
  EXPECT_LE(distance(c.d2L_dwdq, d.d2L_dwdq), tolerance);
  EXPECT_LE(distance(momentum(sparse, x.q, x.w), momentum(dense, x.q, x.w)), tolerance);
  using std::abs;
  EXPECT_LE(abs(T(energy(sparse, x.q, x.w) - energy(dense, x.q, x.w))), tolerance);
  const Vector<T, any_size> acceleration = euler_lagrange_acceleration(dense, x.q, x.w);
  EXPECT_LE(distance(euler_lagrange_acceleration(sparse, x.q, x.w), acceleration), tolerance);
  std::vector<T> y(x.q.data(), x.q.data() + n);
  y.insert(y.end(), x.w.data(), x.w.data() + n);
  const std::vector<T> from_sparse_tape = euler_lagrange_tape(sparse).evaluate(y);
  const std::vector<T> from_dense_tape = euler_lagrange_tape(dense).evaluate(y);
  for (int i = 0; i < n; ++i) {
    EXPECT_LE(abs(T(from_sparse_tape[i] - acceleration[i])), tolerance) << i;
    EXPECT_LE(abs(T(from_dense_tape[i] - acceleration[i])), tolerance) << i;
  }
  const Vector<T, any_size> p = momentum(dense, x.q, x.w);
  const Vector<T, any_size> guess = x.w + Vector<T, any_size>::Constant(n, T(1) / 50);
  EXPECT_LE(distance(velocity_for_momentum(sparse, x.q, p, guess), x.w), tolerance);
}

TYPED_TEST(SparseLegendreTest, GivesTheDenseJetsNumbersAtOneTwoAndSevenCoordinates) {
  for (int n : {1, 2, 7}) {
    SCOPED_TRACE(std::to_string(n) + " coordinates");
    expect_dense_numbers<TypeParam>(n);
  }
}

// The sparse solve refuses what the dense one refuses: a matrix with an empty row, and one whose
// rank is one short by cancellation (rows 1 and 3 equal up to rounding).
TYPED_TEST(SparseLegendreTest, ASingularSparseMatrixIsRefused) {
  using T = TypeParam;
  const T threshold = T(16) * epsilon<T>();
  const Vector<T, any_size> right = Vector<T, any_size>::Ones(3);
  Vector<T, any_size> solution = zero_vector<T, any_size>(3);
  Matrix<T, any_size, any_size> dense(3, 3);
  dense << 2, 1, 0, 1, 3, 1, 2, 1, 0;
  dense(2, 0) += epsilon<T>();
  Eigen::SparseMatrix<T> sparse = dense.sparseView();
  EXPECT_FALSE(solve_linear(dense, right, solution, threshold));
  EXPECT_FALSE(solve_linear(sparse, right, solution, threshold));
  Eigen::SparseMatrix<T> empty_row(3, 3);
  empty_row.insert(0, 0) = 1, empty_row.insert(1, 1) = 1;
  EXPECT_FALSE(solve_linear(empty_row, right, solution, threshold));
  // A sparse matrix of at most dense_factorization_limit unknowns is factored dense: the same
  // refusals by Eigen's SparseLU itself (a limit of 0).
  for (const int limit : {0, dense_factorization_limit}) {
    SparseFactorization<T> lu;
    EXPECT_FALSE(lu.factor(sparse, threshold, limit)) << limit;
    EXPECT_FALSE(lu.factor(empty_row, threshold, limit)) << limit;
  }
  // The control: a regular matrix of the same pattern is solved, as densely, by both.
  dense(2, 0) = 0;
  dense(2, 2) = 1;
  sparse = dense.sparseView();
  ASSERT_TRUE(solve_linear(sparse, right, solution, threshold));
  EXPECT_LE(distance(Vector<T, any_size>(dense * solution), right), 16 * epsilon<T>());
  for (const int limit : {0, dense_factorization_limit}) {
    SparseFactorization<T> lu;
    ASSERT_TRUE(lu.factor(sparse, threshold, limit)) << limit;
    EXPECT_LE(distance(Vector<T, any_size>(dense * lu.solve(right)), right), 16 * epsilon<T>()) << limit;
  }
}

// Either side of dense_factorization_limit the same factorization: a tridiagonal matrix of 2, the
// limit and twice the limit unknowns solved sparse and dense to rounding, and one made singular
// (its last row a copy of the one before) refused by both.
TYPED_TEST(SparseLegendreTest, DenseAndSparseFactorizationsAgreeAcrossTheLimit) {
  using T = TypeParam;
  const T threshold = T(16) * epsilon<T>();
  for (const int n : {2, dense_factorization_limit, 2 * dense_factorization_limit}) {
    Matrix<T, any_size, any_size> dense = Matrix<T, any_size, any_size>::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      dense(i, i) = T(2) + T(i) / 7;
      if (i + 1 < n) dense(i, i + 1) = -1, dense(i + 1, i) = T(-1) / 3;
    }
    const Vector<T, any_size> right = Vector<T, any_size>::Ones(n);
    SparseFactorization<T> sparse_lu, dense_lu;
    ASSERT_TRUE(sparse_lu.factor(dense.sparseView(), threshold, 0)) << n;
    ASSERT_TRUE(dense_lu.factor(dense.sparseView(), threshold, n)) << n;
    EXPECT_LE(distance(sparse_lu.solve(right), dense_lu.solve(right)), 64 * n * epsilon<T>()) << n;
    dense.row(n - 1) = dense.row(n - 2);
    EXPECT_FALSE(sparse_lu.factor(dense.sparseView(), threshold, 0)) << n;
    EXPECT_FALSE(dense_lu.factor(dense.sparseView(), threshold, n)) << n;
  }
}

// L = Σ_k w_{2k−1} w_{2k} + Σ_k w_{2k} w_{2k+1}/4 (+ w_n²/2 for odd n) − Σ cos q_i − Σ (q_{i+1} − q_i)²/2:
// d²L/dw² is tridiagonal with a zero diagonal (but its last entry for odd n) and regular
// (determinant ±1 at 2 and 3 coordinates), so an elimination that took the diagonal as its pivots
// divided by zero; the tape exchanges rows instead, where the structure says an entry is zero.
FormulaSystemDefinition indefinite_chain(int n) {
  std::vector<std::string> q, w;
  for (int i = 1; i <= n; ++i) q.push_back("q" + std::to_string(i)), w.push_back("w" + std::to_string(i));
  std::string text = n % 2 ? w[n - 1] + "^2/2" : "0";
  for (int i = 0; i + 1 < n; ++i) text += " + " + w[i] + "*" + w[i + 1] + (i % 2 ? "/4" : "");
  for (int i = 0; i < n; ++i) {
    text += " - cos(" + q[i] + ")";
    if (i + 1 < n) text += " - (" + q[i + 1] + " - " + q[i] + ")^2/2";
  }
  return {"indefinite-chain", text, parse_formula(text), q, w, {}, {}, nullptr};
}

template <class T, int N>
void expect_pivoted_acceleration(int n) {
  const auto sparse = make_formula_system<T, N>(indefinite_chain(n));
  const auto dense = [&] {
    auto without = sparse;
    without.derivatives = nullptr;
    return without;
  }();
  const State<T, N> x = testing::chain_state<T, N>(n);
  const Vector<T, N> acceleration = euler_lagrange_acceleration(dense, x.q, x.w);
  // The control: the pivoting solve's acceleration does solve M a = dL/dq (no dL/dw dq here).
  const auto d = lagrangian_derivatives(dense, x.q, x.w);
  EXPECT_LE(distance(Vector<T, N>(d.d2L_dw2 * acceleration), Vector<T, N>(d.dL_dq)), 64 * epsilon<T>());
  std::vector<T> y(x.q.data(), x.q.data() + n);
  y.insert(y.end(), x.w.data(), x.w.data() + n);
  using std::abs;
  for (const auto* system : {&sparse, &dense}) {
    if (system == &sparse && !sparse.derivatives) continue;  // fixed sizes have no sparse derivatives
    const std::vector<T> from_tape = euler_lagrange_tape(*system).evaluate(y);
    for (int i = 0; i < n; ++i)
      EXPECT_LE(abs(T(from_tape[i] - acceleration[i])), 64 * epsilon<T>()) << (system == &sparse ? "sparse " : "dense ") << i;
  }
}

TYPED_TEST(SparseLegendreTest, AZeroDiagonalOfTheMassMatrixIsPivotedNotRefused) {
  expect_pivoted_acceleration<TypeParam, 2>(2);
  for (int n : {2, 3, 8}) {
    SCOPED_TRACE(std::to_string(n) + " coordinates");
    expect_pivoted_acceleration<TypeParam, any_size>(n);
  }
  // The negative: w2 enters L nowhere, so column 2 of d²L/dw² is identically zero.
  for (int n : {2, 3}) {
    std::vector<std::string> q{"q1", "q2", "q3"}, w{"w1", "w2", "w3"};
    q.resize(n), w.resize(n);
    const std::string text = n == 2 ? "w1^2/2 - q1^2 - q2^2" : "w1^2/2 + w1*w3 - q1^2 - q2^2 - q3^2";
    const auto singular = make_formula_system<TypeParam, any_size>({"singular", text, parse_formula(text), q, w, {}, {}, nullptr});
    auto dense = singular;
    dense.derivatives = nullptr;
    EXPECT_THROW(euler_lagrange_tape(singular), SingularLagrangianError) << n;
    EXPECT_THROW(euler_lagrange_tape(dense), SingularLagrangianError) << n;
  }
}

}  // namespace
}  // namespace vivv
