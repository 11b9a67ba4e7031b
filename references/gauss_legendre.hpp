// Gauss–Legendre quadrature on [0, 1] at the working precision of T.
//
// The nodes are the roots x_i of the Legendre polynomial P_m, found by Newton
// on the three-term recurrence from the classical guesses
// cos(π (i − 1/4) / (m + 1/2)), all in T (π from boost::math::constants, never
// a double), then mapped from [−1, 1] to [0, 1]. The exact discrete Lagrangian
// L_d^E (docs/theory.md (Q × Q)) and the quadrature discrete Lagrangians (§1.3) use them.
#pragma once

#include <boost/math/constants/constants.hpp>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/scalar.hpp"

namespace vivv {

// The m-point rule ∫₀¹ f ≈ Σ_i weights[i] f(nodes[i]), exact for polynomials of degree ≤ 2m − 1.
template <class T>
struct GaussLegendreRule {
  std::vector<T> nodes;    // increasing, in (0, 1), symmetric: nodes[i] + nodes[m − 1 − i] = 1
  std::vector<T> weights;  // positive, summing to 1
};

// (P_m, P_m')(x): (j+1) P_{j+1} = (2j+1) x P_j − j P_{j−1}, P_m' = m (x P_m − P_{m−1})/(x² − 1).
template <class T>
std::pair<T, T> legendre_and_derivative(int m, const T& x) {
  T previous = 1;  // P_{j−1}
  T current = x;   // P_j
  for (int j = 1; j < m; ++j) {
    T next = ((2 * j + 1) * x * current - j * previous) / (j + 1);
    previous = current;
    current = next;
  }
  T derivative = m * (x * current - previous) / (x * x - 1);
  return {current, derivative};
}

// Nodes (1 ∓ x_i)/2, weights 1 / ((1 − x_i²) P_m'(x_i)²), x_i ≥ 0 the roots of P_m by Newton.
template <class T>
GaussLegendreRule<T> gauss_legendre(int m) {
  using std::abs;
  using std::cos;
  if (m < 1)
    throw std::invalid_argument("gauss_legendre: need m >= 1 nodes, got " + std::to_string(m));
  const T pi = boost::math::constants::pi<T>();
  const T newton_tolerance = 8 * epsilon<T>();
  constexpr int max_iterations = 100;
  GaussLegendreRule<T> rule;
  rule.nodes.assign(m, T(0));
  rule.weights.assign(m, T(0));
  for (int i = 1; i <= (m + 1) / 2; ++i) {
    // The i-th largest root of P_m; for odd m the middle one is exactly 0.
    T x = cos(pi * (T(i) - T(1) / 4) / (T(m) + T(1) / 2));
    if (2 * i - 1 == m) x = 0;
    bool converged = false;
    for (int iteration = 0; iteration < max_iterations && !converged; ++iteration) {
      auto [p, dp] = legendre_and_derivative(m, x);
      T step = p / dp;
      x -= step;
      converged = abs(step) <= newton_tolerance;
    }
    if (!converged) {
      throw std::runtime_error("gauss_legendre: Newton did not converge for root " +
                               std::to_string(i) + " of P_" + std::to_string(m) + " in " +
                               scalar_name<T>());
    }
    T dp = legendre_and_derivative(m, x).second;
    T weight = 1 / ((1 - x * x) * dp * dp);
    rule.nodes[i - 1] = (1 - x) / 2;
    rule.nodes[m - i] = (1 + x) / 2;
    rule.weights[i - 1] = weight;
    rule.weights[m - i] = weight;
  }
  return rule;
}

// ∫_a^b f ≈ (b − a) Σ_i weights[i] f(a + (b − a) nodes[i]); f may return T or an Eigen vector.
template <class T, class F>
auto integrate(const GaussLegendreRule<T>& rule, T a, T b, F f) {
  using Value = std::decay_t<decltype(f(a))>;
  if (rule.nodes.empty()) throw std::invalid_argument("integrate: empty quadrature rule");
  const T length = b - a;
  Value sum = f(T(a + length * rule.nodes[0])) * rule.weights[0];
  for (std::size_t i = 1; i < rule.nodes.size(); ++i) {
    sum += f(T(a + length * rule.nodes[i])) * rule.weights[i];
  }
  return Value(sum * length);
}

}  // namespace vivv
