// Discretizations of TQ (psi, alpha+, alpha−) and of the Lagrangian system on
// them (docs/theory.md (TQ); paper Definitions 4.1, 4.3).
//
// A curve segment psi(h, t, v) passes through v = (q, w) at t = 0; the
// boundary maps are d−(v) = psi(h, α−, v) and d+(v) = psi(h, α+, v) with
// α− = −θh, α+ = (1 − θ)h. The discrete Lagrangian L_h is a function on TQ.
// Everything is evaluated in a scalar S (T or jets over T), so derivatives
// with respect to v come from automatic differentiation.
#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/qxq/discrete_lagrangian.hpp"
#include "core/lagrangian/exact_curve.hpp"
#include "core/autodiff/small_linear_algebra.hpp"
#include "core/lagrangian/state.hpp"
#include "core/autodiff/tape.hpp"
#include "core/lagrangian/taylor_curve.hpp"

namespace vivv {

enum class CurveFamily {
  linear,  // psi = q + t·w
  taylor,  // psi = Σ_{k<=r} t^k/k! q^(k)(0), the solution through v to degree r
  exact,   // psi = q(t), the solution through v (core/lagrangian/exact_curve.hpp)
};

enum class TQLagrangianKind {
  quadrature,  // L_h(v) = ∫_{α−}^{α+} L(psi, dpsi/dt) dt by m-point Gauss–Legendre
  pullback,    // L_h(v) = L_d(d−(v), d+(v); h) for a Q×Q discrete Lagrangian (paper §6)
  exact,       // L_h(v) = ∫_{α−}^{α+} L(psi, dpsi/dt) dt to the curve's tolerance: Gauss–Legendre
               // on every Taylor piece of the exact psi (paper Definition 5.1)
};

template <class T>
struct TQDiscretization {
  CurveFamily psi = CurveFamily::linear;
  int r = 1;  // degree of the taylor family
  // a(q, w) = M⁻¹ (dL/dq − (d²L/dw dq) w), recorded once (core/lagrangian/euler_lagrange_tape.hpp): taylor, exact.
  std::shared_ptr<const Tape<T>> acceleration;
  T curve_tolerance = 0;  // step tolerance of the exact psi's Taylor pieces
  T theta = 0;  // α− = −θh, α+ = (1 − θ)h
  TQLagrangianKind lagrangian = TQLagrangianKind::quadrature;
  std::vector<T> nodes, weights;  // Gauss–Legendre on [0, 1], weights summing to 1 (quadrature;
                                  // exact: the rule used on each Taylor piece)
  QxQDiscretization<T> qxq;       // the Q×Q discrete Lagrangian (pullback)
  std::optional<TwinTerm<T>> twin;  // + a·h^s·(d+(v) − d−(v))
};

// A point of TQ in scalar S.
template <class S, int n>
struct TangentPoint {
  Coordinates<S, n> q, w;
};

// A point of TQ with `size` coordinates (value-initialized).
template <class S, int n>
TangentPoint<S, n> make_tangent_point(int size) {
  return {make_point<S, n>(size), make_point<S, n>(size)};
}

// The state v = (q, w) as a point of TQ.
template <class T, int n>
TangentPoint<T, n> tangent_point(const State<T, n>& v) {
  return {as_point<T, n>(v.q), as_point<T, n>(v.w)};
}

// The curve segment t ↦ psi(h, t, v) through v, for t in [α−, α+]: linear and
// taylor-r as the polynomial psi = Σ_k c_k t^k with (c_0, c_1) = (q, w) (linear)
// or c_k = q^(k)(0)/k!, k <= r, by Taylor-mode AD of the Euler–Lagrange
// acceleration (taylor-r, core/lagrangian/taylor_curve.hpp); exact as the Taylor pieces of
// the solution through v (core/lagrangian/exact_curve.hpp). In scalar S; built once per
// (v, h), at(t) evaluates it as often as needed.
template <class S, int n>
class CurveSegment {
 public:
  using Leaf = leaf_scalar_t<S>;

