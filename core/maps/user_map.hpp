// One-step maps a program linking vivv brings itself (harness/library/vivv.hpp, register_map), on a
// separable system L = ½ wᵀ M w − V(q) as odeint's steppers are (core/maps/one_step_map.hpp). The
// method is a type with one member template, run in the working precision for the step and in
// first-order jets over (q, p) for the Jacobian — so it must be written for any scalar S:
//   template <class S, std::size_t n, class Acceleration>
//   void step(std::array<S, n>& q, std::array<S, n>& w, const S& h, const Acceleration& a) const;
// advancing (q, w) by h in place, with a(q) = M⁻¹ F(q) = q'' as std::array<S, n>.
//
// The registry maps a name to a factory for every scalar and dimension vivv runs
// (map_factories<T, n>), and to the order its authors state (registered_maps): a case names
// it as {"kind": "map", "name": ...}.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/maps/one_step_map.hpp"

namespace vivv {

struct RegisteredMap {
  std::string name;
  int order;
};

// The maps registered in this program, in the order of registration.
inline std::vector<RegisteredMap>& registered_maps() {
  static std::vector<RegisteredMap> maps;
  return maps;
}

template <class T, int n>
using MapFactory = std::function<std::shared_ptr<const OneStepMap<T, n>>(const SeparableSystem<T, n>&)>;

// The factories of the registered maps in scalar T and dimension n, by name.
template <class T, int n>
std::map<std::string, MapFactory<T, n>>& map_factories() {
  static std::map<std::string, MapFactory<T, n>> factories;
  return factories;
}

template <class Method, class T, int n>
class UserMap final : public SeparableMap<UserMap<Method, T, n>, T, n> {
  using Base = SeparableMap<UserMap<Method, T, n>, T, n>;
  friend Base;

 public:
  UserMap(RegisteredMap info, Method method, SeparableSystem<T, n> system)
      : Base(std::move(system)), info_(std::move(info)), method_(std::move(method)) {}

  std::string name() const override { return info_.name; }
  int order() const override { return info_.order; }

 private:
  // The user's step in scalar S, with q'' = M⁻¹ F(q) from the force in S.
  template <class S, class Force>
  void advance(Coordinates<S, n>& q, Coordinates<S, n>& w, const S& h, const Force& force) const {
    auto acceleration = [&](const Coordinates<S, n>& at) { return Base::times(this->system().inverse_mass, force(at)); };
    if constexpr (requires { method_.step(q, w, h, acceleration); }) {
      method_.step(q, w, h, acceleration);
    } else if (q.size() == 1) {
      step_in_array<1>(q, w, h, acceleration);
    } else if (q.size() == 2) {
      step_in_array<2>(q, w, h, acceleration);
    } else if (q.size() == 3) {
      step_in_array<3>(q, w, h, acceleration);
    } else if (q.size() == 4) {
      step_in_array<4>(q, w, h, acceleration);
    } else {
      throw std::invalid_argument("the registered map '" + info_.name + "' is written for std::array<S, n>: a system of " +
                                  std::to_string(q.size()) +
                                  " coordinates passes std::vector<S> (write step() for any container with size() and [])");
    }
  }

  // A method written for std::array<S, k> on a system sized at run time (k = 1 … 4: what vivv
  // compiled for such methods before sizes were run-time ones; outside MPFR, systems of one and
  // two coordinates are sized at run time too).
  template <std::size_t k, class P, class S, class Acceleration>
  void step_in_array(P& q, P& w, const S& h, const Acceleration& acceleration) const {
    std::array<S, k> x, v;
    for (std::size_t i = 0; i < k; ++i) x[i] = q[i], v[i] = w[i];
    auto in_array = [&](const std::array<S, k>& at) {
      const P result = acceleration(P(at.begin(), at.end()));
      std::array<S, k> a;
      for (std::size_t i = 0; i < k; ++i) a[i] = result[i];
      return a;
    };
    if constexpr (requires { method_.step(x, v, h, in_array); }) {
      method_.step(x, v, h, in_array);
      for (std::size_t i = 0; i < k; ++i) q[i] = x[i], w[i] = v[i];
    }
  }

  RegisteredMap info_;
  Method method_;
};

}  // namespace vivv
