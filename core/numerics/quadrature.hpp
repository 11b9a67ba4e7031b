// Gauss–Legendre and Gauss–Lobatto quadrature on [0, 1] at the working precision of T.
//
// The nodes are the roots x_i of the Legendre polynomial P_m, found by Newton
// on the three-term recurrence from the classical guesses
// cos(π (i − 1/4) / (m + 1/2)), all in T (π from boost::math::constants, never
// a double), then mapped from [−1, 1] to [0, 1]. The exact discrete Lagrangian
// L_d^E (docs/theory.md (Q × Q)) and the quadrature discrete Lagrangians (§1.3) use them.
// Gauss–Lobatto adds the end points to the roots of P'_{m−1} (the Galerkin
// discrete Lagrangians of core/qxq/galerkin.hpp use both).
#pragma once

#include <boost/math/constants/constants.hpp>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/numerics/scalar.hpp"

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

// The m-point Gauss–Lobatto rule (m >= 2) on [0, 1], exact for polynomials of degree ≤ 2m − 3:
// nodes 0, 1 and the roots x_i of P'_{m−1} mapped from [−1, 1], weights 1 / (m (m − 1) P_{m−1}(x_i)²)
// (half of the classical 2 / (m (m − 1) P_{m−1}(x_i)²) on [−1, 1]). Newton on P'_{m−1} uses
// P'' = (2x P' − k (k + 1) P) / (1 − x²), k = m − 1, from the guesses cos(π i / (m − 1)).
template <class T>
GaussLegendreRule<T> gauss_lobatto(int m) {
  using std::abs;
  using std::cos;
  if (m < 2) throw std::invalid_argument("gauss_lobatto: need m >= 2 nodes, got " + std::to_string(m));
  const T pi = boost::math::constants::pi<T>();
  const int k = m - 1;
  GaussLegendreRule<T> rule;
  rule.nodes.assign(m, T(0));
  rule.weights.assign(m, T(0));
  auto weight_at = [&](const T& x) {
    const T p = legendre_and_derivative(k, x).first;
    return T(1) / (T(m) * T(k) * p * p);
  };
  rule.nodes[0] = 0, rule.nodes[m - 1] = 1;
  rule.weights[0] = rule.weights[m - 1] = T(1) / (T(m) * T(k));  // P_k(±1)² = 1
  for (int i = 1; i <= (m - 1) / 2; ++i) {
    // The i-th largest interior root; for odd m the middle one is exactly 0.
    T x = cos(pi * T(i) / T(k));
    if (2 * i == k) x = 0;
    bool converged = false;
    for (int iteration = 0; iteration < 100 && !converged; ++iteration) {
      auto [p, dp] = legendre_and_derivative(k, x);
      const T d2p = (2 * x * dp - T(k) * T(k + 1) * p) / (1 - x * x);
      const T step = dp / d2p;
      x -= step;
      converged = abs(step) <= 8 * epsilon<T>();
    }
    if (!converged)
      throw std::runtime_error("gauss_lobatto: Newton did not converge for root " + std::to_string(i) + " of P'_" +
                               std::to_string(k) + " in " + scalar_name<T>());
    rule.nodes[i] = (1 - x) / 2;
    rule.nodes[m - 1 - i] = (1 + x) / 2;
    rule.weights[i] = rule.weights[m - 1 - i] = weight_at(x);
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
