// The user's own system and discrete Lagrangian, each written once for any scalar S: vivv
// records them on a tape in the case's precision (register_system,
// register_discrete_lagrangian).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

// The quartic oscillator L = ½ w² − k q⁴ / 4.
struct QuarticOscillator {
  static constexpr int dimension = 1;
  static std::vector<std::pair<std::string, std::string>> parameters() { return {{"k", "1"}}; }

  template <class S, class Parameter>
  S lagrangian(const std::array<S, 1>& q, const std::array<S, 1>& w, const Parameter& parameter) const {
    return w[0] * w[0] / 2 - parameter("k") * q[0] * q[0] * q[0] * q[0] / 4;
  }
};

// Two-point Gauss–Legendre quadrature of L along the straight line from qb to qe:
//   L_d = h/2 · [L(x₋, v) + L(x₊, v)],  x± = qb + (1/2 ± √3/6)(qe − qb),  v = (qe − qb)/h,
// of order 2 (the straight line limits it; the quadrature alone is of order 4).
struct GaussTwoLine {
  template <class S, std::size_t n, class Lagrangian>
  S discrete_lagrangian(const std::array<S, n>& qb, const std::array<S, n>& qe, const S& h,
                        const Lagrangian& lagrangian) const {
    using std::sqrt;
    const S offset = sqrt(S(3)) / 6;
    std::array<S, n> minus, plus, v;
    for (std::size_t i = 0; i < n; ++i) {
      const S step = qe[i] - qb[i];
      minus[i] = qb[i] + (S(1) / 2 - offset) * step;
      plus[i] = qb[i] + (S(1) / 2 + offset) * step;
      v[i] = step / h;
    }
    return h / 2 * (lagrangian(minus, v) + lagrangian(plus, v));
  }
};
