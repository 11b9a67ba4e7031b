// Truncated power series a(h) = Σ_{k<K} a_k h^k over a scalar T, as a scalar a
// system's generic Lagrangian can be evaluated in: L(q(h), w(h)) expanded in
// h, coefficient by coefficient. The recurrences are the standard ones
// (Griewank & Walther §13.2): products by convolution, quotients, sqrt, exp,
// log, powers and sin/cos by the ODEs they satisfy. All operands of one
// expression have the same length K.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/numerics/scalar.hpp"

namespace vivv {

template <class T>
class PowerSeries {
 public:
  PowerSeries() = default;
  // The constant c, with `length` coefficients (length 0: adopts the other operand's).
  PowerSeries(const T& c, int length = 0) : coefficients_(std::max(length, 1), T(0)) { coefficients_[0] = c; }
  PowerSeries(int c) : PowerSeries(T(c)) {}
  // The series from its coefficients a_0, a_1, ...
  static PowerSeries from(std::vector<T> coefficients) {
    PowerSeries a;
    a.coefficients_ = std::move(coefficients);
    return a;
  }

  int length() const { return static_cast<int>(coefficients_.size()); }
  const T& operator[](int k) const { return coefficients_[k]; }
  T& operator[](int k) { return coefficients_[k]; }
  // a_k, or 0 outside 0 … length − 1.
  T coefficient(int k) const { return k >= 0 && k < length() ? coefficients_[k] : T(0); }

  // a(h)·h^s (s > 0) or a(h)/h^−s (s < 0, dropping a_0 … a_{−s−1}), truncated to the same length.
  PowerSeries shifted(int s) const {
    PowerSeries out = *this;
    for (int k = 0; k < length(); ++k) out[k] = coefficient(k - s);
    return out;
  }
  // da/dh.
  PowerSeries derivative() const {
    PowerSeries out = *this;
    for (int k = 0; k < length(); ++k) out[k] = (k + 1) * coefficient(k + 1);
    return out;
  }