  template <class T>
  CurveSegment(const TQDiscretization<T>& d, const TangentPoint<S, n>& v, const T& h)
      : alpha_minus_(-d.theta * h), alpha_plus_((1 - d.theta) * h), size_(static_cast<int>(v.q.size())) {
    switch (d.psi) {
      case CurveFamily::exact: {
        if (!d.acceleration)
          throw std::logic_error(
              "curve_segment: psi exact needs the Euler–Lagrange tape (acceleration)");
        std::vector<S> q(v.q.begin(), v.q.end()), w(v.w.begin(), v.w.end());
        using std::max;
        using std::min;
        exact_ = std::make_shared<const ExactCurve<S, T>>(*d.acceleration, q, w, min(T(0), alpha_minus_),
                                                          max(T(0), alpha_plus_), d.curve_tolerance);
        return;
      }
      case CurveFamily::linear:
        position_ = {v.q, v.w};
        break;
      case CurveFamily::taylor: {
        if (!d.acceleration)
          throw std::logic_error(
              "curve_segment: psi taylor needs the Euler–Lagrange tape (acceleration)");
        std::vector<S> q(v.q.begin(), v.q.end()), w(v.w.begin(), v.w.end());
        auto series = solution_taylor_coefficients<S, T>(*d.acceleration, q, w, d.r);
        position_.assign(d.r + 1, make_point<S, n>(size_));
        for (int k = 0; k <= d.r; ++k)
          for (int i = 0; i < size_; ++i) position_[k][i] = std::move(series[i][k]);
        break;
      }
    }
    // dpsi/dt = Σ_{k>=1} k c_k t^(k−1).
    for (std::size_t k = 1; k < position_.size(); ++k) {
      velocity_.push_back(position_[k]);
      if (k > 1)
        for (auto& component : velocity_.back())
          taylor_curve_detail::scale_in_place(component, T(static_cast<int>(k)));
    }
  }

  // (psi, dpsi/dt) = (Σ_k c_k t^k, Σ_{k>=1} k c_k t^(k−1)) by Horner, for t in S or in T
  // (a constant time in T multiplies leaf by leaf, much cheaper in nested jets).
  template <class U>
  TangentPoint<S, n> at(const U& t) const {
    TangentPoint<S, n> point = make_tangent_point<S, n>(size_);
    if (exact_) {
      if constexpr (std::is_same_v<U, Leaf>) {
        std::vector<S> q, w;
        exact_->at(t, q, w);
        for (int i = 0; i < size_; ++i) point.q[i] = std::move(q[i]), point.w[i] = std::move(w[i]);
        return point;
      } else {
        throw std::logic_error("curve_segment: psi exact is evaluated at constant times only");
      }
    }
    point.q = horner(position_, t);
    point.w = horner(velocity_, t);
    return point;
  }

  // The times in (α−, α+) where psi is not one polynomial: the exact psi's piece boundaries.
  std::vector<Leaf> breakpoints() const {
    return exact_ ? exact_->breakpoints(alpha_minus_, alpha_plus_) : std::vector<Leaf>{};
  }

 private:
  // Σ_k p_k t^k, component by component.
  template <class U>
  static Coordinates<S, n> horner(const std::vector<Coordinates<S, n>>& p, const U& t) {
    if (p.empty()) throw std::logic_error("curve_segment: psi exact has no single polynomial");
    Coordinates<S, n> sum = p.back();
    for (int k = static_cast<int>(p.size()) - 2; k >= 0; --k) {
      for (std::size_t i = 0; i < sum.size(); ++i) {
        if constexpr (std::is_same_v<U, S>) {
          sum[i] = sum[i] * t;
        } else {
          taylor_curve_detail::scale_in_place(sum[i], t);
        }
        sum[i] += p[k][i];
      }
    }
    return sum;
  }

