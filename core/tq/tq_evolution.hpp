// The discrete evolution F_h: v ↦ ṽ of a TQ discretization (docs/theory.md (TQ),
// paper Theorem 4.2), solved in blown-up form.
//
// (h, v, ṽ) is critical iff d+(v) = d−(ṽ) and P+(v) = P−(ṽ). With the unknowns
// z = (q̃ − q)/h and w̃ (the scaled difference of the configurations), the
// equations
//   (d−(q + h z, w̃) − d+(v))/h = 0,   P−(q + h z, w̃) − P+(v) = 0
// stay well conditioned as h → 0, where their solution is z = w̃ = w (F_0 is
// the identity): Newton starts there.
#pragma once

#include <functional>
#include <string>

#include "core/numerics/newton.hpp"
#include "core/lagrangian/state.hpp"
#include "core/tq/tq_discretization.hpp"

namespace vivv {

// The blown-up residual at the unknowns x = (z, w̃), in scalar S.
template <LagrangianSystem System, class P>
P tq_residual(const System& system, const TQDiscretization<typename System::Scalar>& d,
              const State<typename System::Scalar, System::dimension>& v,
              const TQLegendre<typename System::Scalar, System::dimension>& at_v, const P& x,
              const typename System::Scalar& h) {
  using S = typename P::value_type;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(v.q.size());
  TangentPoint<S, N> next = make_tangent_point<S, N>(n);
  for (int i = 0; i < n; ++i) {
    next.q[i] = v.q[i] + h * x[i];
    next.w[i] = x[n + i];
  }
  auto legendre = tq_legendre(system, d, next, h);
  Coordinates<S, twice(N)> residual = make_point<S, twice(N)>(2 * n);
  for (int i = 0; i < n; ++i) {
    residual[i] = (legendre.d_minus[i] - at_v.d_plus[i]) / h;
    residual[n + i] = legendre.p_minus[i] - at_v.p_plus[i];
  }
  return residual;
}

// F and J = dF/dx for Newton from F evaluated on the jets x_i = variable(i).
template <class T, int m, class P>
void split_jets(const P& f, Vector<T, m>& residual, Matrix<T, m, m>& jacobian) {
  using J = typename P::value_type;
  const int size = static_cast<int>(f.size());
  for (int i = 0; i < size; ++i) {
    residual[i] = f[i].value;
    const J row = with_size(f[i], size);
    for (int j = 0; j < size; ++j) jacobian(i, j) = row.gradient[j];
  }
}

// Whether L_h is pulled back from a Q×Q discrete Lagrangian (it then divides d+ − d− by h).
template <class T>
bool pulls_back(const TQDiscretization<T>& d) {
  return d.lagrangian == TQLagrangianKind::pullback;
}

template <class T, int n>
struct TQStep {
  explicit TQStep(int size) : next{zero_vector<T, n>(size), zero_vector<T, n>(size)} {}
  State<T, n> next;
  SolveReport<T> report;
};

// F_h(v) by Newton on the blown-up equations from the unknowns `start` =
// (z, w̃) (the h = 0 solution is z = w̃ = w). The report says whether it
// converged; callers that need the step use require_converged. A mismatched
// step takes d+ and P+ at v from `past` and d− and P− at ṽ from `future` (the
// TQ form of the mismatched DEL, paper §2.3).
template <LagrangianSystem System>
TQStep<typename System::Scalar, System::dimension> tq_step_from(
    const System& system, const TQDiscretization<typename System::Scalar>& past,
    const TQDiscretization<typename System::Scalar>& future,
    const State<typename System::Scalar, System::dimension>& v, const typename System::Scalar& h,
    const Vector<typename System::Scalar, twice(System::dimension)>& start, const NewtonOptions& options = {}) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  constexpr int M = twice(N);
  const int n = static_cast<int>(v.q.size()), m = 2 * n;
  using J = Jet<T, M, 1>;  // the Jacobian needs first derivatives only
  auto at_v = tq_legendre(system, past, tangent_point(v), h);
  Vector<T, M> x = start;
  // The residual rounds at ε·|q|/h (its first block divides a difference of
  // configurations by h): z cannot be resolved below that, and q̃ = q + h z
  // is then still at working precision. A pulled-back L_h evaluates L_d at
  // (d−, d+) and so divides d+ − d− by h too: its P± and hence w̃ round there as well.
  Vector<T, M> rounding_scale = Vector<T, M>::Ones(m);
  const T point_scale = std::max<T>(T(1), max_norm<T, N>(v.q) / h);
  const bool velocities_too = pulls_back(past) || pulls_back(future);
  for (int i = 0; i < n; ++i) {
    rounding_scale[i] = point_scale;
    if (velocities_too) rounding_scale[n + i] = point_scale;
  }
  TQStep<T, N> step(n);
  step.report = newton_solve<T, M>(
      x,
      [&](const Vector<T, M>& at, Vector<T, M>& residual, Matrix<T, M, M>& jacobian) {
        Coordinates<J, M> jet_x = make_point<J, M>(m);
        for (int i = 0; i < m; ++i) jet_x[i] = J::variable(at[i], i, m);
        split_jets<T, M>(tq_residual(system, future, v, at_v, jet_x, h), residual, jacobian);
      },
      options, rounding_scale);
  for (int i = 0; i < n; ++i) {
    step.next.q[i] = v.q[i] + h * x[i];
    step.next.w[i] = x[n + i];
  }
  return step;
}

