// Taylor-mode automatic differentiation over a tape (issue 3).
//
// For a second-order system x'' = a(x, x') in R^m whose acceleration a is
// recorded on a Tape with inputs (x, v = x') and outputs a, TaylorExpansion
// computes the normalized Taylor coefficients x_k = x^(k)(0)/k!, v_k of the
// solution through (x_0, v_0) up to order p, coefficient by coefficient:
//   x_{k+1} = v_k / (k+1),   v_{k+1} = a_k / (k+1),
// where a_k, the k-th coefficient of a(x(t), v(t)), comes from the standard
// recurrences of power-series arithmetic applied node by node (Griewank &
// Walther, Evaluating Derivatives, §13.2; Jorba & Zou 2005, §2):
//   (u·w)_k = Σ_{j=0..k} u_j w_{k−j}
//   (u/w)_k = (u_k − Σ_{j=1..k} w_j (u/w)_{k−j}) / w_0
//   s = sin u, c = cos u:  s_k = (1/k) Σ_{j=1..k} j u_j c_{k−j},  c_k = −(1/k) Σ_{j=1..k} j u_j s_{k−j}
//   e = exp u:             e_k = (1/k) Σ_{j=1..k} j u_j e_{k−j}
//   l = log u:             l_k = (u_k − (1/k) Σ_{j=1..k−1} j l_j u_{k−j}) / u_0
//   r = √u:                r_k = (u_k − Σ_{j=1..k−1} r_j r_{k−j}) / (2 r_0)
//   v = u^α:               v_k = (α Σ_{j=0..k−1} (k−j) u_{k−j} v_j − Σ_{j=1..k−1} j v_j u_{k−j}) / (k u_0)
// so an expansion to order p costs O(p² · nodes) multiply-adds, which are counted.
//
// Everything is in T; for MPFR the operations run on the raw mpfr_t in place
// (no temporaries), and each inner product is summed exactly in fixed point and
// rounded once (taylor_detail::fixed_point_dot). Construct and use an expansion at one
// MPFR precision.
#pragma once

#include <gmp.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/numerics/scalar.hpp"
#include "core/autodiff/tape.hpp"

