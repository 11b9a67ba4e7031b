// Second-order forward-mode automatic differentiation.
//
// A Jet<T, N> carries a value f, its gradient ∇f and its Hessian ∇²f with
// respect to N independent variables, all exact in T (no finite differences).
// Every elementary function u ↦ φ(u) propagates by the chain rule
//   ∇φ(u) = φ'(u) ∇u,   ∇²φ(u) = φ'(u) ∇²u + φ''(u) ∇u ∇uᵀ.
// Jet<T, N, 1> carries the value and gradient only (no Hessian): where only
// first derivatives are used — the TQ Legendre transforms and the Newton
// Jacobians of core/tq/tq_evolution.hpp, often nested — it is N + 1 numbers
// instead of 1 + N + N².
// Jet<T, N, 2, s> with 0 < s < N carries, of the Hessian, only the block
// ∂²f/∂x_i∂x_j with i < s ≤ j: a DEL step's Newton needs p_begin = −∂L_d/∂q_b and
// ∂p_begin/∂q_e, not the q_b–q_b and q_e–q_e blocks. Each entry it keeps is
// computed by the same operations, in the same order, as the full Hessian's:
// the two agree bit for bit.
// Systems write their Lagrangian once, templated on the scalar S; core/
// evaluates it with S = Jet<T, 2n> to get dL/dq, dL/dw and the blocks of the
// Hessian, and discrete Lagrangians the same way in (q_b, q_e).
#pragma once

#include <array>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/numerics/scalar.hpp"

namespace vivv {

// The arithmetic both jets share (the fixed one below and the run-time one after it), written
// once so that both compute the same numbers operation for operation: the chain rule, the
// product's derivatives and the scaling by a constant. Derived has value, gradient, hessian,
// second(i, j), for_each_second(f) (each Hessian entry it computes, mirrored where symmetric)
// and is_constant() (no derivatives: a run-time jet before its first variable).
//
// φ(u) from φ(u0), φ'(u0), φ''(u0): the chain rule above, in place (`apply_chain`) or on a
// copy. The arithmetic works in place through one scratch number and fills the symmetric
// Hessian's upper triangle, mirroring it: for MPFR every temporary is an allocation, and these
// loops are most of a DEL step's cost. (The elementary functions below take their argument by
// value for the same reason: a caller that moves a jet in gets it back transformed, with no
// allocation.)
template <class Derived, class T, int Order>
struct JetArithmetic {
  Derived& apply_chain(const T& f0, const T& f1, const T& f2) {
    Derived& u = self();
    if (!u.is_constant()) {
      if constexpr (Order == 2) {
        T scratch;
        u.for_each_second([&](T& h, int i, int j) {
          h *= f1;
          scratch = u.gradient[i];
          scratch *= u.gradient[j];
          scratch *= f2;
          h += scratch;
        });
      } else {
        (void)f2;
      }
      for (auto& g : u.gradient) g *= f1;
    }
    u.value = f0;
    return u;
  }
  Derived chain(const T& f0, const T& f1, const T& f2) const {
    Derived r = self();
    r.apply_chain(f0, f1, f2);
    return r;
  }

  // a / b = a · (1/b), with (1/u)' = −1/u², (1/u)'' = 2/u³.
  Derived& operator/=(const Derived& b) {
    T inverse = 1 / b.value;
    return self() *= b.chain(inverse, -inverse * inverse, 2 * inverse * inverse * inverse);
  }
  Derived& operator*=(const T& c) {
    Derived& u = self();
    u.value *= c;
    for (auto& g : u.gradient) g *= c;
    for (auto& h : u.hessian) h *= c;
    return u;
  }
  Derived& operator/=(const T& c) {
    Derived& u = self();
    u.value /= c;
    for (auto& g : u.gradient) g /= c;
    for (auto& h : u.hessian) h /= c;
    return u;
  }
  Derived operator-() const {
    Derived r = self();
    r *= T(-1);
    return r;
  }

 protected:
  // (ab)'' = a b'' + b a'' + a' b'ᵀ + b' a'ᵀ, in place, for a and b (not the same jet) both
  // with derivatives: the Hessian first (it reads the old value and gradient), then the
  // gradient, then the value.
  void multiply_by(const Derived& b) {
    Derived& a = self();
    T scratch, term;
    if constexpr (Order == 2)
      a.for_each_second([&](T& h, int i, int j) {
        h *= b.value;
        scratch = a.value;
        scratch *= b.second(i, j);
        h += scratch;
        scratch = a.gradient[i];
        scratch *= b.gradient[j];
        term = b.gradient[i];
        term *= a.gradient[j];
        scratch += term;
        h += scratch;
      });
    for (std::size_t i = 0; i < a.gradient.size(); ++i) {
      a.gradient[i] *= b.value;
      scratch = a.value;
      scratch *= b.gradient[i];
      a.gradient[i] += scratch;
    }
    a.value *= b.value;
  }

