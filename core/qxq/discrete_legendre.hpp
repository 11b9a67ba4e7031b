// What a discrete Lagrangian gives at a pair (q_b, q_e): its value, the two
// discrete Legendre transforms and their derivatives (docs/theory.md (Q × Q)).
#pragma once

#include "core/numerics/scalar.hpp"

namespace vivv {

// L_d and its derivatives at (q_b, q_e): p_begin = −∂L_d/∂q_b, p_end = +∂L_d/∂q_e,
// and the second-derivative blocks ∂p_begin/∂q_e = −∂²L_d/∂q_b∂q_e,
// ∂p_end/∂q_b = ∂²L_d/∂q_e∂q_b, ∂p_end/∂q_e = ∂²L_d/∂q_e².
template <class T, int n>
struct DiscreteLegendre {
  DiscreteLegendre() : DiscreteLegendre(n == any_size ? 0 : n) {}
  explicit DiscreteLegendre(int size)
      : p_begin(zero_vector<T, n>(size)), p_end(zero_vector<T, n>(size)),
        dp_begin_dq_b(zero_matrix<T, n, n>(size, size)), dp_begin_dq_e(zero_matrix<T, n, n>(size, size)),
        dp_end_dq_b(zero_matrix<T, n, n>(size, size)), dp_end_dq_e(zero_matrix<T, n, n>(size, size)) {}
  T value;
  Vector<T, n> p_begin, p_end;
  Matrix<T, n, n> dp_begin_dq_b, dp_begin_dq_e, dp_end_dq_b, dp_end_dq_e;
};

}  // namespace vivv