namespace vivv {

namespace taylor_detail {

// r = a + b, a − b, a · b, a / b, −a, a / k (k an integer), without temporaries for MPFR.
template <class T>
void set_add(T& r, const T& a, const T& b) {
  if constexpr (is_mpfr_v<T>) {
    mpfr_add(r.backend().data(), a.backend().data(), b.backend().data(), MPFR_RNDN);
  } else {
    r = a + b;
  }
}
template <class T>
void set_sub(T& r, const T& a, const T& b) {
  if constexpr (is_mpfr_v<T>) {
    mpfr_sub(r.backend().data(), a.backend().data(), b.backend().data(), MPFR_RNDN);
  } else {
    r = a - b;
  }
}
template <class T>
void set_mul(T& r, const T& a, const T& b) {
  if constexpr (is_mpfr_v<T>) {
    mpfr_mul(r.backend().data(), a.backend().data(), b.backend().data(), MPFR_RNDN);
  } else {
    r = a * b;
  }
}
template <class T>
void set_div(T& r, const T& a, const T& b) {
  if constexpr (is_mpfr_v<T>) {
    mpfr_div(r.backend().data(), a.backend().data(), b.backend().data(), MPFR_RNDN);
  } else {
    r = a / b;
  }
}
template <class T>
void set_neg(T& r, const T& a) {
  if constexpr (is_mpfr_v<T>) {
    mpfr_neg(r.backend().data(), a.backend().data(), MPFR_RNDN);
  } else {
    r = -a;
  }
}
template <class T>
void set_div_int(T& r, const T& a, long k) {
  if constexpr (is_mpfr_v<T>) {
    mpfr_div_si(r.backend().data(), a.backend().data(), k, MPFR_RNDN);
  } else {
    r = a / T(k);
  }
}
template <class T>
void set_mul_int(T& r, const T& a, long k) {
  if constexpr (is_mpfr_v<T>) {
    mpfr_mul_si(r.backend().data(), a.backend().data(), k, MPFR_RNDN);
  } else {
    r = a * T(k);
  }
}

// s = sin a, c = cos a (one MPFR call for both).
template <class T>
void set_sin_cos(T& s, T& c, const T& a) {
  using std::cos;
  using std::sin;
  if constexpr (is_mpfr_v<T>) {
    mpfr_sin_cos(s.backend().data(), c.backend().data(), a.backend().data(), MPFR_RNDN);
  } else {
    s = sin(a);
    c = cos(a);
  }
}

// r = Σ_{j=from..to} a[j] b[total − j] by mpfr_mul and mpfr_add, term by term (any operands).
inline void mpfr_dot_termwise(mpfr_real& r, const mpfr_real* a, const mpfr_real* b, int from,
                              int to, int total, mpfr_real& scratch) {
  mpfr_set_zero(r.backend().data(), 1);
  for (int j = from; j <= to; ++j) {
    mpfr_mul(scratch.backend().data(), a[j].backend().data(), b[total - j].backend().data(),
             MPFR_RNDN);
    mpfr_add(r.backend().data(), r.backend().data(), scratch.backend().data(), MPFR_RNDN);
  }
}

// Significands of up to this many limbs take the fixed-point path of fixed_point_dot (2048 bits).
inline constexpr int fixed_point_dot_max_limbs = 32;

// r = Σ_{j=from..to} a[j] b[total − j] for MPFR operands at r's precision of n limbs: with
// E = max_j (e(a_j) + e(b_{total−j})), the exact products are added in one fixed-point
// accumulator of unit 2^(E − 64(n+1)), each truncated to that unit, and the sum is rounded
// once: |error| ≤ ½ ulp(r) + (terms)·2^(E − 64(n+1)), below the mpfr_mul + mpfr_add rounding
// of every term (≈ (terms)·2^(E − 64n)) and at about half its cost.
// NaN or infinite operands, or other precisions, take mpfr_dot_termwise.
inline void fixed_point_dot(mpfr_real& r, const mpfr_real* a, const mpfr_real* b, int from, int to,
                            int total, mpfr_real& scratch) {
  constexpr int limb_bits = GMP_NUMB_BITS;
  mpfr_ptr result = r.backend().data();
  const mpfr_prec_t precision = mpfr_get_prec(result);
  const mp_size_t n = (precision + limb_bits - 1) / limb_bits;  // limbs of every significand
  const mp_size_t width = n + 1;  // accumulator limbs below 2^E; one more holds carries and sign
  if (n > fixed_point_dot_max_limbs) return mpfr_dot_termwise(r, a, b, from, to, total, scratch);
  // E, and whether every operand is zero or a regular number at r's precision.
  mpfr_exp_t top = 0;
  bool any = false;
  for (int j = from; j <= to; ++j) {
    mpfr_srcptr x = a[j].backend().data(), y = b[total - j].backend().data();
    if (mpfr_zero_p(x) || mpfr_zero_p(y)) continue;
    if (!mpfr_regular_p(x) || !mpfr_regular_p(y) || mpfr_get_prec(x) != precision ||
        mpfr_get_prec(y) != precision)
      return mpfr_dot_termwise(r, a, b, from, to, total, scratch);
    const mpfr_exp_t exponent = mpfr_get_exp(x) + mpfr_get_exp(y);
    if (!any || exponent > top) top = exponent;
    any = true;
  }
  if (!any) {
    mpfr_set_zero(result, 1);
    return;
  }
  mp_limb_t accumulator[fixed_point_dot_max_limbs + 2] = {};  // two's complement
  mp_limb_t product[2 * fixed_point_dot_max_limbs];
  mp_limb_t shifted[fixed_point_dot_max_limbs + 1];
  for (int j = from; j <= to; ++j) {
    mpfr_srcptr x = a[j].backend().data(), y = b[total - j].backend().data();
    if (mpfr_zero_p(x) || mpfr_zero_p(y)) continue;
    // The 2n-limb product has unit 2^(e(x) + e(y) − 128n): shift it right by `shift` bits.
    const mpfr_exp_t shift = top - (mpfr_get_exp(x) + mpfr_get_exp(y)) + (n - 1) * limb_bits;
    const mp_size_t skipped = shift / limb_bits, count = 2 * n - skipped;
    if (count <= 0) continue;  // the whole term is below the unit
    mpn_mul_n(product, static_cast<const mp_limb_t*>(mpfr_custom_get_significand(x)),
              static_cast<const mp_limb_t*>(mpfr_custom_get_significand(y)), n);
    const mp_limb_t* aligned = product + skipped;
    if (shift % limb_bits != 0) {
      mpn_rshift(shifted, aligned, count, static_cast<unsigned>(shift % limb_bits));
      aligned = shifted;
    }
    if (mpfr_signbit(x) == mpfr_signbit(y)) {
      mpn_add(accumulator, accumulator, width + 1, aligned, count);
    } else {
      mpn_sub(accumulator, accumulator, width + 1, aligned, count);
    }
  }
  // r = ±|accumulator| · 2^(E − 64(n+1)), rounded to nearest once.
  const bool negative = (accumulator[width] >> (limb_bits - 1)) != 0;
  if (negative) mpn_neg(accumulator, accumulator, width + 1);
  mpz_t sum;
  mpz_roinit_n(sum, accumulator, negative ? -(width + 1) : width + 1);
  mpfr_set_z_2exp(result, sum, top - width * limb_bits, MPFR_RNDN);
}

// r = Σ_{j=from..to} a[j] b[total − j] (r = 0 for an empty range); `scratch` may be overwritten.
template <class T>
void set_dot(T& r, const T* a, const T* b, int from, int to, int total, T& scratch) {
  if constexpr (is_mpfr_v<T>) {
    fixed_point_dot(r, a, b, from, to, total, scratch);
  } else {
    (void)scratch;
    T sum = 0;
    for (int j = from; j <= to; ++j) sum += a[j] * b[total - j];
    r = sum;
  }
}

// ln |x| to double accuracy, for any exponent range (MPFR: from the exponent and leading bits);
// −∞ for 0.
template <class T>
double log_abs(const T& x) {
  using std::abs;
  using std::log;
  if constexpr (is_mpfr_v<T>) {
    long exponent = 0;
    const double mantissa = mpfr_get_d_2exp(&exponent, x.backend().data(), MPFR_RNDN);
    return std::log(std::fabs(mantissa)) + static_cast<double>(exponent) * 0.69314718055994531;
  } else {
    return static_cast<double>(log(abs(x)));
  }
}

}  // namespace taylor_detail

// Jorba & Zou (2005), as heyoka does, for a step tolerance tol:
// p = ⌈−ln(tol)/2 + 1⌉, at least 2 (an integer heuristic: double suffices).
template <class T>
int taylor_order_for(const T& tolerance) {
  using std::log;
  if (!(tolerance > 0 && tolerance < 1))
    throw std::invalid_argument("taylor_order_for: tolerance must be in (0, 1), got " +
                                to_decimal<T>(tolerance));
  const double minus_log = -static_cast<double>(log(tolerance));
  return std::max(2, static_cast<int>(std::ceil(minus_log / 2 + 1)));
}

// The step h = ρ e^{−2} e^{−0.7/(p−1)}, ρ = min((s/‖y_{p−1}‖)^{1/(p−1)}, (s/‖y_p‖)^{1/p}), from
// ln s, ln ‖y_{p−1}‖ and ln ‖y_p‖ (−∞ for a vanishing norm); +∞ when both norms vanish.
inline double jorba_zou_step(double log_scale, double log_previous, double log_last, int p) {
  const double log_rho = std::min((log_scale - log_previous) / (p - 1), (log_scale - log_last) / p);
  return std::exp(log_rho - 2 - 0.7 / (p - 1));
}

template <class T>
class TaylorExpansion {
 public:
  // The expansion of x'' = a(x, x') for `tape`: inputs (x_0..x_{m−1}, v_0..v_{m−1}), outputs a.
  explicit TaylorExpansion(Tape<T> tape) : tape_(std::move(tape)) {
    if (tape_.inputs % 2 != 0 || 2 * static_cast<int>(tape_.outputs.size()) != tape_.inputs)
      throw std::invalid_argument("TaylorExpansion: the tape must map (x, v) in R^2m to a in R^m");
  }