 private:
  Derived& self() { return static_cast<Derived&>(*this); }
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

template <class T, int N, int Order = 2, int Split = 0>
struct Jet : JetArithmetic<Jet<T, N, Order, Split>, T, Order> {
  static_assert(Order == 1 || Order == 2, "Jet: derivatives of order 1 or 2");
  static_assert(Split == 0 || (Order == 2 && 0 < Split && Split < N),
                "Jet: a block Hessian splits 0 < s < N");
  static constexpr int hessian_size = Order == 2 ? (Split ? Split * (N - Split) : N * N) : 0;
  T value = 0;
  std::array<T, N> gradient{};
  // Order 2: row-major and symmetric, or (Split) the block i < s ≤ j, row-major.
  std::array<T, hessian_size> hessian{};

  Jet() { clear_derivatives(); }
  Jet(const T& constant) : value(constant) { clear_derivatives(); }  // NOLINT: constants promote
  template <class I, std::enable_if_t<std::is_integral_v<I>, int> = 0>
  Jet(I constant) : value(constant) {  // NOLINT
    clear_derivatives();
  }

  // A floating-point constant as another library writes it (odeint's 1.0): converted to T exactly
  // when T has at least its precision; vivv's own code writes T(1) / 2 instead.
  template <class F, std::enable_if_t<std::is_floating_point_v<F> && !std::is_same_v<F, T>, int> = 0>
  Jet(F constant) : value(constant) {  // NOLINT
    clear_derivatives();
  }

  // The independent variable number `index` at `at` (of `size` variables: N, for a fixed jet).
  static Jet variable(const T& at, int index, int size = N) {
    (void)size;
    Jet x(at);
    x.gradient[index] = 1;
    return x;
  }
  // A fixed jet always has its N derivatives.
  void ensure_size(int) {}

  // Where ∂²/∂x_i∂x_j is kept: with Split, i < s ≤ j (or the mirror, j < s ≤ i).
  static constexpr int index(int i, int j) {
    if constexpr (Split == 0)
      return i * N + j;
    else
      return i < j ? i * (N - Split) + (j - Split) : j * (N - Split) + (i - Split);
  }
  const T& second(int i, int j) const { return hessian[index(i, j)]; }

  // f(h, i, j) for every Hessian entry the jet computes: the upper triangle (then mirrored into
  // the lower), or the block i < s ≤ j.
  template <class F>
  void for_each_second(F&& f) {
    if constexpr (Split == 0) {
      for (int i = 0; i < N; ++i)
        for (int j = i; j < N; ++j) {
          T& h = hessian[i * N + j];
          f(h, i, j);
          if (j != i) hessian[j * N + i] = h;
        }
    } else {
      for (int i = 0; i < Split; ++i)
        for (int j = Split; j < N; ++j) f(hessian[i * (N - Split) + (j - Split)], i, j);
    }
  }

  void clear_derivatives() {
    gradient.fill(T(0));
    hessian.fill(T(0));
  }

  using Base = JetArithmetic<Jet, T, Order>;
  using Base::operator*=;
  using Base::operator/=;
  static constexpr bool is_constant() { return false; }  // a fixed jet always has its N derivatives

  Jet& operator+=(const Jet& b) {
    value += b.value;
    for (int i = 0; i < N; ++i) gradient[i] += b.gradient[i];
    for (int i = 0; i < hessian_size; ++i) hessian[i] += b.hessian[i];
    return *this;
  }
  Jet& operator-=(const Jet& b) {
    value -= b.value;
    for (int i = 0; i < N; ++i) gradient[i] -= b.gradient[i];
    for (int i = 0; i < hessian_size; ++i) hessian[i] -= b.hessian[i];
    return *this;
  }
  Jet& operator*=(const Jet& b) {
    if (&b == this) {
      const Jet copy = b;
      return *this *= copy;
    }
    this->multiply_by(b);
    return *this;
  }
};

// A jet over a number of variables known at run time (a system of any_size coordinates): the
// gradient and Hessian on the heap, empty for a constant (every derivative 0), sized by the
// first variable an operation meets. It keeps the whole Hessian whatever Split asks: Split only
// saves work, and the entries a split jet keeps are the full Hessian's. The arithmetic is the
// fixed jet's, operation for operation, so both give the same numbers.
template <class T, int Order, int Split>
struct Jet<T, any_size, Order, Split> : JetArithmetic<Jet<T, any_size, Order, Split>, T, Order> {
  using Base = JetArithmetic<Jet, T, Order>;
  using Base::operator*=;
  using Base::operator/=;
  static_assert(Order == 1 || Order == 2, "Jet: derivatives of order 1 or 2");
  T value = 0;
  std::vector<T> gradient;  // empty: a constant
  std::vector<T> hessian;   // Order 2: size() × size(), row-major and symmetric; empty: a constant

