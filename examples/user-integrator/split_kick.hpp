// The user's integrator: a symmetric kick-drift-kick-drift-kick splitting of q'' = a(q),
//   w += b·h·a(q);  q += h/2·w;  w += (1 − 2b)·h·a(q);  q += h/2·w;  w += b·h·a(q),
// symplectic and of order 2 for any b whose weights b + (1 − 2b) + b sum to 1. Written once for
// any scalar S, as vivv::register_map asks: vivv runs it in the case's precision and, for its
// Jacobian, in automatic-differentiation jets.
#pragma once

#include <array>
#include <cstddef>

template <class Weights>
struct SplitKick {
  template <class S, std::size_t n, class Acceleration>
  void step(std::array<S, n>& q, std::array<S, n>& w, const S& h, const Acceleration& acceleration) const {
    const S outer = Weights::template outer<S>(), inner = Weights::template inner<S>();
    kick(w, outer * h, acceleration(q));
    drift(q, h / 2, w);
    kick(w, inner * h, acceleration(q));
    drift(q, h / 2, w);
    kick(w, outer * h, acceleration(q));
  }

 private:
  template <class S, std::size_t n>
  static void kick(std::array<S, n>& w, const S& dt, const std::array<S, n>& a) {
    for (std::size_t i = 0; i < n; ++i) w[i] += dt * a[i];
  }
  template <class S, std::size_t n>
  static void drift(std::array<S, n>& q, const S& dt, const std::array<S, n>& w) {
    for (std::size_t i = 0; i < n; ++i) q[i] += dt * w[i];
  }
};

// b = 1/10, 1 − 2b = 4/5, each computed in the scalar.
struct TenthWeights {
  template <class S> static S outer() { return S(1) / 10; }
  template <class S> static S inner() { return S(4) / 5; }
};

// The same weights copied from a table, the outer one as the double literal 0.1: the weights
// then sum to 1 + 1.1e-17, in every precision.
struct TenthLiteralWeights {
  template <class S> static S outer() { return S(0.1); }
  template <class S> static S inner() { return S(4) / 5; }
};