  Leaf alpha_minus_, alpha_plus_;
  int size_;  // the number of coordinates
  std::vector<Coordinates<S, n>> position_;  // c_0 … c_degree (linear, taylor)
  std::vector<Coordinates<S, n>> velocity_;  // k c_k, k = 1 … degree
  std::shared_ptr<const ExactCurve<S, Leaf>> exact_;  // exact
};

// psi(h, t, v) and dpsi/dt: linear (q + t·w, w); taylor-r the degree-r Taylor
// polynomial of the solution through v and its derivative; exact the solution.
template <class S, int n, class T>
TangentPoint<S, n> curve_segment(const TQDiscretization<T>& d, const TangentPoint<S, n>& v,
                                 const T& h, const S& t) {
  return CurveSegment<S, n>(d, v, h).at(t);
}

// d−(v) = psi(h, α−, v), on a curve segment already built through v.
template <class S, int n, class T>
Coordinates<S, n> d_minus(const TQDiscretization<T>& d, const CurveSegment<S, n>& curve, const T& h) {
  return curve.at(T(-d.theta * h)).q;
}

// d+(v) = psi(h, α+, v), on a curve segment already built through v.
template <class S, int n, class T>
Coordinates<S, n> d_plus(const TQDiscretization<T>& d, const CurveSegment<S, n>& curve, const T& h) {
  return curve.at(T((1 - d.theta) * h)).q;
}

// d−(v) = psi(h, α−, v).
template <class S, int n, class T>
Coordinates<S, n> d_minus(const TQDiscretization<T>& d, const TangentPoint<S, n>& v, const T& h) {
  return d_minus<S, n>(d, CurveSegment<S, n>(d, v, h), h);
}

// d+(v) = psi(h, α+, v).
template <class S, int n, class T>
Coordinates<S, n> d_plus(const TQDiscretization<T>& d, const TangentPoint<S, n>& v, const T& h) {
  return d_plus<S, n>(d, CurveSegment<S, n>(d, v, h), h);
}

// The blown-up discrete Lagrangian L̂_h(v) = L_h(v)/h (paper §2.4, stage 1), on
// the curve segment through v:
// quadrature: Σ_i b_i L(psi(α− + c_i h), dpsi/dt(α− + c_i h));
// exact: the same rule on every Taylor piece [a, b] of the exact psi, weighted by (b − a)/h;
// pullback: L_d(d−(v), d+(v); h)/h; twin term: + a·h^(s−1)·(d+(v) − d−(v)).
template <LagrangianSystem System, class S>
S blown_up_lagrangian(const System& system, const TQDiscretization<typename System::Scalar>& d,
                      const CurveSegment<S, System::dimension>& curve,
                      const typename System::Scalar& h) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  S value = S(0);
  switch (d.lagrangian) {
    case TQLagrangianKind::quadrature:
      for (std::size_t i = 0; i < d.nodes.size(); ++i) {
        T t = -d.theta * h + d.nodes[i] * h;
        auto point = curve.at(t);
        value += d.weights[i] * system.lagrangian(point.q, point.w);
      }
      break;
    case TQLagrangianKind::exact: {
      std::vector<T> ends{T(-d.theta * h)};
      for (const T& t : curve.breakpoints()) ends.push_back(t);
      ends.push_back(T((1 - d.theta) * h));
      for (std::size_t piece = 0; piece + 1 < ends.size(); ++piece) {
        const T length = ends[piece + 1] - ends[piece];
        for (std::size_t i = 0; i < d.nodes.size(); ++i) {
          auto point = curve.at(T(ends[piece] + d.nodes[i] * length));
          value += T(d.weights[i] * length / h) * system.lagrangian(point.q, point.w);
        }
      }
      break;
    }
    case TQLagrangianKind::pullback:
      value = discrete_lagrangian(system, d.qxq, d_minus<S, N>(d, curve, h),
                                  d_plus<S, N>(d, curve, h), h) / h;
      break;
  }
  if (d.twin) {
    using std::pow;
    T scale = pow(h, d.twin->power - 1);
    auto minus = d_minus<S, N>(d, curve, h);
    auto plus = d_plus<S, N>(d, curve, h);
    for (std::size_t i = 0; i < minus.size(); ++i) value += scale * d.twin->a[i] * (plus[i] - minus[i]);
  }
  return value;
}

// L̂_h(v) = L_h(v)/h as above, building the curve segment through v.
template <LagrangianSystem System, class S>
S blown_up_lagrangian(const System& system, const TQDiscretization<typename System::Scalar>& d,
                      const TangentPoint<S, System::dimension>& v, const typename System::Scalar& h) {
  return blown_up_lagrangian(system, d, CurveSegment<S, System::dimension>(d, v, h), h);
}