 private:
  std::vector<T> coefficients_{T(0)};
};

namespace power_series_detail {

// A constant of length 1 takes the other operand's length.
template <class T>
void match(PowerSeries<T>& a, PowerSeries<T>& b) {
  if (a.length() == b.length()) return;
  if (a.length() == 1) a = PowerSeries<T>(a[0], b.length());
  else if (b.length() == 1) b = PowerSeries<T>(b[0], a.length());
  else throw std::invalid_argument("PowerSeries: operands of different lengths");
}

}  // namespace power_series_detail

template <class T>
PowerSeries<T> operator+(PowerSeries<T> a, PowerSeries<T> b) {
  power_series_detail::match(a, b);
  for (int k = 0; k < a.length(); ++k) a[k] += b[k];
  return a;
}
template <class T>
PowerSeries<T> operator-(PowerSeries<T> a) {
  for (int k = 0; k < a.length(); ++k) a[k] = -a[k];
  return a;
}
template <class T>
PowerSeries<T> operator-(const PowerSeries<T>& a, const PowerSeries<T>& b) {
  return a + (-b);
}
// (ab)_k = Σ_j a_j b_{k−j}.
template <class T>
PowerSeries<T> operator*(PowerSeries<T> a, PowerSeries<T> b) {
  power_series_detail::match(a, b);
  PowerSeries<T> c(T(0), a.length());
  for (int k = 0; k < a.length(); ++k)
    for (int j = 0; j <= k; ++j) c[k] += a[j] * b[k - j];
  return c;
}
// c = a/b: c_k = (a_k − Σ_{j<k} c_j b_{k−j}) / b_0.
template <class T>
PowerSeries<T> operator/(PowerSeries<T> a, PowerSeries<T> b) {
  power_series_detail::match(a, b);
  if (b[0] == 0) throw std::domain_error("PowerSeries: division by a series with zero constant term");
  PowerSeries<T> c(T(0), a.length());
  for (int k = 0; k < a.length(); ++k) {
    T sum = a[k];
    for (int j = 0; j < k; ++j) sum -= c[j] * b[k - j];
    c[k] = sum / b[0];
  }
  return c;
}

// Mixed operands: scalars in T or int.
#define VIVV_SERIES_MIXED(op)                                                  \
  template <class T>                                                           \
  PowerSeries<T> operator op(const PowerSeries<T>& a, const T& c) {           \
    return a op PowerSeries<T>(c);                                             \
  }                                                                            \
  template <class T>                                                           \
  PowerSeries<T> operator op(const T& c, const PowerSeries<T>& a) {           \
    return PowerSeries<T>(c) op a;                                             \
  }                                                                            \
  template <class T>                                                           \
  PowerSeries<T> operator op(const PowerSeries<T>& a, int c) {                \
    return a op PowerSeries<T>(T(c));                                          \
  }                                                                            \
  template <class T>                                                           \
  PowerSeries<T> operator op(int c, const PowerSeries<T>& a) {                \
    return PowerSeries<T>(T(c)) op a;                                          \
  }
VIVV_SERIES_MIXED(+)
VIVV_SERIES_MIXED(-)
VIVV_SERIES_MIXED(*)
VIVV_SERIES_MIXED(/)
#undef VIVV_SERIES_MIXED

// e = exp(a): e' = a' e, so k e_k = Σ_{j=1..k} j a_j e_{k−j}.
template <class T>
PowerSeries<T> exp(const PowerSeries<T>& a) {
  using std::exp;
  PowerSeries<T> e(T(0), a.length());
  e[0] = exp(a[0]);
  for (int k = 1; k < a.length(); ++k) {
    T sum = 0;
    for (int j = 1; j <= k; ++j) sum += j * a[j] * e[k - j];
    e[k] = sum / k;
  }
  return e;
}

// t with d t' = a' and t_0 = first: k d_0 t_k = k a_k − Σ_{j=1..k−1} j t_j d_{k−j}
// (log: d = a; atan: d = 1 + a²).
template <class T>
PowerSeries<T> integral_of_ratio(const PowerSeries<T>& a, const PowerSeries<T>& d, const T& first) {
  PowerSeries<T> t(T(0), a.length());
  t[0] = first;
  for (int k = 1; k < a.length(); ++k) {
    T sum = k * a[k];
    for (int j = 1; j < k; ++j) sum -= j * t[j] * d[k - j];
    t[k] = sum / (k * d[0]);
  }
  return t;
}

// l = log(a): a l' = a'.
template <class T>
PowerSeries<T> log(const PowerSeries<T>& a) {
  using std::log;
  if (!(a[0] > 0)) throw std::domain_error("PowerSeries: log of a series with constant term <= 0");
  return integral_of_ratio(a, a, T(log(a[0])));
}

// p = a^c: a p' = c a' p, so k a_0 p_k = Σ_{j=1..k} (c j − (k − j)) a_j p_{k−j}.
template <class T>
PowerSeries<T> pow(const PowerSeries<T>& a, const T& c) {
  using std::pow;
  if (!(a[0] > 0)) throw std::domain_error("PowerSeries: power of a series with constant term <= 0");
  PowerSeries<T> p(T(0), a.length());
  p[0] = pow(a[0], c);
  for (int k = 1; k < a.length(); ++k) {
    T sum = 0;
    for (int j = 1; j <= k; ++j) sum += (c * j - (k - j)) * a[j] * p[k - j];
    p[k] = sum / (k * a[0]);
  }
  return p;
}

template <class T>
PowerSeries<T> sqrt(const PowerSeries<T>& a) {
  return pow(a, T(1) / 2);
}

// t = atan a: (1 + a²) t' = a'.
template <class T>
PowerSeries<T> atan(const PowerSeries<T>& a) {
  using std::atan;
  return integral_of_ratio(a, PowerSeries<T>(1 + a * a), T(atan(a[0])));
}

// s = sin a, c = cos a: s' = c a', c' = −s a'.
template <class T>
void sin_cos(const PowerSeries<T>& a, PowerSeries<T>& s, PowerSeries<T>& c) {
  using std::cos, std::sin;
  s = PowerSeries<T>(sin(a[0]), a.length());
  c = PowerSeries<T>(cos(a[0]), a.length());
  for (int k = 1; k < a.length(); ++k) {
    T sum_s = 0, sum_c = 0;
    for (int j = 1; j <= k; ++j) {
      sum_s += j * a[j] * c[k - j];
      sum_c -= j * a[j] * s[k - j];
    }
    s[k] = sum_s / k;
    c[k] = sum_c / k;
  }
}
template <class T>
PowerSeries<T> sin(const PowerSeries<T>& a) {
  PowerSeries<T> s, c;
  sin_cos(a, s, c);
  return s;
}
template <class T>
PowerSeries<T> cos(const PowerSeries<T>& a) {
  PowerSeries<T> s, c;
  sin_cos(a, s, c);
  return c;
}

// A power series whose coefficients are known only below `known` — what a
// truncated series leaves after a division by one that starts at h^m (h itself,
// or q(h) − q(0)): a/b = (a/h^m)/(b/h^m) drops a_0 … a_{m−1}, which must vanish,
// and the top m coefficients of the quotient are then unknown. A discrete
// Lagrangian written as a formula divides by h, (qe − qb)/h; this is the scalar
// it is expanded in (references/lagrangian_error_expansion.hpp). Every other
// operation is causal — coefficient k of the result needs coefficients ≤ k of
// its operands — so `known` is the smaller of the operands'.
template <class T>
struct KnownSeries {
  PowerSeries<T> series;
  int known = std::numeric_limits<int>::max();  // a constant is known exactly

