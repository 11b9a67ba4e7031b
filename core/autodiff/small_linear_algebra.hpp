// Dense n×n linear algebra on std::array for any scalar S — T itself or
// jets over T — where Eigen's traits do not reach (automatic differentiation
// through a linear solve, as the TQ Legendre transforms need).
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>

#include "core/autodiff/jet.hpp"

namespace vivv {

template <class S, int rows, int cols>
using SmallMatrix = std::array<std::array<S, cols>, rows>;

// |x| of the value part, for pivoting: x itself for a scalar, x.value for a jet.
template <class S>
auto magnitude(const S& x) {
  if constexpr (is_jet<S>::value) {
    return magnitude(x.value);
  } else {
    using std::abs;
    return abs(x);
  }
}

// x solving A x = b by Gaussian elimination with partial pivoting.
// Throws std::domain_error when A is singular at working precision.
template <class S, int n>
std::array<S, n> solve(SmallMatrix<S, n, n> a, std::array<S, n> b) {
  for (int column = 0; column < n; ++column) {
    int pivot = column;
    for (int row = column + 1; row < n; ++row)
      if (magnitude(a[row][column]) > magnitude(a[pivot][column])) pivot = row;
    if (!(magnitude(a[pivot][column]) > 0)) throw std::domain_error("singular matrix in a linear solve");
    std::swap(a[pivot], a[column]);
    std::swap(b[pivot], b[column]);
    for (int row = column + 1; row < n; ++row) {
      S factor = a[row][column] / a[column][column];
      for (int k = column; k < n; ++k) a[row][k] -= factor * a[column][k];
      b[row] -= factor * b[column];
    }
  }
  std::array<S, n> x;
  for (int row = n - 1; row >= 0; --row) {
    S sum = b[row];
    for (int k = row + 1; k < n; ++k) sum -= a[row][k] * x[k];
    x[row] = sum / a[row][row];
  }
  return x;
}

// Aᵀ.
template <class S, int rows, int cols>
SmallMatrix<S, cols, rows> transpose(const SmallMatrix<S, rows, cols>& a) {
  SmallMatrix<S, cols, rows> t;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) t[j][i] = a[i][j];
  return t;
}

// A B.
template <class S, int rows, int inner, int cols>
SmallMatrix<S, rows, cols> multiply(const SmallMatrix<S, rows, inner>& a,
                                    const SmallMatrix<S, inner, cols>& b) {
  SmallMatrix<S, rows, cols> c;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      c[i][j] = S(0);
      for (int k = 0; k < inner; ++k) c[i][j] += a[i][k] * b[k][j];
    }
  return c;
}

// A⁻¹ B, column by column.
template <class S, int n, int cols>
SmallMatrix<S, n, cols> solve_columns(const SmallMatrix<S, n, n>& a, const SmallMatrix<S, n, cols>& b) {
  SmallMatrix<S, n, cols> x;
  for (int j = 0; j < cols; ++j) {
    std::array<S, n> column;
    for (int i = 0; i < n; ++i) column[i] = b[i][j];
    auto solved = solve<S, n>(a, column);
    for (int i = 0; i < n; ++i) x[i][j] = solved[i];
  }
  return x;
}

}  // namespace vivv
