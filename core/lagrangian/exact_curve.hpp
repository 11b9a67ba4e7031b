// The exact curve segment psi(h, t, v) = q(t) of the Euler–Lagrange solution
// through v (docs/theory.md (TQ), paper Definition 5.1), in any scalar S.
//
// The solution of x'' = a(x, x') through (x_0, v_0) is covered, on a time
// interval [t_begin, t_end] around 0, by Taylor pieces: on each piece
// x(start + τ) = Σ_{k<=p+1} x_k τ^k with the normalized coefficients of
// core/lagrangian/taylor_curve.hpp, computed in S (T or nested jets), so psi and
// everything built on it differentiates exactly with respect to (x_0, v_0).
// Order and piece length follow Jorba & Zou (2005) as the reference flow does
// (references/taylor_flow.hpp):
//   p = ⌈−ln(tol)/2 + 1⌉,   length = ρ e^{−2} e^{−0.7/(p−1)},
//   ρ = min((s/‖y_{p−1}‖)^{1/(p−1)}, (s/‖y_p‖)^{1/p}),   s = max(1, ‖y_0‖),
// y_k = (x_k, (k+1) x_{k+1}) measured on the values (the leaves) of S. The
// pieces depend on v only through those values: a piece boundary is a
// constant, not a function to differentiate.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/autodiff/jet.hpp"
#include "core/numerics/scalar.hpp"
#include "core/autodiff/tape.hpp"
#include "core/lagrangian/taylor_curve.hpp"
#include "core/autodiff/taylor_expansion.hpp"  // taylor_order_for, jorba_zou_step

namespace vivv {


// The value of x at the leaves (its derivatives dropped).
template <class S>
const leaf_scalar_t<S>& leaf_value(const S& x) {
  if constexpr (is_jet<S>::value) {
    return leaf_value(x.value);
  } else {
    return x;
  }
}

template <class S, class T>
class ExactCurve {
 public:
  // The solution of the tape's x'' = a(x, x') through (x0, v0) on [t_begin, t_end] ∋ 0,
  // pieces at step tolerance `tolerance`.
  ExactCurve(const Tape<T>& tape, const std::vector<S>& x0, const std::vector<S>& v0,
             const T& t_begin, const T& t_end, const T& tolerance)
      : order_(taylor_order_for(tolerance)), dimension_(static_cast<int>(x0.size())) {
    if (!(t_begin <= 0 && 0 <= t_end))
      throw std::invalid_argument("ExactCurve: the interval must contain 0");
    Piece first = expand(tape, x0, v0, T(0));
    forward_.push_back(first);
    backward_.push_back(first);
    extend(tape, forward_, t_end, 1);
    extend(tape, backward_, t_begin, -1);
  }

  // x(t) and x'(t) for a constant t in [t_begin, t_end].
  void at(const T& t, std::vector<S>& x, std::vector<S>& v) const { evaluate(piece_at(t), t, x, v); }

  // The piece boundaries strictly between t_begin and t_end, increasing.
  std::vector<T> breakpoints(const T& t_begin, const T& t_end) const {
    std::vector<T> times;
    for (auto it = backward_.rbegin(); it != backward_.rend(); ++it)
      if (it->start > t_begin && it->start < 0) times.push_back(it->start);
    for (const Piece& piece : forward_)
      if (piece.start > 0 && piece.start < t_end) times.push_back(piece.start);
    return times;
  }

 private:
  struct Piece {
    T start;   // the time at τ = 0
    T length;  // how far it reaches from start (forward pieces ahead, backward ones behind)
    std::vector<std::vector<S>> coefficients;  // [component][k], k = 0..p+1
  };

  // x(t), x'(t) on `piece`: x = Σ_k c_k τ^k and x' = Σ_{k>=1} k c_k τ^(k−1), τ = t − start, by Horner.
  void evaluate(const Piece& piece, const T& t, std::vector<S>& x, std::vector<S>& v) const {
    const T tau = t - piece.start;
    x.assign(dimension_, S(0));
    v.assign(dimension_, S(0));
    const int degree = order_ + 1;
    for (int i = 0; i < dimension_; ++i) {
      const std::vector<S>& c = piece.coefficients[i];
      x[i] = c[degree];
      v[i] = taylor_curve_detail::scaled(c[degree], T(degree));
      for (int k = degree - 1; k >= 0; --k) {
        taylor_curve_detail::scale_in_place(x[i], tau);
        x[i] += c[k];
        if (k >= 1) {
          taylor_curve_detail::scale_in_place(v[i], tau);
          v[i] += taylor_curve_detail::scaled(c[k], T(k));
        }
      }
    }
  }

  // The piece starting at `start` through (x0, v0): its coefficients and its Jorba–Zou length.
  Piece expand(const Tape<T>& tape, const std::vector<S>& x0, const std::vector<S>& v0,
               const T& start) const {
    Piece piece{start, T(0), solution_taylor_coefficients<S, T>(tape, x0, v0, order_ + 1)};
    using taylor_detail::log_abs;
    const int p = order_;
    double log_state = 0, log_previous = -std::numeric_limits<double>::infinity(),
           log_last = log_previous;
    for (const std::vector<S>& c : piece.coefficients) {
      // y_k = (x_k, (k+1) x_{k+1}).
      auto log_y = [&](int k) {
        const double position = log_abs(leaf_value(c[k]));
        const double velocity = log_abs(T(leaf_value(c[k + 1]) * (k + 1)));
        constexpr double infinity = std::numeric_limits<double>::infinity();
        if (!(position < infinity) || !(velocity < infinity))  // NaN or ∞ (ln 0 = −∞ is fine)
          throw std::runtime_error(
              "ExactCurve: non-finite Taylor coefficients (the solution left the Lagrangian's domain "
              "or its mass matrix became singular)");
        return std::max(position, velocity);
      };
      log_state = std::max(log_state, log_y(0));
      log_previous = std::max(log_previous, log_y(p - 1));
      log_last = std::max(log_last, log_y(p));
    }
    double length = jorba_zou_step(log_state, log_previous, log_last, p);
    if (!std::isfinite(length))  // a polynomial solution: any length is exact
      length = 1;
    if (!(length > 0))
      throw std::runtime_error("ExactCurve: piece length underflow (Taylor coefficients too large)");
    piece.length = T(length);
    return piece;
  }

  // Pieces in `direction` until they cover `t_end`.
  void extend(const Tape<T>& tape, std::vector<Piece>& pieces, const T& t_end, int direction) {
    using std::abs;
    constexpr int max_pieces = 100000;
    while (abs(pieces.back().start) + pieces.back().length < abs(t_end)) {
      if (static_cast<int>(pieces.size()) >= max_pieces)
        throw std::runtime_error("ExactCurve: more than " + std::to_string(max_pieces) + " pieces");
      const Piece& last = pieces.back();
      T end = last.start + direction * last.length;
      std::vector<S> x, v;
      evaluate(last, end, x, v);
      pieces.push_back(expand(tape, x, v, end));
    }
  }

  // The first piece, in the direction of t, whose reach covers t.
  const Piece& piece_at(const T& t) const {
    using std::abs;
    const std::vector<Piece>& pieces = t >= 0 ? forward_ : backward_;
    for (const Piece& piece : pieces)
      if (abs(t) <= abs(piece.start) + piece.length) return piece;
    throw std::out_of_range("ExactCurve: t = " + to_decimal<T>(t) + " is outside the curve");
  }

  int order_;
  int dimension_;
  std::vector<Piece> forward_, backward_;
};

}  // namespace vivv
