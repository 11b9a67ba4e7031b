// A chain of n coordinates written as a formula, for the tests of systems sized at run time:
// L = Σ w_i²/2 − Σ (q_{i+1} − q_i)²/2 − (q_1² + q_n²)/2 − Σ q_i⁴/4 (fixed ends, and a quartic
// on-site term so that its Hessian depends on q), with a state exact in every scalar.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/lagrangian/state.hpp"

namespace vivv::testing {

inline FormulaSystemDefinition chain(int n) {
  std::string kinetic, springs = "q1^2 + q" + std::to_string(n) + "^2", quartic;
  std::vector<std::string> q, w;
  for (int i = 1; i <= n; ++i) {
    const std::string qi = "q" + std::to_string(i), wi = "w" + std::to_string(i);
    q.push_back(qi), w.push_back(wi);
    kinetic += (i > 1 ? " + " : "") + wi + "^2";
    quartic += (i > 1 ? " + " : "") + qi + "^4";
    if (i < n) springs += " + (q" + std::to_string(i + 1) + " - " + qi + ")^2";
  }
  const std::string text = "(" + kinetic + ")/2 - (" + springs + ")/2 - (" + quartic + ")/4";
  return {"chain", text, parse_formula(text), q, w, {}, {}, nullptr};
}

// q_i = (i mod 5 − 2)/10, w_i = (i mod 3 − 1)/4.
template <class T, int N>
State<T, N> chain_state(int n) {
  State<T, N> x{zero_vector<T, N>(n), zero_vector<T, N>(n)};
  for (int i = 0; i < n; ++i) x.q[i] = T(i % 5 - 2) / 10, x.w[i] = T(i % 3 - 1) / 4;
  return x;
}

// max |a_ij − b_ij| (NaN when an entry is NaN), the shapes checked.
template <class T, int R, int C, int R2, int C2>
T distance(const Matrix<T, R, C>& a, const Matrix<T, R2, C2>& b) {
  EXPECT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.cols(), b.cols());
  using std::abs;
  T largest = 0;
  for (int i = 0; i < a.rows(); ++i)
    for (int j = 0; j < a.cols(); ++j) largest = nan_max(largest, T(abs(T(a(i, j) - b(i, j)))));
  return largest;
}

}  // namespace vivv::testing
