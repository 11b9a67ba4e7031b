// A point v = (q, w) of TQ = R^n × R^n: configuration and velocity (docs/theory.md).
#pragma once

#include "core/numerics/scalar.hpp"

namespace vivv {

template <class T, int n>
struct State {
  Vector<T, n> q;
  Vector<T, n> w;
};

// Max norm of the difference of two states, over the components of q and w.
template <class T, int n>
T state_distance(const State<T, n>& a, const State<T, n>& b) {
  using std::max;
  return max(max_norm<T, n>(a.q - b.q), max_norm<T, n>(a.w - b.w));
}

}  // namespace vivv
