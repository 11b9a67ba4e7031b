// Exact flows F_t in closed form, accurate to working precision.
//
// Harmonic oscillator L = ½ w² − ½ ω² q²:
//   q(t) = q0 cos ωt + (w0/ω) sin ωt,   w(t) = −ω q0 sin ωt + w0 cos ωt.
// Pendulum L = ½ w² − k (1 − cos q), q'' = −k sin q, through Jacobi elliptic
// functions. With s = sin(q0/2), c = cos(q0/2), v = w0 / (2√k), the energy
// E = ½ w² + 2k sin²(q/2) gives the modulus κ² = E / (2k) = s² + v²:
//   libration (κ < 1):  sin(q/2) = κ sn(u, κ), cos(q/2) = dn(u, κ), w = 2κ√k cn(u, κ),
//                       u = F(atan2(s, v), κ) + √k t;
//   separatrix (κ = 1): q = 2 atan(sinh σ), w = 2√k / cosh σ, σ = asinh(s/c) + √k t;
//   rotation (κ > 1):   q/2 = am(u, 1/κ), w = 2κ√k dn(u, 1/κ), u = F(q0/2, 1/κ) + κ√k t;
//   rest at the bottom (κ = 0): q = q0.
// q0 is first reduced to [−π, π] and the multiple of 2π added back; w0 < 0 on
// the separatrix and in rotation uses the symmetry (q, w) ↦ (−q, −w); k = 0 is
// free motion and k < 0 is the inverted pendulum, the pendulum in q − π.
//
// Boost's dn(u, κ) = cos φ₀ / cos(φ₁ − φ₀) loses most digits near u = K (both
// factors vanish), so dn is always taken from dn² = κ'² + κ² cn², whose terms
// are both positive, with κ'² = 1 − κ² computed from the state as (c − v)(c + v).
// Arguments are reduced modulo the period before calling Boost, whose small-κ
// expansion and Landen recursion lose accuracy for large u.
#pragma once

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cases/systems.hpp"
#include "core/scalar.hpp"
#include "core/state.hpp"