  Jet() = default;
  Jet(const T& constant) : value(constant) {}  // NOLINT: constants promote
  template <class I, std::enable_if_t<std::is_integral_v<I>, int> = 0>
  Jet(I constant) : value(constant) {}  // NOLINT
  template <class F, std::enable_if_t<std::is_floating_point_v<F> && !std::is_same_v<F, T>, int> = 0>
  Jet(F constant) : value(constant) {}  // NOLINT

  int size() const { return static_cast<int>(gradient.size()); }
  bool is_constant() const { return gradient.empty(); }

  static Jet variable(const T& at, int index, int size) {
    Jet x(at);
    x.ensure_size(size);
    x.gradient[index] = 1;
    return x;
  }
  // A constant given its `size` derivatives (zeros), so that they can be read.
  void ensure_size(int size) {
    if (!gradient.empty()) return;
    gradient.assign(size, T(0));
    if constexpr (Order == 2) hessian.assign(static_cast<std::size_t>(size) * size, T(0));
  }

  const T& second(int i, int j) const { return hessian[static_cast<std::size_t>(i) * size() + j]; }

  template <class F>
  void for_each_second(F&& f) {
    const int n = size();
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) {
        T& h = hessian[static_cast<std::size_t>(i) * n + j];
        f(h, i, j);
        if (j != i) hessian[static_cast<std::size_t>(j) * n + i] = h;
      }
  }

