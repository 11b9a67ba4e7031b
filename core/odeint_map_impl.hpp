// The definitions behind core/odeint_map.hpp: include only where they are explicitly
// instantiated (the odeint_map_<scalar> units harness/CMakeLists.txt generates).
#pragma once

// The m4 header uses the RKN base without including it (Boost 1.74): include it first.
#include <boost/numeric/odeint/stepper/base/symplectic_rkn_stepper_base.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <boost/numeric/odeint/stepper/symplectic_rkn_sb3a_m4_mclachlan.hpp>
#include <boost/numeric/odeint/stepper/symplectic_rkn_sb3a_mclachlan.hpp>
#include <boost/numeric/odeint/stepper/velocity_verlet.hpp>
#include <stdexcept>
#include <utility>

#include "core/odeint_map.hpp"

namespace vivv {

template <class T, int n>
class OdeintMap final : public OneStepMap<T, n> {
 public:
  OdeintMap(OdeintStepperInfo info, SeparableSystem<T, n> system) : info_(std::move(info)), system_(std::move(system)) {}

  std::string name() const override { return "odeint " + info_.name; }
  int order() const override { return info_.order; }

  State<T, n> step(const State<T, n>& x, const T& h) const override {
    std::array<T, n> q, w;
    for (int i = 0; i < n; ++i) q[i] = x.q[i], w[i] = x.w[i];
    advance(q, w, h, system_.force);
    State<T, n> next;
    for (int i = 0; i < n; ++i) next.q[i] = q[i], next.w[i] = w[i];
    return next;
  }

  // The step run in jets with (q, p) as the 2n variables, w = M⁻¹ p; rows of the result are
  // the gradients of q' and of p' = M w'.
  Matrix<T, 2 * n, 2 * n> jacobian(const State<T, n>& x, const T& h) const override {
    using J = PhaseJet<T, n>;
    const Vector<T, n> p = system_.mass * x.w;
    std::array<J, n> q, w, momentum;
    for (int i = 0; i < n; ++i) q[i] = J::variable(x.q[i], i), momentum[i] = J::variable(p[i], n + i);
    w = times(system_.inverse_mass, momentum);
    advance(q, w, J(h), system_.force_jet);
    const std::array<J, n> p_next = times(system_.mass, w);
    Matrix<T, 2 * n, 2 * n> jacobian;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < 2 * n; ++j) jacobian(i, j) = q[i].gradient[j], jacobian(n + i, j) = p_next[i].gradient[j];
    return jacobian;
  }

 private:
  // A·v for a matrix in T and a vector in S.
  template <class S>
  static std::array<S, n> times(const Matrix<T, n, n>& a, const std::array<S, n>& v) {
    std::array<S, n> r;
    for (int i = 0; i < n; ++i) {
      r[i] = S(0);
      for (int j = 0; j < n; ++j) r[i] += S(a(i, j)) * v[j];
    }
    return r;
  }

  // One step of the stepper on (q, w) in scalar S, with force F in S.
  template <class S, class Force>
  void advance(std::array<S, n>& q, std::array<S, n>& w, const S& h, const Force& force) const {
    namespace odeint = boost::numeric::odeint;
    using Coordinates = std::array<S, n>;
    // q'' = M⁻¹ F(q), and its first-order forms.
    auto acceleration = [&](const Coordinates& x, const Coordinates&, Coordinates& a, const S&) {
      a = times(system_.inverse_mass, force(x));
    };
    auto coordinate_rate = [&](const Coordinates& momentum, Coordinates& dq) { dq = times(system_.inverse_mass, momentum); };
    auto momentum_rate = [&](const Coordinates& x, Coordinates& dp) { dp = force(x); };
    const std::string& name = info_.name;
    if (name == "velocity_verlet") {
      odeint::velocity_verlet<Coordinates, Coordinates, S> stepper;
      std::pair<Coordinates, Coordinates> state(q, w);
      stepper.do_step(acceleration, state, S(0), h);
      q = state.first, w = state.second;
    } else if (name == "symplectic_rkn_sb3a_mclachlan" || name == "symplectic_rkn_sb3a_m4_mclachlan") {
      std::pair<Coordinates, Coordinates> state(q, times(system_.mass, w));
      auto rates = std::make_pair(coordinate_rate, momentum_rate);
      if (name == "symplectic_rkn_sb3a_mclachlan")
        odeint::symplectic_rkn_sb3a_mclachlan<Coordinates, Coordinates, S>().do_step(rates, state, S(0), h);
      else
        odeint::symplectic_rkn_sb3a_m4_mclachlan<Coordinates, Coordinates, S>().do_step(rates, state, S(0), h);
      q = state.first, w = times(system_.inverse_mass, state.second);
    } else if (name == "runge_kutta4") {
      using Phase = std::array<S, 2 * n>;
      auto rate = [&](const Phase& y, Phase& dy, const S&) {
        Coordinates x, a;
        for (int i = 0; i < n; ++i) x[i] = y[i], dy[i] = y[n + i];
        a = times(system_.inverse_mass, force(x));
        for (int i = 0; i < n; ++i) dy[n + i] = a[i];
      };
      Phase y;
      for (int i = 0; i < n; ++i) y[i] = q[i], y[n + i] = w[i];
      odeint::runge_kutta4<Phase, S, Phase, S>().do_step(rate, y, S(0), h);
      for (int i = 0; i < n; ++i) q[i] = y[i], w[i] = y[n + i];
    } else {
      throw std::invalid_argument("unknown odeint stepper '" + name + "'");
    }
  }

  OdeintStepperInfo info_;
  SeparableSystem<T, n> system_;
};

template <class T, int n>
std::shared_ptr<const OneStepMap<T, n>> make_odeint_map(const std::string& name, const SeparableSystem<T, n>& system) {
  for (const auto& info : odeint_steppers())
    if (info.name == name) return std::make_shared<const OdeintMap<T, n>>(info, system);
  throw std::invalid_argument("unknown odeint stepper '" + name + "'");
}

}  // namespace vivv
