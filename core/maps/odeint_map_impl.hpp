// The definitions behind core/maps/odeint_map.hpp: include only where they are explicitly
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

#include "core/maps/odeint_map.hpp"

namespace vivv {

template <class T, int n>
class OdeintMap final : public SeparableMap<OdeintMap<T, n>, T, n> {
  using Base = SeparableMap<OdeintMap<T, n>, T, n>;
  friend Base;

 public:
  OdeintMap(OdeintStepperInfo info, SeparableSystem<T, n> system) : Base(std::move(system)), info_(std::move(info)) {}

  std::string name() const override { return "odeint " + info_.name; }
  int order() const override { return info_.order; }

 private:
  using Base::times;

  // One step of the stepper on (q, w) in scalar S, with force F in S.
  template <class S, class Force>
  void advance(vivv::Coordinates<S, n>& q, vivv::Coordinates<S, n>& w, const S& h, const Force& force) const {
    namespace odeint = boost::numeric::odeint;
    using Coordinates = vivv::Coordinates<S, n>;
    const int size = static_cast<int>(q.size());
    // q'' = M⁻¹ F(q), and its first-order forms.
    auto acceleration = [&](const Coordinates& x, const Coordinates&, Coordinates& a, const S&) {
      a = times(this->system().inverse_mass, force(x));
    };
    auto coordinate_rate = [&](const Coordinates& momentum, Coordinates& dq) { dq = times(this->system().inverse_mass, momentum); };
    auto momentum_rate = [&](const Coordinates& x, Coordinates& dp) { dp = force(x); };
    const std::string& name = info_.name;
    if (name == "velocity_verlet") {
      odeint::velocity_verlet<Coordinates, Coordinates, S> stepper;
      std::pair<Coordinates, Coordinates> state(q, w);
      stepper.do_step(acceleration, state, S(0), h);
      q = state.first, w = state.second;
    } else if (name == "symplectic_rkn_sb3a_mclachlan" || name == "symplectic_rkn_sb3a_m4_mclachlan") {
      std::pair<Coordinates, Coordinates> state(q, times(this->system().mass, w));
      auto rates = std::make_pair(coordinate_rate, momentum_rate);
      if (name == "symplectic_rkn_sb3a_mclachlan")
        odeint::symplectic_rkn_sb3a_mclachlan<Coordinates, Coordinates, S>().do_step(rates, state, S(0), h);
      else
        odeint::symplectic_rkn_sb3a_m4_mclachlan<Coordinates, Coordinates, S>().do_step(rates, state, S(0), h);
      q = state.first, w = times(this->system().inverse_mass, state.second);
    } else if (name == "runge_kutta4") {
      using Phase = vivv::Coordinates<S, twice(n)>;
      auto rate = [&](const Phase& y, Phase& dy, const S&) {
        Coordinates x = q, a;
        for (int i = 0; i < size; ++i) x[i] = y[i], dy[i] = y[size + i];
        a = times(this->system().inverse_mass, force(x));
        for (int i = 0; i < size; ++i) dy[size + i] = a[i];
      };
      Phase y = make_point<S, twice(n)>(2 * size);
      for (int i = 0; i < size; ++i) y[i] = q[i], y[size + i] = w[i];
      odeint::runge_kutta4<Phase, S, Phase, S>().do_step(rate, y, S(0), h);
      for (int i = 0; i < size; ++i) q[i] = y[i], w[i] = y[size + i];
    } else {
      throw std::invalid_argument("unknown odeint stepper '" + name + "'");
    }
  }

  OdeintStepperInfo info_;
};

template <class T, int n>
std::shared_ptr<const OneStepMap<T, n>> make_odeint_map(const std::string& name, const SeparableSystem<T, n>& system) {
  for (const auto& info : odeint_steppers())
    if (info.name == name) return std::make_shared<const OdeintMap<T, n>>(info, system);
  throw std::invalid_argument("unknown odeint stepper '" + name + "'");
}

}  // namespace vivv