  Jet& operator+=(const Jet& b) {
    value += b.value;
    if (b.is_constant()) return *this;
    if (is_constant()) {
      gradient = b.gradient, hessian = b.hessian;
      return *this;
    }
    for (std::size_t i = 0; i < gradient.size(); ++i) gradient[i] += b.gradient[i];
    for (std::size_t i = 0; i < hessian.size(); ++i) hessian[i] += b.hessian[i];
    return *this;
  }
  Jet& operator-=(const Jet& b) {
    value -= b.value;
    if (b.is_constant()) return *this;
    ensure_size(b.size());
    for (std::size_t i = 0; i < gradient.size(); ++i) gradient[i] -= b.gradient[i];
    for (std::size_t i = 0; i < hessian.size(); ++i) hessian[i] -= b.hessian[i];
    return *this;
  }
  Jet& operator*=(const Jet& b) {
    if (&b == this) {
      const Jet copy = b;
      return *this *= copy;
    }
    if (b.is_constant()) return *this *= b.value;
    if (is_constant()) {
      const T a = value;
      *this = b;
      return *this *= a;
    }
    this->multiply_by(b);
    return *this;
  }
};

// `jet` with its `size` derivatives readable: a dynamic jet that came out constant gets zeros.
template <class J>
J with_size(J jet, int size) {
  jet.ensure_size(size);
  return jet;
}

template <class T>
struct is_jet : std::false_type {};
template <class T, int N, int Order, int Split>
struct is_jet<Jet<T, N, Order, Split>> : std::true_type {};

// The scalar at the leaves of nested jets: T for T, Jet<T, N> and Jet<Jet<T, N>, M>.
template <class S>
struct leaf_scalar {
  using type = S;
};
template <class T, int N, int Order, int Split>
struct leaf_scalar<Jet<T, N, Order, Split>> {
  using type = typename leaf_scalar<T>::type;
};
template <class S>
using leaf_scalar_t = typename leaf_scalar<S>::type;

// Binary operators between jets.
#define VIVV_JET_BINARY(op)                                                  \
  template <class T, int N, int O, int B>                                    \
  Jet<T, N, O, B> operator op(Jet<T, N, O, B> a, const Jet<T, N, O, B>& b) { \
    return a op## = b;                                                       \
  }
VIVV_JET_BINARY(+)
VIVV_JET_BINARY(-)
VIVV_JET_BINARY(*)
VIVV_JET_BINARY(/)
#undef VIVV_JET_BINARY

// Between a jet and a constant c (anything that converts to its scalar: T, int): a constant
// has no derivatives, so c ± u and c·u act on the value or scale, and c / u is one chain rule.
template <class T, class U>
inline constexpr bool is_jet_constant_v = std::is_convertible_v<U, T> && !is_jet<U>::value;
#define VIVV_JET_CONSTANT                          \
  template <class T, int N, int O, int B, class U, \
            std::enable_if_t<is_jet_constant_v<T, U>, int> = 0>
VIVV_JET_CONSTANT Jet<T, N, O, B> operator+(Jet<T, N, O, B> a, const U& c) {
  a.value += T(c);
  return a;
}
VIVV_JET_CONSTANT Jet<T, N, O, B> operator+(const U& c, Jet<T, N, O, B> a) {
  return std::move(a) + c;
}
VIVV_JET_CONSTANT Jet<T, N, O, B> operator-(Jet<T, N, O, B> a, const U& c) {
  a.value -= T(c);
  return a;
}
VIVV_JET_CONSTANT Jet<T, N, O, B> operator-(const U& c, const Jet<T, N, O, B>& a) {
  Jet<T, N, O, B> r = -a;
  r.value += T(c);
  return r;
}
VIVV_JET_CONSTANT Jet<T, N, O, B> operator*(Jet<T, N, O, B> a, const U& c) { return a *= T(c); }
VIVV_JET_CONSTANT Jet<T, N, O, B> operator*(const U& c, Jet<T, N, O, B> a) { return a *= T(c); }
VIVV_JET_CONSTANT Jet<T, N, O, B> operator/(Jet<T, N, O, B> a, const U& c) { return a /= T(c); }
// c / u, with (c/u)' = −c/u², (c/u)'' = 2c/u³.
VIVV_JET_CONSTANT Jet<T, N, O, B> operator/(const U& c, const Jet<T, N, O, B>& a) {
  const T inverse = 1 / a.value, quotient = T(c) * inverse;
  return a.chain(quotient, -quotient * inverse, 2 * quotient * inverse * inverse);
}
#undef VIVV_JET_CONSTANT

// Elementary functions, each by its first and second derivative.
template <class T, int N, int O, int B>
Jet<T, N, O, B> sin(Jet<T, N, O, B> u) {
  using std::cos, std::sin;
  T s = sin(u.value), c = cos(u.value);
  u.apply_chain(s, c, -s);
  return u;
}
template <class T, int N, int O, int B>
Jet<T, N, O, B> cos(Jet<T, N, O, B> u) {
  using std::cos, std::sin;
  T s = sin(u.value), c = cos(u.value);
  u.apply_chain(c, -s, -c);
  return u;
}
template <class T, int N, int O, int B>
Jet<T, N, O, B> exp(Jet<T, N, O, B> u) {
  using std::exp;
  T e = exp(u.value);
  u.apply_chain(e, e, e);
  return u;
}
template <class T, int N, int O, int B>
Jet<T, N, O, B> log(Jet<T, N, O, B> u) {
  using std::log;
  T inverse = 1 / u.value;
  u.apply_chain(log(u.value), inverse, -inverse * inverse);
  return u;
}
template <class T, int N, int O, int B>
Jet<T, N, O, B> sqrt(Jet<T, N, O, B> u) {
  using std::sqrt;
  T s = sqrt(u.value);
  u.apply_chain(s, 1 / (2 * s), -1 / (4 * s * s * s));
  return u;
}
template <class T, int N, int O, int B>
Jet<T, N, O, B> atan(Jet<T, N, O, B> u) {
  using std::atan;
  T inverse = 1 / (1 + u.value * u.value);
  u.apply_chain(atan(u.value), inverse, -2 * u.value * inverse * inverse);
  return u;
}
// u^p for a constant exponent p (in T, or in the scalar under nested jets).
template <class T, int N, int O, int B, class P,
          std::enable_if_t<!is_jet<P>::value || std::is_same_v<P, T>, int> = 0>
Jet<T, N, O, B> pow(Jet<T, N, O, B> u, const P& p) {
  using std::pow;
  T f0 = pow(u.value, p);
  T f1 = p * pow(u.value, P(p - 1));
  T f2 = p * (p - 1) * pow(u.value, P(p - 2));
  u.apply_chain(f0, f1, f2);
  return u;
}

}  // namespace vivv