// The TQ discrete Legendre transforms at v (docs/theory.md (TQ)), with N∓ = [−A⁻¹B; I]
// spanning ker Dd∓ (A = ∂d∓/∂q, B = ∂d∓/∂w):
//   ((Dd+ N−)/h)ᵀ P+ =  N−ᵀ ∇L̂_h(v),
//   ((Dd− N+)/h)ᵀ P− = −N+ᵀ ∇L̂_h(v).
template <class S, int n>
struct TQLegendre {
  Coordinates<S, n> d_minus, d_plus, p_plus, p_minus;
};

template <LagrangianSystem System, class S>
TQLegendre<S, System::dimension> tq_legendre(const System& system,
                                             const TQDiscretization<typename System::Scalar>& d,
                                             const TangentPoint<S, System::dimension>& v,
                                             const typename System::Scalar& h) {
  constexpr int N = System::dimension;
  const int n = static_cast<int>(v.q.size());
  using J = Jet<S, twice(N), 1>;  // first derivatives only
  TangentPoint<J, N> jet_v = make_tangent_point<J, N>(n);
  for (int i = 0; i < n; ++i) {
    jet_v.q[i] = J::variable(v.q[i], i, 2 * n);
    jet_v.w[i] = J::variable(v.w[i], n + i, 2 * n);
  }
  const CurveSegment<J, N> curve(d, jet_v, h);
  J lagrangian = with_size(blown_up_lagrangian(system, d, curve, h), 2 * n);
  Coordinates<J, N> minus = d_minus<J, N>(d, curve, h), plus = d_plus<J, N>(d, curve, h);
  for (auto& x : minus) x.ensure_size(2 * n);
  for (auto& x : plus) x.ensure_size(2 * n);
  // Blocks of Dd− = [A B] and Dd+ = [C D].
  SmallMatrix<S, N, N> a = make_small_matrix<S, N, N>(n, n), b = a, c = a, dd = a;
  SmallVector<S, N> gradient_q = make_small_vector<S, N>(n), gradient_w = gradient_q;
  for (int i = 0; i < n; ++i) {
    gradient_q[i] = lagrangian.gradient[i];
    gradient_w[i] = lagrangian.gradient[n + i];
    for (int j = 0; j < n; ++j) {
      a[i][j] = minus[i].gradient[j];
      b[i][j] = minus[i].gradient[n + j];
      c[i][j] = plus[i].gradient[j];
      dd[i][j] = plus[i].gradient[n + j];
    }
  }
  // N− = [−A⁻¹B; I]: Dd+ N− = D − C A⁻¹B and N−ᵀ∇L̂ = ∇_w L̂ − (A⁻¹B)ᵀ ∇_q L̂.
  auto kernel_minus = solve_columns<S, N, N>(a, b);
  auto kernel_plus = solve_columns<S, N, N>(c, dd);
  auto c_kernel = multiply<S, N, N, N>(c, kernel_minus);
  auto a_kernel = multiply<S, N, N, N>(a, kernel_plus);
  SmallMatrix<S, N, N> k_plus = make_small_matrix<S, N, N>(n, n), k_minus = k_plus;
  SmallVector<S, N> rhs_plus = make_small_vector<S, N>(n), rhs_minus = rhs_plus;
  for (int i = 0; i < n; ++i) {
    rhs_plus[i] = gradient_w[i];
    rhs_minus[i] = -gradient_w[i];
    for (int j = 0; j < n; ++j) {
      k_plus[i][j] = (dd[i][j] - c_kernel[i][j]) / h;
      k_minus[i][j] = (b[i][j] - a_kernel[i][j]) / h;
      rhs_plus[i] -= kernel_minus[j][i] * gradient_q[j];
      rhs_minus[i] += kernel_plus[j][i] * gradient_q[j];
    }
  }
  TQLegendre<S, N> result;
  result.p_plus = solve<S, N>(transpose<S, N, N>(k_plus), rhs_plus);
  result.p_minus = solve<S, N>(transpose<S, N, N>(k_minus), rhs_minus);
  result.d_minus = make_point<S, N>(n), result.d_plus = make_point<S, N>(n);
  for (int i = 0; i < n; ++i) {
    result.d_minus[i] = minus[i].value;
    result.d_plus[i] = plus[i].value;
  }
  return result;
}

}  // namespace vivv
