// Taylor coefficients of the Euler–Lagrange solution in any scalar S (the
// taylor-r curve segments of docs/theory.md (TQ)).
//
// For x'' = a(x, x') in R^m with a recorded on a Tape (core/lagrangian/euler_lagrange_tape.hpp
// records it from the system's generic L), the solution through (x_0, v_0) has
// the normalized coefficients x_k = x^(k)(0)/k!:
//   x_{k+1} = v_k / (k+1),   v_{k+1} = a_k / (k+1),
// a_k the k-th coefficient of a(x(t), x'(t)), computed node by node with the
// power-series recurrences listed in core/autodiff/taylor_expansion.hpp (Griewank &
// Walther §13.2). TaylorExpansion runs them in T on raw MPFR storage; here
// they are written once for any scalar S — T, Jet<T, 2n> or
// Jet<Jet<T, 2n>, 2n> — so the coefficients, and psi built from them, can be
// differentiated exactly with respect to (x_0, v_0). Coefficients up to x_r
// need a_0 … a_{r−2}: O(r² · nodes) operations in S.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/autodiff/jet.hpp"
#include "core/autodiff/tape.hpp"

namespace vivv {

namespace taylor_curve_detail {

// x ← x · c for a constant c in T, leaf by leaf through nested jets (no temporaries).
template <class S, class T>
void scale_in_place(S& x, const T& c) {
  if constexpr (is_jet<S>::value) {
    scale_in_place(x.value, c);
    for (auto& g : x.gradient) scale_in_place(g, c);
    for (auto& h : x.hessian) scale_in_place(h, c);
  } else {
    x *= c;
  }
}

// x ← x / c for a constant c in T, leaf by leaf through nested jets.
template <class S, class T>
void divide_in_place(S& x, const T& c) {
  if constexpr (is_jet<S>::value) {
    divide_in_place(x.value, c);
    for (auto& g : x.gradient) divide_in_place(g, c);
    for (auto& h : x.hessian) divide_in_place(h, c);
  } else {
    x /= c;
  }
}

// x · c for a constant c in T.
template <class S, class T>
S scaled(S x, const T& c) {
  scale_in_place(x, c);
  return x;
}

// x / c for a constant c in T.
template <class S, class T>
S divided(S x, const T& c) {
  divide_in_place(x, c);
  return x;
}

// x^α for a constant exponent α in T, through nested jets:
// (x^α)' = α x^(α−1), (x^α)'' = α(α−1) x^(α−2).
template <class S, class T>
S constant_power(const S& x, const T& alpha) {
  if constexpr (is_jet<S>::value) {
    using Inner = std::decay_t<decltype(x.value)>;
    Inner f0 = constant_power(x.value, alpha);
    Inner f1 = alpha * constant_power(x.value, T(alpha - 1));
    Inner f2 = alpha * (alpha - 1) * constant_power(x.value, T(alpha - 2));
    return x.chain(f0, f1, f2);
  } else {
    using std::pow;
    return pow(x, S(alpha));
  }
}

// Σ_{j=from..to} weight(j) · a[j] · b[total − j], weight(j) = j when `weighted`, else 1.
template <class S, class T>
S convolution(const std::vector<S>& a, const std::vector<S>& b, int from, int to, int total,
              bool weighted) {
  S sum = S(0);
  for (int j = from; j <= to; ++j) {
    S term = a[j] * b[total - j];
    if (weighted) scale_in_place(term, T(j));
    sum += term;
  }
  return sum;
}

}  // namespace taylor_curve_detail

// x_k = x^(k)(0)/k! for k = 0..order of the solution of x'' = a(x, x') through
// (x0, v0), a on `tape` (inputs (x, v), outputs a): component i's coefficients
// in result[i].
template <class S, class T>
std::vector<std::vector<S>> solution_taylor_coefficients(const Tape<T>& tape,
                                                         const std::vector<S>& x0,
                                                         const std::vector<S>& v0, int order) {
  using std::cos;
  using std::exp;
  using std::log;
  using std::sin;
  using std::sqrt;
  using taylor_curve_detail::convolution;
  using taylor_curve_detail::divided;
  using taylor_curve_detail::scaled;
  const int m = tape.inputs / 2;
  if (tape.inputs != 2 * m || static_cast<int>(tape.outputs.size()) != m)
    throw std::invalid_argument(
        "solution_taylor_coefficients: the tape must map (x, v) in R^2m to a in R^m");
  if (static_cast<int>(x0.size()) != m || static_cast<int>(v0.size()) != m)
    throw std::invalid_argument("solution_taylor_coefficients: expected " + std::to_string(m) +
                                " components of x0 and v0");
  if (order < 1)
    throw std::invalid_argument("solution_taylor_coefficients: order must be at least 1");
  const int count = static_cast<int>(tape.nodes.size());
  // c[node][k]: the k-th coefficient of every node; nodes 0..m−1 are x, m..2m−1 are v.
  std::vector<std::vector<S>> c(count, std::vector<S>(order + 1, S(0)));
  for (int i = 0; i < m; ++i) c[i][0] = x0[i], c[m + i][0] = v0[i];

  // The k-th coefficient of node `index` from the coefficients 0..k of its operands.
  auto node_coefficient = [&](int index, int k) {
    const TapeNode& node = tape.nodes[index];
    std::vector<S>& r = c[index];
    const bool unary = node.op != TapeOp::input && node.op != TapeOp::constant;
    const std::vector<S>& u = unary ? c[node.a] : r;
    const std::vector<S>& w = node.b >= 0 ? c[node.b] : r;
    const T constant = node.c >= 0 ? tape.constants[node.c] : T(0);
    switch (node.op) {
      case TapeOp::input:
        return;
      case TapeOp::constant:
        r[k] = k == 0 ? S(constant) : S(0);
        return;
      case TapeOp::add:
        r[k] = u[k] + w[k];
        return;
      case TapeOp::sub:
        r[k] = u[k] - w[k];
        return;
      case TapeOp::neg:
        r[k] = -u[k];
        return;
      // (u·w)_k = Σ_{j=0..k} u_j w_{k−j}
      case TapeOp::mul:
        r[k] = convolution<S, T>(u, w, 0, k, k, false);
        return;
      case TapeOp::square:
        r[k] = convolution<S, T>(u, u, 0, k, k, false);
        return;
      // (u/w)_k = (u_k − Σ_{j=1..k} w_j r_{k−j}) / w_0
      case TapeOp::div:
        r[k] = (u[k] - convolution<S, T>(w, r, 1, k, k, false)) / w[0];
        return;
      case TapeOp::add_constant:
        r[k] = k == 0 ? S(u[0] + S(constant)) : u[k];
        return;
      case TapeOp::constant_minus:
        r[k] = k == 0 ? S(S(constant) - u[0]) : S(-u[k]);
        return;
      case TapeOp::scale:
        r[k] = scaled(u[k], constant);
        return;
      // (c/u)_k = −(Σ_{j=1..k} u_j r_{k−j}) / u_0 for k ≥ 1
      case TapeOp::constant_div:
        r[k] = k == 0 ? S(S(constant) / u[0]) : S(-convolution<S, T>(u, r, 1, k, k, false) / u[0]);
        return;
      // s_k = (1/k) Σ_{j=1..k} j u_j c_{k−j},  c_k = −(1/k) Σ_{j=1..k} j u_j s_{k−j}
      case TapeOp::sin: {
        std::vector<S>& partner = c[index + 1];
        if (k == 0) {
          r[0] = sin(u[0]);
          partner[0] = cos(u[0]);
          return;
        }
        S sine = divided(convolution<S, T>(u, partner, 1, k, k, true), T(k));
        partner[k] = divided(convolution<S, T>(u, r, 1, k, k, true), T(-k));
        r[k] = sine;
        return;
      }
      case TapeOp::cos:
        return;  // computed with its sin partner
      // e_k = (1/k) Σ_{j=1..k} j u_j e_{k−j}
      case TapeOp::exp:
        r[k] = k == 0 ? S(exp(u[0])) : divided(convolution<S, T>(u, r, 1, k, k, true), T(k));
        return;
      // l_k = (u_k − (1/k) Σ_{j=1..k−1} j l_j u_{k−j}) / u_0
      case TapeOp::log:
        r[k] = k == 0
                   ? S(log(u[0]))
                   : S((u[k] - divided(convolution<S, T>(r, u, 1, k - 1, k, true), T(k))) / u[0]);
        return;
      // t_k = (u_k − (1/k) Σ_{j=1..k−1} j t_j d_{k−j}) / d_0, d = 1 + u² the node b
      case TapeOp::atan: {
        using std::atan;
        r[k] = k == 0
                   ? S(atan(u[0]))
                   : S((u[k] - divided(convolution<S, T>(r, w, 1, k - 1, k, true), T(k))) / w[0]);
        return;
      }
      // r_k = (u_k − Σ_{j=1..k−1} r_j r_{k−j}) / (2 r_0)
      case TapeOp::sqrt:
        r[k] = k == 0
                   ? S(sqrt(u[0]))
                   : S((u[k] - convolution<S, T>(r, r, 1, k - 1, k, false)) / scaled(r[0], T(2)));
        return;
      // v_k = (α Σ_{j=0..k−1} (k−j) u_{k−j} v_j − Σ_{j=1..k−1} j v_j u_{k−j}) / (k u_0)
      case TapeOp::pow: {
        if (k == 0) {
          r[0] = taylor_curve_detail::constant_power(u[0], constant);
          return;
        }
        S forward = S(0);
        for (int j = 0; j < k; ++j) forward += scaled(S(u[k - j] * r[j]), T(k - j));
        S numerator = scaled(forward, constant) - convolution<S, T>(r, u, 1, k - 1, k, true);
        r[k] = numerator / scaled(u[0], T(k));
        return;
      }
    }
  };

  for (int k = 0; k < order; ++k) {
    for (int i = 0; i < m; ++i) c[i][k + 1] = divided(c[m + i][k], T(k + 1));
    if (k + 1 == order) break;  // x_order needs v_{order−1} only
    for (int index = tape.inputs; index < count; ++index) node_coefficient(index, k);
    for (int i = 0; i < m; ++i) c[m + i][k + 1] = divided(c[tape.outputs[i]][k], T(k + 1));
  }
  c.resize(m);  // the coefficients of x
  return c;
}

}  // namespace vivv
