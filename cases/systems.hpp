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

#include "core/lagrangian/lagrangian.hpp"

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
    count_lagrangian_evaluation();
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
    count_lagrangian_evaluation();
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
    count_lagrangian_evaluation();
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
    count_lagrangian_evaluation();
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
    count_lagrangian_evaluation();
    return (w[0] * w[0] + w[1] * w[1]) / 2 + B * (q[0] * w[1] - q[1] * w[0]) / 2 -
           k * (q[0] * q[0] + q[1] * q[1]) / 2;
  }
  // The generator of rotations, ξ(q) = (−q2, q1).
  template <class S>
  Point<S, 2> symmetry_generator(const Point<S, 2>& q) const {
    return {-q[1], q[0]};
  }
};

// L = ½ |w|² + μ / |q|: the Kepler problem in the plane. Rotations about the
// origin are a symmetry, with momentum map the angular momentum q1 p2 − q2 p1.
template <class T>
struct Kepler {
  using Scalar = T;
  static constexpr int dimension = 2;
  static constexpr const char* name = "kepler";
  static std::vector<ParameterSpec> parameters() { return {{"mu", "1"}}; }
  T mu = 1;
  void set(const std::vector<T>& p) { mu = p[0]; }

  template <class S>
  S lagrangian(const Point<S, 2>& q, const Point<S, 2>& w) const {
    count_lagrangian_evaluation();
    using std::sqrt;
    return (w[0] * w[0] + w[1] * w[1]) / 2 + mu / sqrt(q[0] * q[0] + q[1] * q[1]);
  }
  // The generator of rotations, ξ(q) = (−q2, q1).
  template <class S>
  Point<S, 2> symmetry_generator(const Point<S, 2>& q) const {
    return {-q[1], q[0]};
  }
};

// L = ½ |w|² − ½ |q|² − λ (x² y − y³/3): Hénon–Heiles, non-integrable, chaotic
// above energy about 1/8 (for λ = 1).
template <class T>
struct HenonHeiles {
  using Scalar = T;
  static constexpr int dimension = 2;
  static constexpr const char* name = "henon_heiles";
  static std::vector<ParameterSpec> parameters() { return {{"lambda", "1"}}; }
  T lambda = 1;
  void set(const std::vector<T>& p) { lambda = p[0]; }

  template <class S>
  S lagrangian(const Point<S, 2>& q, const Point<S, 2>& w) const {
    count_lagrangian_evaluation();
    const S& x = q[0];
    const S& y = q[1];
    return (w[0] * w[0] + w[1] * w[1]) / 2 - (x * x + y * y) / 2 - lambda * (x * x * y - y * y * y / 3);
  }
};

// The planar double pendulum, angles q1, q2 from the downward vertical:
// L = ½ (m1 + m2) l1² w1² + ½ m2 l2² w2² + m2 l1 l2 w1 w2 cos(q1 − q2)
//     + (m1 + m2) g l1 cos q1 + m2 g l2 cos q2.
// Its mass matrix depends on q: the DEL and the Legendre map are nonlinear in w.
template <class T>
struct DoublePendulum {
  using Scalar = T;
  static constexpr int dimension = 2;
  static constexpr const char* name = "double_pendulum";
  static std::vector<ParameterSpec> parameters() {
    return {{"m1", "1"}, {"m2", "1"}, {"l1", "1"}, {"l2", "1"}, {"g", "1"}};
  }
  T m1 = 1, m2 = 1, l1 = 1, l2 = 1, g = 1;
  void set(const std::vector<T>& p) { m1 = p[0], m2 = p[1], l1 = p[2], l2 = p[3], g = p[4]; }

  template <class S>
  S lagrangian(const Point<S, 2>& q, const Point<S, 2>& w) const {
    count_lagrangian_evaluation();
    using std::cos;
    const T m = m1 + m2;
    return m * l1 * l1 * w[0] * w[0] / 2 + m2 * l2 * l2 * w[1] * w[1] / 2 +
           m2 * l1 * l2 * w[0] * w[1] * cos(q[0] - q[1]) + m * g * l1 * cos(q[0]) + m2 * g * l2 * cos(q[1]);
  }
};

}  // namespace vivv