// The h = 0 solution of the blown-up equations, z = w̃ = w: where Newton starts.
template <class T, int N>
Vector<T, twice(N)> blown_up_identity(const State<T, N>& v) {
  const int n = static_cast<int>(v.q.size());
  Vector<T, twice(N)> x(2 * n);
  for (int i = 0; i < n; ++i) x[i] = v.w[i], x[n + i] = v.w[i];
  return x;
}

// F_h(v) by Newton from the h = 0 solution ṽ = v (Theorem 4.2: the critical
// point near the diagonal).
template <LagrangianSystem System>
TQStep<typename System::Scalar, System::dimension> tq_step(
    const System& system, const TQDiscretization<typename System::Scalar>& past,
    const TQDiscretization<typename System::Scalar>& future,
    const State<typename System::Scalar, System::dimension>& v, const typename System::Scalar& h,
    const NewtonOptions& options = {}) {
  return tq_step_from(system, past, future, v, h, blown_up_identity(v), options);
}

// F_h(v) of one discretization (past = future = d).
template <LagrangianSystem System>
TQStep<typename System::Scalar, System::dimension> tq_step(
    const System& system, const TQDiscretization<typename System::Scalar>& d,
    const State<typename System::Scalar, System::dimension>& v, const typename System::Scalar& h,
    const NewtonOptions& options = {}) {
  return tq_step(system, d, d, v, h, options);
}

// N steps of F_h from v (mismatched when past ≠ future); a step whose solve
// fails is an error naming it.
template <LagrangianSystem System>
std::vector<State<typename System::Scalar, System::dimension>> tq_trajectory(
    const System& system, const TQDiscretization<typename System::Scalar>& past,
    const TQDiscretization<typename System::Scalar>& future,
    const State<typename System::Scalar, System::dimension>& v, const typename System::Scalar& h,
    int steps, const std::function<void(int, int)>& after_step = {}) {
  using T = typename System::Scalar;
  std::vector<State<T, System::dimension>> trajectory{v};
  for (int k = 0; k < steps; ++k) {
    auto step = tq_step(system, past, future, trajectory.back(), h);
    require_converged(step.report, "TQ step " + std::to_string(k + 1) + " of " +
                                       std::to_string(steps) + " with h = " + to_decimal<T>(h, 17));
    trajectory.push_back(step.next);
    if (after_step) after_step(k + 1, steps);
  }
  return trajectory;
}

// N steps of F_h of one discretization d.
template <LagrangianSystem System>
std::vector<State<typename System::Scalar, System::dimension>> tq_trajectory(
    const System& system, const TQDiscretization<typename System::Scalar>& d,
    const State<typename System::Scalar, System::dimension>& v, const typename System::Scalar& h,
    int steps, const std::function<void(int, int)>& after_step = {}) {
  return tq_trajectory(system, d, d, v, h, steps, after_step);
}

