// The catalogue of Lagrangian systems (docs/theory.md, foundation issue).
//
// Each system states L(q, w) once, templated on the scalar S it is evaluated
// in (T itself or a jet over T); parameters live in T. `parameters` lists the
// parameter names with their defaults as decimal strings, in the order `set`
// takes them.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/lagrangian.hpp"

namespace vivv {

struct ParameterSpec {
  std::string name;
  std::string default_value;
};

// L = ½ g(q) w² − V(q), g(q) = g0 + g2 q², V(q) = k (1 − cos q) + ½ m q² (paper §2, eq. 2.1).
template <class T>
struct PaperExample {
  using Scalar = T;
  static constexpr int dimension = 1;
  static constexpr const char* name = "paper_example";
  static std::vector<ParameterSpec> parameters() {
    return {{"g0", "1"}, {"g2", "0.5"}, {"k", "1"}, {"m", "0"}};
  }
  T g0 = 1, g2 = T(1) / 2, k = 1, m = 0;
  void set(const std::vector<T>& p) { g0 = p[0], g2 = p[1], k = p[2], m = p[3]; }

  template <class S>
  S g(const S& q) const { return g0 + g2 * q * q; }
  template <class S>
  S V(const S& q) const {
    using std::cos;
    return k * (1 - cos(q)) + m * q * q / 2;
  }
  template <class S>
  S lagrangian(const Point<S, 1>& q, const Point<S, 1>& w) const {
    return g(q[0]) * w[0] * w[0] / 2 - V(q[0]);
  }
};

// L = ½ w² − ½ ω² q².
template <class T>
struct HarmonicOscillator {
  using Scalar = T;
  static constexpr int dimension = 1;
  static constexpr const char* name = "harmonic_oscillator";
  static std::vector<ParameterSpec> parameters() { return {{"omega", "1"}}; }
  T omega = 1;
  void set(const std::vector<T>& p) { omega = p[0]; }

  template <class S>
  S lagrangian(const Point<S, 1>& q, const Point<S, 1>& w) const {
    return w[0] * w[0] / 2 - omega * omega * q[0] * q[0] / 2;
  }
};

// L = ½ w² − k (1 − cos q).
template <class T>
struct Pendulum {
  using Scalar = T;
  static constexpr int dimension = 1;
  static constexpr const char* name = "pendulum";
  static std::vector<ParameterSpec> parameters() { return {{"k", "1"}}; }
  T k = 1;
  void set(const std::vector<T>& p) { k = p[0]; }

  template <class S>
  S lagrangian(const Point<S, 1>& q, const Point<S, 1>& w) const {
    using std::cos;
    return w[0] * w[0] / 2 - k * (1 - cos(q[0]));
  }
};

// L = −m sqrt(1 − w²) − ½ k q² (c = 1): regular for |w| < 1, not quadratic in w.
template <class T>
struct RelativisticParticle {
  using Scalar = T;
  static constexpr int dimension = 1;
  static constexpr const char* name = "relativistic_particle";
  static std::vector<ParameterSpec> parameters() { return {{"mass", "1"}, {"k", "1"}}; }
  T mass = 1, k = 1;
  void set(const std::vector<T>& p) { mass = p[0], k = p[1]; }

  template <class S>
  S lagrangian(const Point<S, 1>& q, const Point<S, 1>& w) const {
    using std::sqrt;
    return -mass * sqrt(1 - w[0] * w[0]) - k * q[0] * q[0] / 2;
  }
};

// L = ½ |w|² + (B/2)(q1 w2 − q2 w1) − ½ k |q|²: a charge in a uniform magnetic
// field B and an isotropic harmonic trap; rotations about the origin are a symmetry.
template <class T>
struct ChargedParticle {
  using Scalar = T;
  static constexpr int dimension = 2;
  static constexpr const char* name = "charged_particle";
  static std::vector<ParameterSpec> parameters() { return {{"B", "1"}, {"k", "1"}}; }
  T B = 1, k = 1;
  void set(const std::vector<T>& p) { B = p[0], k = p[1]; }

  template <class S>
  S lagrangian(const Point<S, 2>& q, const Point<S, 2>& w) const {
    return (w[0] * w[0] + w[1] * w[1]) / 2 + B * (q[0] * w[1] - q[1] * w[0]) / 2 -
           k * (q[0] * q[0] + q[1] * q[1]) / 2;
  }
};

}  // namespace vivv