  KnownSeries() = default;
  KnownSeries(const T& c) : series(c) {}
  KnownSeries(int c) : series(T(c)) {}
  KnownSeries(PowerSeries<T> s, int k) : series(std::move(s)), known(k) {}
};

namespace power_series_detail {
template <class T>
KnownSeries<T> known(PowerSeries<T> s, int a, int b) {
  return KnownSeries<T>(std::move(s), std::min(a, b));
}
}  // namespace power_series_detail

template <class T>
KnownSeries<T> operator+(const KnownSeries<T>& a, const KnownSeries<T>& b) {
  return power_series_detail::known(a.series + b.series, a.known, b.known);
}
template <class T>
KnownSeries<T> operator-(const KnownSeries<T>& a, const KnownSeries<T>& b) {
  return power_series_detail::known(a.series - b.series, a.known, b.known);
}
template <class T>
KnownSeries<T> operator-(const KnownSeries<T>& a) {
  return KnownSeries<T>(-a.series, a.known);
}
template <class T>
KnownSeries<T> operator*(const KnownSeries<T>& a, const KnownSeries<T>& b) {
  return power_series_detail::known(a.series * b.series, a.known, b.known);
}
// a/b with b = h^m b', b'_0 ≠ 0: a's first m coefficients must vanish (to the rounding of the
// largest known one; a nonzero one is a pole in h, which the expansion cannot hold).
template <class T>
KnownSeries<T> operator/(const KnownSeries<T>& a, const KnownSeries<T>& b) {
  using std::abs, std::max;
  const int usable = std::min({a.known, b.known, std::max(a.series.length(), b.series.length())});
  int m = 0;
  while (m < b.series.length() && m < usable && b.series[m] == 0) ++m;
  if (m >= usable)
    throw std::domain_error("KnownSeries: division by a series with no known nonzero coefficient");
  if (m == 0) return power_series_detail::known(a.series / b.series, a.known, b.known);
  T scale = 0;
  for (int k = 0; k < std::min(a.series.length(), a.known); ++k)
    scale = max(scale, T(abs(a.series[k])));
  const T negligible = 256 * epsilon<T>() * scale;
  for (int k = 0; k < m; ++k)
    if (abs(a.series.coefficient(k)) > negligible)
      throw std::domain_error(
          "KnownSeries: a pole in h (the dividend does not vanish where the divisor does)");
  return power_series_detail::known(a.series.shifted(-m) / b.series.shifted(-m), a.known - m,
                                    b.known - m);
}

#define VIVV_KNOWN_MIXED(op)                                        \
  template <class T>                                                \
  KnownSeries<T> operator op(const KnownSeries<T>& a, const T& c) { \
    return a op KnownSeries<T>(c);                                  \
  }                                                                 \
  template <class T>                                                \
  KnownSeries<T> operator op(const T& c, const KnownSeries<T>& a) { \
    return KnownSeries<T>(c) op a;                                  \
  }
VIVV_KNOWN_MIXED(+)
VIVV_KNOWN_MIXED(-)
VIVV_KNOWN_MIXED(*)
VIVV_KNOWN_MIXED(/)
#undef VIVV_KNOWN_MIXED

#define VIVV_KNOWN_UNARY(f)                      \
  template <class T>                             \
  KnownSeries<T> f(const KnownSeries<T>& a) {    \
    return KnownSeries<T>(f(a.series), a.known); \
  }
VIVV_KNOWN_UNARY(exp)
VIVV_KNOWN_UNARY(log)
VIVV_KNOWN_UNARY(sqrt)
VIVV_KNOWN_UNARY(atan)
VIVV_KNOWN_UNARY(sin)
VIVV_KNOWN_UNARY(cos)
#undef VIVV_KNOWN_UNARY
template <class T>
KnownSeries<T> pow(const KnownSeries<T>& a, const T& c) {
  return KnownSeries<T>(pow(a.series, c), a.known);
}

}  // namespace vivv