// The blown-up critical point (v, ṽ) at fixed end points (paper §2.4, proof of
// Theorem 5.4): d−(v) = q_minus and d+(ṽ) = q_plus are held, the connection
// d+(v) = d−(ṽ) is free, and S = L_h(v) + L_h(ṽ) is stationary. The past
// segment v may use another discretization than the future one ṽ (a
// mismatched pair, which breaks the past–future symmetry); both need the same θ. With
// q = q_minus + h ζ and q̃ = q_minus + h ζ̃, the unknowns x = (ζ, w, ζ̃, w̃) solve
//   (d−(v) − q_minus)/h = 0,   (d+(ṽ) − q_plus)/h = 0,
//   (d+(v) − d−(ṽ))/h = 0,     P+(v) − P−(ṽ) = 0,
// well conditioned as h → 0, where with z = (q_plus − q_minus)/h the solution is
// w = w̃ = z/2, ζ = θ z/2, ζ̃ = (1 + θ) z/2 (the past–future symmetric point
// v = ṽ of the h = 0 principle): Newton starts there.
template <class T, int n>
struct TQCriticalPair {
  explicit TQCriticalPair(int size)
      : v{zero_vector<T, n>(size), zero_vector<T, n>(size)}, v_next{zero_vector<T, n>(size), zero_vector<T, n>(size)} {}
  State<T, n> v, v_next;  // v and ṽ
  SolveReport<T> report;
};

template <LagrangianSystem System>
TQCriticalPair<typename System::Scalar, System::dimension> tq_critical_pair(
    const System& system, const TQDiscretization<typename System::Scalar>& past,
    const TQDiscretization<typename System::Scalar>& future,
    const VectorOf<System>& q_minus,
    const VectorOf<System>& q_plus, const typename System::Scalar& h,
    const NewtonOptions& options = {}) {
  using T = typename System::Scalar;
  constexpr int N = System::dimension;
  constexpr int M = twice(twice(N));
  const int n = static_cast<int>(q_minus.size()), m = 4 * n;
  using J = Jet<T, M, 1>;  // the Jacobian needs first derivatives only
  using std::max;
  if (past.theta != future.theta)
    throw std::invalid_argument("tq_critical_pair: the past and future discretizations need the same θ");
  const Vector<T, N> z = (q_plus - q_minus) / h;
  Vector<T, M> x(m);
  for (int i = 0; i < n; ++i) {
    x[i] = past.theta * z[i] / 2;
    x[n + i] = z[i] / 2;
    x[2 * n + i] = (1 + past.theta) * z[i] / 2;
    x[3 * n + i] = z[i] / 2;
  }
  // As in tq_step: the configuration blocks divide differences of points by h,
  // and so do the velocity blocks of a pulled-back L_h.
  Vector<T, M> rounding_scale = Vector<T, M>::Ones(m);
  const T point_scale = max(T(1), T(max(max_norm<T, N>(q_minus), max_norm<T, N>(q_plus)) / h));
  const bool velocities_too = pulls_back(past) || pulls_back(future);
  for (int i = 0; i < n; ++i) {
    rounding_scale[i] = rounding_scale[2 * n + i] = point_scale;
    if (velocities_too) rounding_scale[n + i] = rounding_scale[3 * n + i] = point_scale;
  }
  auto point_of = [&](const auto& at, int offset) {
    using S = std::decay_t<decltype(at[0])>;
    TangentPoint<S, N> point = make_tangent_point<S, N>(n);
    for (int i = 0; i < n; ++i) {
      point.q[i] = q_minus[i] + h * at[offset + i];
      point.w[i] = at[offset + n + i];
    }
    return point;
  };
  TQCriticalPair<T, N> pair(n);
  pair.report = newton_solve<T, M>(
      x,
      [&](const Vector<T, M>& at, Vector<T, M>& residual, Matrix<T, M, M>& jacobian) {
        Coordinates<J, M> jet_x = make_point<J, M>(m);
        for (int i = 0; i < m; ++i) jet_x[i] = J::variable(at[i], i, m);
        auto at_v = tq_legendre(system, past, point_of(jet_x, 0), h);
        auto at_next = tq_legendre(system, future, point_of(jet_x, 2 * n), h);
        Coordinates<J, M> r = make_point<J, M>(m);
        for (int i = 0; i < n; ++i) {
          r[i] = (at_v.d_minus[i] - q_minus[i]) / h;
          r[n + i] = (at_next.d_plus[i] - q_plus[i]) / h;
          r[2 * n + i] = (at_v.d_plus[i] - at_next.d_minus[i]) / h;
          r[3 * n + i] = at_v.p_plus[i] - at_next.p_minus[i];
        }
        split_jets<T, M>(r, residual, jacobian);
      },
      options, rounding_scale);
  for (int i = 0; i < n; ++i) {
    pair.v.q[i] = q_minus[i] + h * x[i];
    pair.v.w[i] = x[n + i];
    pair.v_next.q[i] = q_minus[i] + h * x[2 * n + i];
    pair.v_next.w[i] = x[3 * n + i];
  }
  return pair;
}

}  // namespace vivv