  // m, the dimension of x.
  int dimension() const { return tape_.inputs / 2; }
  const Tape<T>& tape() const { return tape_; }

  // Computes x_k = x^(k)(0)/k! and v_k = x^(k+1)(0)/k! for k = 0..order from x(0) = x0, x'(0) = v0.
  void expand(const T* x0, const T* v0, int order);

  int order() const { return order_; }
  // x_k of component i.
  const T& position(int i, int k) const { return coefficients_[i * stride_ + k]; }
  // v_k of component i.
  const T& velocity(int i, int k) const { return coefficients_[(dimension() + i) * stride_ + k]; }

  // Multiply-adds performed so far (inner-product terms plus scalings).
  long long multiply_adds() const { return multiply_adds_; }

  // Test-only negative control: when ≥ 1, the cosine coefficient of that order gets the wrong
  // sign in every sin/cos recurrence (a deliberately wrong series coefficient).
  int fault_order = -1;

 private:
  void resize(int order);
  void node_coefficient(int index, int k);

  T* coefficients(int node) { return coefficients_.data() + node * stride_; }
  T* weighted(int node) { return weighted_.data() + node * stride_; }   // j·u_j of the operand
  T* weighted_self(int node) { return self_weighted_.data() + node * stride_; }  // j·c_j

