// The exact discrete Lagrangian L_d^E(q_b, q_e; h) and its Legendre transforms (docs/theory.md (Q × Q)).
//
//   L_d^E(q_b, q_e; h) = ∫₀ʰ L(q(t), q'(t)) dt,   q the solution with q(0) = q_b, q(h) = q_e,
//   p_begin = −∂L_d^E/∂q_b = p(0) = ∂L/∂w(q_b, q'(0)),   p_end = ∂L_d^E/∂q_e = p(h).
//
// The two-point problem is solved by Newton shooting on w0 = q'(0):
//   r(w0) = q(h; q_b, w0) − q_e,   w0 ← w0 − (∂q(h)/∂w0)⁻¹ r(w0),
// with q(h) and ∂q(h)/∂w0 (the upper right block of the flow's Jacobian) from
// the Taylor variational flow, from the guess w0 = (q_e − q_b)/h, until the
// Newton step is below the tolerance. The action is composite Gauss–Legendre
// quadrature (core/numerics/quadrature.hpp, nodes computed in T) over each
// Taylor step of the dense output of the solution, whose integrand is then
// analytic well beyond the step. The shooting converges for h below the
// first conjugate time of the solution; the result says whether it did.
//
// For an L that depends on t the segment starts at the system's time t_b (at_time): the flows
// start there, the action integrates L(t_b + τ, q(τ), q'(τ)) over τ ∈ [0, h], and p_end is read at
// t_b + h.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/lagrangian/lagrangian.hpp"
#include "core/numerics/scalar.hpp"
#include "core/numerics/quadrature.hpp"
#include "references/taylor_flow.hpp"
#include "references/taylor_variational_flow.hpp"

namespace vivv {

template <class T, int n>
struct ExactDiscreteLagrangianValue {
  explicit ExactDiscreteLagrangianValue(int size) : p_begin(size), p_end(size), w_begin(size), w_end(size) {}
  T value;              // L_d^E(q_b, q_e; h)
  Vector<T, n> p_begin;  // p(0) = −∂L_d^E/∂q_b
  Vector<T, n> p_end;    // p(h) = ∂L_d^E/∂q_e
  Vector<T, n> w_begin;  // q'(0) of the solution
  Vector<T, n> w_end;    // q'(h)
  int iterations = 0;    // Newton iterations
  T residual;            // ‖q(h; q_b, w_begin) − q_e‖_max at the last Newton step
  bool converged = false;
  int quadrature_nodes = 0;  // per Taylor step
};

template <TapeRecordable System>
class ExactDiscreteLagrangian {
 public:
  using T = typename System::Scalar;
  static constexpr int N = System::dimension;

  // `tolerance`: accuracy wanted for the solution (the flows run at step tolerance tolerance/1000);
  // `quadrature_nodes` per Taylor step, 0 for order/2 + 4.
  ExactDiscreteLagrangian(const System& system, const T& tolerance, int quadrature_nodes = 0)
      : system_(system),
        tolerance_(tolerance),
        flow_(system, tolerance / 1000),
        variational_(system, tolerance / 1000) {
    const int nodes = quadrature_nodes > 0 ? quadrature_nodes : flow_.order() / 2 + 4;
    rule_ = gauss_legendre<T>(nodes);
  }

  const T& tolerance() const { return tolerance_; }
  // Test-only access to the flows' recurrences (TaylorExpansion::fault_order).
  TaylorFlow<System>& flow() { return flow_; }
  TaylorVariationalFlow<System>& variational_flow() { return variational_; }

  // L_d^E(q_b, q_e; h) and the end momenta; `guess`, if given, starts Newton at w0 = *guess.
  ExactDiscreteLagrangianValue<T, N> operator()(const Vector<T, N>& q_begin,
                                                const Vector<T, N>& q_end, const T& h,
                                                const Vector<T, N>* guess = nullptr) {
    using std::abs;
    using std::max;
    const int n = static_cast<int>(q_begin.size());
    if (!(h != 0)) throw std::invalid_argument("ExactDiscreteLagrangian: h must be nonzero");
    ExactDiscreteLagrangianValue<T, N> result(n);
    State<T, N> start;
    start.q = q_begin;
    start.w = guess ? *guess : Vector<T, N>((q_end - q_begin) / h);
    // Newton shooting on w0.
    for (int iteration = 1; iteration <= max_iterations; ++iteration) {
      FlowWithJacobian<T, N> shot = variational_.advance(start, h);
      Vector<T, N> residual = shot.state.q - q_end;
      Matrix<T, N, N> dq_dw0 = shot.jacobian.topRightCorner(n, n);
      Vector<T, N> correction = dq_dw0.fullPivLu().solve(residual);
      start.w -= correction;
      result.iterations = iteration;
      result.residual = max_norm<T, N>(residual);
      bool small = true;
      for (int i = 0; i < n; ++i)
        small = small && abs(correction[i]) <= tolerance_ * (1 + abs(start.w[i]));
      if (small) {
        result.converged = true;
        break;
      }
    }
    // The action along the dense output, composite Gauss–Legendre over the Taylor steps.
    TaylorTrajectory<T> solution = flow_.trajectory(start, h);
    result.quadrature_nodes = static_cast<int>(rule_.nodes.size());
    result.value = 0;
    for (const TaylorStep<T>& step : solution.steps()) {
      const T a = step.start;
      T b = step.start + step.length;
      if (h > 0 ? b > h : b < h) b = h;
      result.value += integrate(rule_, a, b, [&](const T& t) {
        const State<T, N> y = flow_.state_of(TaylorTrajectory<T>::evaluate(step, T(t - a)));
        return T(lagrangian_at(system_, T(system_time(system_) + t), as_point<T, N>(y.q), as_point<T, N>(y.w)));
      });
      if (b == h) break;
    }
    State<T, N> end = flow_.state_of(solution.state_at(h));
    result.w_begin = start.w;
    result.w_end = end.w;
    result.p_begin = momentum(system_, q_begin, start.w);
    result.p_end = momentum(at_time(system_, T(system_time(system_) + h)), q_end, end.w);
    return result;
  }

  int max_iterations = 40;

 private:
  System system_;
  T tolerance_;
  TaylorFlow<System> flow_;
  TaylorVariationalFlow<System> variational_;
  GaussLegendreRule<T> rule_;
};

}  // namespace vivv
