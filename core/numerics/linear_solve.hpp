// Linear solves that say when the matrix is singular, dense or sparse (Eigen's LU factorizations).
#pragma once

#include <Eigen/LU>
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
// At most this many unknowns, a sparse matrix is factored dense (FullPivLU, as solve_linear's dense
// form): Eigen's SparseLU sets up work arrays for every factorization, which for MPFR are numbers
// allocated and freed each time — 86 % of a two-coordinate midpoint DEL step at 60 digits, which
// took 3.9 times the fixed-size step's time. Measured (bench/run_time_size_benchmark.cpp, an LU of
// a tridiagonal matrix and a solve, one run): in MPFR at 60 digits dense/sparse 0.04 at 2
// unknowns, 0.37 at 8, 1.38 at 16; in double 0.10, 0.25, 0.36 and 1.0 at 32. 8 keeps both below
// sparse; above it the sparse LU's cost follows the matrix's nonzeros.
inline constexpr int dense_factorization_limit = 8;

// An LU kept for several right-hand sides (symplecticity's probes solve with one matrix many
// times); factor() is false for a singular matrix, by the pivot test of solve_linear. Sparse above
// `dense_limit` unknowns, dense at or below it.
template <class T>
class SparseFactorization {
 public:
  bool factor(const Eigen::SparseMatrix<T>& sparse, const T& threshold,
              int dense_limit = dense_factorization_limit) {
    using std::abs;
    dense_ = sparse.rows() <= dense_limit;
    if (dense_) {
      dense_lu_.compute(Matrix<T, any_size, any_size>(sparse));
      dense_lu_.setThreshold(threshold);
      return dense_lu_.isInvertible();
    }
    Eigen::SparseMatrix<T> matrix = sparse;
    matrix.makeCompressed();
    lu_.analyzePattern(matrix);
    lu_.factorize(matrix);
    if (lu_.info() != Eigen::Success) return false;
    // U's diagonal sits in the supernodes of L's storage (as in SparseLU::absDeterminant).
    const auto& supernodes = lu_.matrixL().m_mapL;
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
    return largest > 0 && smallest > threshold * largest;
  }
  // After a factor() that returned true.
  Vector<T, any_size> solve(const Vector<T, any_size>& right) const {
    return dense_ ? Vector<T, any_size>(dense_lu_.solve(right)) : Vector<T, any_size>(lu_.solve(right));
  }
  bool solved() const { return dense_ || lu_.info() == Eigen::Success; }

 private:
  bool dense_ = false;
  Eigen::FullPivLU<Matrix<T, any_size, any_size>> dense_lu_;
  Eigen::SparseLU<Eigen::SparseMatrix<T>, Eigen::COLAMDOrdering<int>> lu_;
};

template <class T, int m>
bool solve_linear(const Eigen::SparseMatrix<T>& sparse, const Vector<T, m>& right, Vector<T, m>& solution,
                  const T& threshold) {
  SparseFactorization<T> lu;
  if (!lu.factor(sparse, threshold)) return false;
  solution = lu.solve(right);
  return lu.solved();
}

}  // namespace vivv
