// Dense n×n linear algebra on std::array for any scalar S — T itself or
// jets over T — where Eigen's traits do not reach (automatic differentiation
// through a linear solve, as the TQ Legendre transforms need).
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/autodiff/jet.hpp"

namespace vivv {

// n numbers: std::array for a fixed n, std::vector for any_size.
template <class S, int n>
using SmallVector = Coordinates<S, n>;

template <class S, int rows, int cols>
using SmallMatrix = SmallVector<SmallVector<S, cols>, rows>;

// A SmallVector of `size` entries and a SmallMatrix of rows × cols (fixed sizes: their own).
template <class S, int n>
SmallVector<S, n> make_small_vector(int size) {
  if constexpr (n == any_size)
    return SmallVector<S, n>(static_cast<std::size_t>(size));
  else
    return (void)size, SmallVector<S, n>{};
}
template <class S, int rows, int cols>
SmallMatrix<S, rows, cols> make_small_matrix(int r, int c) {
  if constexpr (rows == any_size) {
    return SmallMatrix<S, rows, cols>(static_cast<std::size_t>(r), make_small_vector<S, cols>(c));
  } else {
    SmallMatrix<S, rows, cols> m{};
    for (auto& row : m) row = make_small_vector<S, cols>(c);
    return m;
  }
}

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
template <class S, int N>
SmallVector<S, N> solve(SmallMatrix<S, N, N> a, SmallVector<S, N> b) {
  const int n = static_cast<int>(b.size());
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
  SmallVector<S, N> x = make_small_vector<S, N>(n);
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
  const int r = static_cast<int>(a.size()), c = r ? static_cast<int>(a[0].size()) : 0;
  SmallMatrix<S, cols, rows> t = make_small_matrix<S, cols, rows>(c, r);
  for (int i = 0; i < r; ++i)
    for (int j = 0; j < c; ++j) t[j][i] = a[i][j];
  return t;
}

// A B.
template <class S, int rows, int inner, int cols>
SmallMatrix<S, rows, cols> multiply(const SmallMatrix<S, rows, inner>& a,
                                    const SmallMatrix<S, inner, cols>& b) {
  const int r = static_cast<int>(a.size()), m = static_cast<int>(b.size()),
            c = m ? static_cast<int>(b[0].size()) : 0;
  SmallMatrix<S, rows, cols> product = make_small_matrix<S, rows, cols>(r, c);
  for (int i = 0; i < r; ++i)
    for (int j = 0; j < c; ++j) {
      product[i][j] = S(0);
      for (int k = 0; k < m; ++k) product[i][j] += a[i][k] * b[k][j];
    }
  return product;
}

// A⁻¹ B, column by column.
template <class S, int N, int cols>
SmallMatrix<S, N, cols> solve_columns(const SmallMatrix<S, N, N>& a, const SmallMatrix<S, N, cols>& b) {
  const int n = static_cast<int>(b.size()), c = n ? static_cast<int>(b[0].size()) : 0;
  SmallMatrix<S, N, cols> x = make_small_matrix<S, N, cols>(n, c);
  for (int j = 0; j < c; ++j) {
    SmallVector<S, N> column = make_small_vector<S, N>(n);
    for (int i = 0; i < n; ++i) column[i] = b[i][j];
    auto solved = solve<S, N>(a, column);
    for (int i = 0; i < n; ++i) x[i][j] = solved[i];
  }
  return x;
}

}  // namespace vivv
