// The paper's example discrete Lagrangian (§2.1), shared by the tests that check its printed
// statements: L_h(q+, q−) = h L(q−, (q+ − q−)/h) + a h (q+ − q−), the left rectangle with the
// twin term a·h¹·(q_e − q_b).
#pragma once

#include "core/qxq/discrete_lagrangian.hpp"

namespace vivv::testing {

template <class T>
QxQDiscretization<T> paper_discrete_lagrangian(const T& a) {
  QxQDiscretization<T> d;
  d.rule = QxQRule::left_rectangle;
  d.twin = TwinTerm<T>{{a}, 1};
  return d;
}

}  // namespace vivv::testing
