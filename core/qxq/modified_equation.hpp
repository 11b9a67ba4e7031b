// The modified Lagrangian that a mismatched DEL with twin terms solves (docs/theory.md (twin terms)).
//
// With twin terms a·h·(q_e − q_b) on L_d and ã·h·(q_e − q_b) on L~_d, the
// mismatched DEL p_begin[L_d](q_k, q_{k+1}) = p_end[L~_d](q_{k−1}, q_k) is a
// consistent discretization not of L but of
//   L_mod(q, w) = L(q, w) − c·q,   c = a − ã,
// whose Euler–Lagrange force is shifted by −c (for the paper's example,
// V'(q) ↦ V'(q) + (a − ã)). The order-1 scheme converges to its solution.
#pragma once

#include <vector>

#include "core/lagrangian/lagrangian.hpp"

namespace vivv {

template <LagrangianSystem System>
struct ForceShifted {
  using Scalar = typename System::Scalar;
  static constexpr int dimension = System::dimension;
  System base;
  std::vector<Scalar> c;

  int size() const { return dimension_of(base); }

  // L_mod(q, w) = L(q, w) − c·q.
  template <class P>
  auto lagrangian(const P& q, const P& w) const {
    using S = typename P::value_type;
    S value = base.lagrangian(q, w);
    for (std::size_t i = 0; i < q.size(); ++i) value -= c[i] * q[i];
    return value;
  }
};

}  // namespace vivv
