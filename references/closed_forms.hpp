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
// Kepler L = ½|w|² + μ/|q| on a bound orbit (energy < 0), through Kepler's
// equation in difference form (Battin §4.5; Danby ch. 6). With r0 = |q0|,
// σ0 = q0·w0, 1/a = 2/r0 − |w0|²/μ, n = √(μ/a³), C = 1 − r0/a = e cos E0 and
// S = σ0/√(μa) = e sin E0, the change x = E − E0 of the eccentric anomaly
// after time t solves
//   x − C sin x + S (1 − cos x) = n t
// (Newton, Boost.Math, in the working precision; the left side's derivative is
// r/a ≥ 1 − e > 0), and the Lagrange coefficients give the state:
//   r = a (1 − C cos x + S sin x),
//   q = f q0 + g w0,   f = 1 − (a/r0)(1 − cos x),  g = t − (x − sin x)/n,
//   w = ḟ q0 + ġ w0,   ḟ = −√(μa) sin x / (r r0),   ġ = 1 − (a/r)(1 − cos x).
// t is first reduced modulo the period 2π/n.
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
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cases/systems.hpp"
#include "core/numerics/scalar.hpp"
#include "core/lagrangian/state.hpp"

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

// F_t(q0, w0) of the Kepler problem on a bound orbit (formulas at the top of the file).
// Throws std::domain_error for an orbit that is not bound or passes through q = 0.
template <class T>
State<T, 2> kepler_flow(const Kepler<T>& system, const State<T, 2>& start, const T& t) {
  using std::abs;
  using std::cos;
  using std::round;
  using std::sin;
  using std::sqrt;
  const T& mu = system.mu;
  const auto& q0 = start.q;
  const auto& w0 = start.w;
  const T r0 = sqrt(T(q0[0] * q0[0] + q0[1] * q0[1]));
  const T sigma0 = q0[0] * w0[0] + q0[1] * w0[1];
  const T inverse_a = 2 / r0 - (w0[0] * w0[0] + w0[1] * w0[1]) / mu;
  const bool finite = closed_form_detail::finite(r0) && closed_form_detail::finite(sigma0) &&
                      closed_form_detail::finite(inverse_a) && closed_form_detail::finite(t);
  if (!finite || !(mu > 0) || !(r0 > 0) || !(inverse_a > 0))
    throw std::domain_error("kepler_flow: the closed form needs mu > 0 and a bound orbit away from q = 0 (energy < "
                            "0), got |q0| = " + to_decimal<T>(r0) + ", 1/a = " + to_decimal<T>(inverse_a));
  const T a = 1 / inverse_a;
  const T mean_motion = sqrt(mu * inverse_a * inverse_a * inverse_a);
  const T C = 1 - r0 * inverse_a, S = sigma0 / sqrt(mu * a);
  const T angular_momentum = q0[0] * w0[1] - q0[1] * w0[0];
  if (angular_momentum == 0 || !(C * C + S * S < 1))
    throw std::domain_error("kepler_flow: eccentricity " + to_decimal<T>(T(sqrt(T(C * C + S * S)))) +
                            " >= 1: a radial orbit through q = 0");
  const T period = 2 * boost::math::constants::pi<T>() / mean_motion;
  const T reduced_t = t - period * round(t / period);
  const T M = mean_motion * reduced_t;
  // x − (C sin x − S (1 − cos x)) = M, and |C sin x − S (1 − cos x)| ≤ 2e < 2.
  auto kepler_equation = [&](const T& x) {
    return std::pair<T, T>(x - C * sin(x) + S * (1 - cos(x)) - M, 1 - C * cos(x) + S * sin(x));
  };
  std::uintmax_t iterations = 200;
  const T x = boost::math::tools::newton_raphson_iterate(kepler_equation, M, T(M - 2), T(M + 2),
                                                         precision_bits<T>() - 2, iterations);
  if (iterations >= 200)
    throw std::runtime_error("kepler_flow: Newton on Kepler's equation did not converge at t = " + to_decimal<T>(t));
  const T half_sine = sin(x / 2);
  const T one_minus_cos = 2 * half_sine * half_sine;
  const T r = a * (1 - C * cos(x) + S * sin(x));
  const T f = 1 - a / r0 * one_minus_cos;
  const T g = reduced_t - (x - sin(x)) / mean_motion;
  const T f_dot = -sqrt(mu * a) * sin(x) / (r * r0);
  const T g_dot = 1 - a / r * one_minus_cos;
  State<T, 2> end;
  end.q = f * q0 + g * w0;
  end.w = f_dot * q0 + g_dot * w0;
  return end;
}

}  // namespace vivv