namespace vivv {

namespace closed_form_detail {

// Whether x is neither infinite nor NaN.
template <class T>
bool finite(const T& x) {
  using boost::multiprecision::isfinite;
  using std::isfinite;
  return static_cast<bool>(isfinite(x));
}

// Throws std::domain_error unless q0, w0, t and the parameters are all finite.
template <class T>
void require_finite(const char* what, const State<T, 1>& start, const T& t,
                    std::initializer_list<T> parameters) {
  bool ok = finite(start.q[0]) && finite(start.w[0]) && finite(t);
  for (const T& p : parameters) ok = ok && finite(p);
  if (!ok) {
    throw std::domain_error(
        std::string(what) + ": non-finite input (q0 = " + to_decimal<T>(start.q[0]) +
        ", w0 = " + to_decimal<T>(start.w[0]) + ", t = " + to_decimal<T>(t) + ")");
  }
}

// (sn, cn, dn)(u, κ) for 0 ≤ κ < 1 with dn = sqrt(κ'² + κ² cn²), κ'² = 1 − κ² given exactly.
template <class T>
struct JacobiTriple {
  T sn, cn, dn;
};
template <class T>
JacobiTriple<T> jacobi_sn_cn_dn(const T& u, const T& kappa, const T& kappa_prime_squared) {
  using std::sqrt;
  JacobiTriple<T> r;
  T boost_dn;
  r.sn = boost::math::jacobi_elliptic(kappa, u, &r.cn, &boost_dn);
  r.dn = sqrt(kappa_prime_squared + kappa * kappa * r.cn * r.cn);
  return r;
}

// x − period · round(x / period): x reduced to [−period/2, period/2], and the multiple.
template <class T>
std::pair<T, T> reduce(const T& x, const T& period) {
  using std::round;
  T multiple = round(x / period);
  return {x - multiple * period, multiple};
}

}  // namespace closed_form_detail

// F_t(q0, w0) = (q0 cos ωt + (w0/ω) sin ωt, −ω q0 sin ωt + w0 cos ωt); ω = 0 is q0 + w0 t.
template <class T>
State<T, 1> harmonic_oscillator_flow(const HarmonicOscillator<T>& system, const State<T, 1>& start,
                                     const T& t) {
  using std::cos;
  using std::sin;
  closed_form_detail::require_finite("harmonic_oscillator_flow", start, t, {system.omega});
  const T& omega = system.omega;
  const T& q0 = start.q[0];
  const T& w0 = start.w[0];
  State<T, 1> end;
  if (omega == 0) {
    end.q[0] = q0 + w0 * t;
    end.w[0] = w0;
    return end;
  }
  T cosine = cos(omega * t), sine = sin(omega * t);
  end.q[0] = q0 * cosine + w0 / omega * sine;
  end.w[0] = -omega * q0 * sine + w0 * cosine;
  return end;
}

// Which closed-form branch F_t(q0, w0) of the pendulum takes, from κ² = sin²(q0/2) + w0²/(4k).
enum class PendulumMotion { rest, libration, separatrix, rotation, free };

namespace closed_form_detail {

// Pendulum flow for k > 0 and q0 ∈ [−π, π]; see the formulas at the top of the file.
template <class T>
State<T, 1> pendulum_flow_reduced(const T& k, const T& q0, const T& w0, const T& t,
                                  PendulumMotion* motion) {
  using std::abs;
  using std::asinh;
  using std::atan;
  using std::atan2;
  using std::cos;
  using std::cosh;
  using std::max;
  using std::sin;
  using std::sinh;
  using std::sqrt;
  const T pi = boost::math::constants::pi<T>();
  const T root_k = sqrt(k);
  const T s = sin(q0 / 2), c = cos(q0 / 2), v = w0 / (2 * root_k);
  // κ = 1 is tested on κ itself, so that 1/κ in the rotation never rounds to 1.
  const T kappa = sqrt(s * s + v * v);
  const T abs_v = abs(v);
  State<T, 1> end;
  if (kappa == 0) {
    if (motion) *motion = PendulumMotion::rest;
    end.q[0] = q0;
    end.w[0] = w0;
    return end;
  }
  if (kappa < 1) {
    // Libration: sin(q/2) = κ sn(u), cos(q/2) = dn(u), w = 2κ√k cn(u).
    if (motion) *motion = PendulumMotion::libration;
    const T kappa_prime_squared = max(T((c - abs_v) * (c + abs_v)), T(0));
    const T quarter_period = boost::math::ellint_1(kappa);
    const T u0 = boost::math::ellint_1(kappa, T(atan2(s, v)));
    const T u = reduce(T(u0 + root_k * t), T(4 * quarter_period)).first;
    auto [sn, cn, dn] = jacobi_sn_cn_dn(u, kappa, kappa_prime_squared);
    end.q[0] = 2 * atan2(kappa * sn, dn);
    end.w[0] = 2 * kappa * root_k * cn;
    return end;
  }
  // Separatrix and rotation: w0 ≥ 0 by the symmetry (q, w) ↦ (−q, −w).
  if (w0 < 0) {
    State<T, 1> mirrored = pendulum_flow_reduced(k, T(-q0), T(-w0), t, motion);
    mirrored.q[0] = -mirrored.q[0];
    mirrored.w[0] = -mirrored.w[0];
    return mirrored;
  }
  const T modulus = 1 / kappa;
  if (kappa == 1 || modulus == 1) {
    // Separatrix: q = 2 atan(sinh σ), w = 2√k / cosh σ, σ = asinh(tan(q0/2)) + √k t.
    if (motion) *motion = PendulumMotion::separatrix;
    if (c == 0) {  // at rest on the top: the unstable equilibrium
      end.q[0] = q0;
      end.w[0] = 0;
      return end;
    }
    const T sigma = asinh(s / c) + root_k * t;
    end.q[0] = 2 * atan(sinh(sigma));
    end.w[0] = 2 * root_k / cosh(sigma);
    return end;
  }
  // Rotation: q/2 = am(u, 1/κ), w = 2κ√k dn(u, 1/κ), u = F(q0/2, 1/κ) + κ√k t.
  if (motion) *motion = PendulumMotion::rotation;
  const T modulus_prime_squared = max(T((v - c) * (v + c)), T(0)) / (kappa * kappa);
  const T half_period = 2 * boost::math::ellint_1(modulus);  // am(u + 2K) = am(u) + π
  const T u0 = boost::math::ellint_1(modulus, T(q0 / 2));
  auto [u, turns] = reduce(T(u0 + kappa * root_k * t), half_period);
  auto [sn, cn, dn] = jacobi_sn_cn_dn(u, modulus, modulus_prime_squared);
  // For |u| ≤ K, am(u) ∈ [−π/2, π/2] and cn ≥ 0.
  end.q[0] = 2 * atan2(sn, cn) + 2 * pi * turns;
  end.w[0] = 2 * kappa * root_k * dn;
  return end;
}

}  // namespace closed_form_detail

// F_t(q0, w0) of q'' = −k sin q by Jacobi elliptic functions (formulas at the top of the file).
// `motion`, when given, receives the branch taken.
template <class T>
State<T, 1> pendulum_flow(const Pendulum<T>& system, const State<T, 1>& start, const T& t,
                          PendulumMotion* motion = nullptr) {
  using std::abs;
  closed_form_detail::require_finite("pendulum_flow", start, t, {system.k});
  const T pi = boost::math::constants::pi<T>();
  const T& k = system.k;
  const T& w0 = start.w[0];
  if (k == 0) {
    if (motion) *motion = PendulumMotion::free;
    State<T, 1> end;
    end.q[0] = start.q[0] + w0 * t;
    end.w[0] = w0;
    return end;
  }
  // k < 0: p = q − π satisfies p'' = −|k| sin p.
  const T shift = k > 0 ? T(0) : pi;
  const T k_positive = abs(k);
  auto [q0, turns] = closed_form_detail::reduce(T(start.q[0] - shift), T(2 * pi));
  State<T, 1> end = closed_form_detail::pendulum_flow_reduced(k_positive, q0, w0, t, motion);
  end.q[0] += 2 * pi * turns + shift;
  return end;
}

}  // namespace vivv
