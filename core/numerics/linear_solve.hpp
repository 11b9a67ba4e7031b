// Linear solves that say when the matrix is singular, dense or sparse (Eigen's LU factorizations).
#pragma once

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <type_traits>

#include "core/numerics/scalar.hpp"

namespace vivv {

// A⁻¹ r into `solution`; false for a singular A: a pivot at most `threshold` times the largest
// (full pivoting for a dense A; for a sparse A, Eigen's SparseLU with the COLAMD ordering and
// the same bound on the diagonal of its U, which partial pivoting makes a rank test too).
template <class T, int m>
bool solve_linear(const Matrix<T, m, m>& matrix, const Vector<T, m>& right, Vector<T, m>& solution,
                  const T& threshold) {
  Eigen::FullPivLU<Matrix<T, m, m>> lu(matrix);
  lu.setThreshold(threshold);
  if (!lu.isInvertible()) return false;
  solution = lu.solve(right);
  return true;
}
template <class T, int m>
bool solve_linear(const Eigen::SparseMatrix<T>& sparse, const Vector<T, m>& right, Vector<T, m>& solution,
                  const T& threshold) {
  using std::abs;
  Eigen::SparseMatrix<T> matrix = sparse;
  matrix.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<T>, Eigen::COLAMDOrdering<int>> lu;
  lu.analyzePattern(matrix);
  lu.factorize(matrix);
  if (lu.info() != Eigen::Success) return false;
  // U's diagonal sits in the supernodes of L's storage (as in SparseLU::absDeterminant).
  const auto& supernodes = lu.matrixL().m_mapL;
  T largest = 0, smallest = -1;
  for (Eigen::Index j = 0; j < matrix.cols(); ++j) {
    T pivot = 0;
    for (typename std::decay_t<decltype(supernodes)>::InnerIterator it(supernodes, j); it; ++it)
      if (it.index() == j) {
        pivot = abs(it.value());
        break;
      }
    largest = std::max(largest, pivot);
    smallest = smallest < 0 ? pivot : std::min(smallest, pivot);
  }
  if (!(largest > 0) || !(smallest > threshold * largest)) return false;
  solution = lu.solve(right);
  return lu.info() == Eigen::Success;
}

}  // namespace vivv