  Tape<T> tape_;
  int order_ = -1;
  int stride_ = 0;
  std::vector<T> coefficients_;
  std::vector<T> weighted_;
  std::vector<T> self_weighted_;
  T scratch_, sum_, other_;
  long long multiply_adds_ = 0;
};

template <class T>
void TaylorExpansion<T>::resize(int order) {
  if (order == order_) return;
  order_ = order;
  stride_ = order + 1;
  const std::size_t size = tape_.nodes.size() * static_cast<std::size_t>(stride_);
  coefficients_.assign(size, T(0));
  weighted_.assign(size, T(0));
  self_weighted_.assign(size, T(0));
  scratch_ = T(0), sum_ = T(0), other_ = T(0);
}

template <class T>
void TaylorExpansion<T>::expand(const T* x0, const T* v0, int order) {
  if (order < 1) throw std::invalid_argument("TaylorExpansion: order must be at least 1");
  resize(order);
  const int m = dimension();
  for (int i = 0; i < m; ++i) {
    coefficients(i)[0] = x0[i];
    coefficients(m + i)[0] = v0[i];
  }
  const int count = static_cast<int>(tape_.nodes.size());
  for (int k = 0; k < order; ++k) {
    for (int index = tape_.inputs; index < count; ++index) node_coefficient(index, k);
    // x_{k+1} = v_k / (k+1), v_{k+1} = a_k / (k+1).
    for (int i = 0; i < m; ++i) {
      taylor_detail::set_div_int(coefficients(i)[k + 1], coefficients(m + i)[k], k + 1);
      taylor_detail::set_div_int(coefficients(m + i)[k + 1], coefficients(tape_.outputs[i])[k], k + 1);
    }
  }
}

template <class T>
void TaylorExpansion<T>::node_coefficient(int index, int k) {
  using namespace taylor_detail;  // set_add, set_mul, set_dot, ...
  using std::exp;
  using std::log;
  using std::pow;
  using std::sqrt;
  const TapeNode& node = tape_.nodes[index];
  T* c = coefficients(index);
  const T* u = node.a >= 0 ? coefficients(node.a) : nullptr;
  const T* w = node.b >= 0 ? coefficients(node.b) : nullptr;
  switch (node.op) {
    case TapeOp::input:
      return;
    case TapeOp::constant:
      c[k] = k == 0 ? tape_.constants[node.c] : T(0);
      return;
    case TapeOp::add:
      set_add(c[k], u[k], w[k]);
      return;
    case TapeOp::sub:
      set_sub(c[k], u[k], w[k]);
      return;
    case TapeOp::neg:
      set_neg(c[k], u[k]);
      return;
    case TapeOp::mul:
      set_dot(c[k], u, w, 0, k, k, scratch_);
      multiply_adds_ += k + 1;
      return;
    case TapeOp::square:
      // 2 Σ_{j<k/2} u_j u_{k−j} + [k even] u_{k/2}².
      set_dot(c[k], u, u, 0, (k + 1) / 2 - 1, k, scratch_);
      set_mul_int(c[k], c[k], 2);
      if (k % 2 == 0) {
        set_mul(scratch_, u[k / 2], u[k / 2]);
        set_add(c[k], c[k], scratch_);
      }
      multiply_adds_ += k / 2 + 1;
      return;
    case TapeOp::div:
      set_dot(sum_, w, c, 1, k, k, scratch_);
      set_sub(sum_, u[k], sum_);
      set_div(c[k], sum_, w[0]);
      multiply_adds_ += k + 1;
      return;
    case TapeOp::add_constant:
      if (k == 0) {
        set_add(c[0], u[0], tape_.constants[node.c]);
      } else {
        c[k] = u[k];
      }
      return;
    case TapeOp::constant_minus:
      if (k == 0) {
        set_sub(c[0], tape_.constants[node.c], u[0]);
      } else {
        set_neg(c[k], u[k]);
      }
      return;
    case TapeOp::scale:
      set_mul(c[k], tape_.constants[node.c], u[k]);
      multiply_adds_ += 1;
      return;
    case TapeOp::constant_div:
      if (k == 0) {
        set_div(c[0], tape_.constants[node.c], u[0]);
      } else {
        set_dot(sum_, u, c, 1, k, k, scratch_);
        set_neg(sum_, sum_);
        set_div(c[k], sum_, u[0]);
      }
      multiply_adds_ += k + 1;
      return;
    case TapeOp::sin: {
      T* s = c;
      T* co = coefficients(index + 1);
      T* du = weighted(index);
      if (k == 0) {
        set_sin_cos(s[0], co[0], u[0]);
        return;
      }
      set_mul_int(du[k], u[k], k);
      set_dot(sum_, du, co, 1, k, k, scratch_);
      set_dot(other_, du, s, 1, k, k, scratch_);
      set_div_int(s[k], sum_, k);
      set_div_int(co[k], other_, fault_order == k ? k : -k);
      multiply_adds_ += 2 * k + 1;
      return;
    }
    case TapeOp::cos:
      return;  // computed with its sin partner
    case TapeOp::exp: {
      T* du = weighted(index);
      if (k == 0) {
        c[0] = exp(u[0]);
        return;
      }
      set_mul_int(du[k], u[k], k);
      set_dot(sum_, du, c, 1, k, k, scratch_);
      set_div_int(c[k], sum_, k);
      multiply_adds_ += k + 1;
      return;
    }
    case TapeOp::log:
    case TapeOp::atan: {
      // d c' = u' with d = u (log) or d = 1 + u², the node b (atan):
      // c_k = (u_k − (1/k) Σ_{j=1..k−1} j c_j d_{k−j}) / d_0.
      const T* d = node.op == TapeOp::log ? u : w;
      T* dc = weighted_self(index);
      if (k == 0) {
        using std::atan;
        if (node.op == TapeOp::log) c[0] = log(u[0]);
        else c[0] = atan(u[0]);
        return;
      }
      set_dot(sum_, dc, d, 1, k - 1, k, scratch_);
      set_div_int(sum_, sum_, k);
      set_sub(sum_, u[k], sum_);
      set_div(c[k], sum_, d[0]);
      set_mul_int(dc[k], c[k], k);
      multiply_adds_ += k + 1;
      return;
    }
    case TapeOp::sqrt: {
      if (k == 0) {
        c[0] = sqrt(u[0]);
        return;
      }
      // Σ_{j=1..k−1} r_j r_{k−j} = 2 Σ_{j=1..⌊(k−1)/2⌋} r_j r_{k−j} + [k even] r_{k/2}².
      set_dot(sum_, c, c, 1, (k - 1) / 2, k, scratch_);
      set_mul_int(sum_, sum_, 2);
      if (k % 2 == 0) {
        set_mul(scratch_, c[k / 2], c[k / 2]);
        set_add(sum_, sum_, scratch_);
      }
      set_sub(sum_, u[k], sum_);
      set_mul_int(other_, c[0], 2);
      set_div(c[k], sum_, other_);
      multiply_adds_ += k / 2 + 1;
      return;
    }
    case TapeOp::pow: {
      const T& alpha = tape_.constants[node.c];
      T* du = weighted(index);
      T* dv = weighted_self(index);
      if (k == 0) {
        c[0] = pow(u[0], alpha);
        return;
      }
      set_mul_int(du[k], u[k], k);
      // α Σ_{j=0..k−1} du_{k−j} v_j − Σ_{j=1..k−1} dv_j u_{k−j}, over k u_0.
      set_dot(sum_, c, du, 0, k - 1, k, scratch_);
      set_mul(sum_, sum_, alpha);
      set_dot(other_, dv, u, 1, k - 1, k, scratch_);
      set_sub(sum_, sum_, other_);
      set_mul_int(other_, u[0], k);
      set_div(c[k], sum_, other_);
      set_mul_int(dv[k], c[k], k);
      multiply_adds_ += 2 * k + 2;
      return;
    }
  }
}

}  // namespace vivv
