// One-step maps a program linking vivv brings itself (harness/vivv.hpp, register_map), on a
// separable system L = ½ wᵀ M w − V(q) as odeint's steppers are (core/one_step_map.hpp). The
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
#include <string>
#include <utility>
#include <vector>

#include "core/one_step_map.hpp"

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
class UserMap final : public OneStepMap<T, n> {
 public:
  UserMap(RegisteredMap info, Method method, SeparableSystem<T, n> system)
      : info_(std::move(info)), method_(std::move(method)), system_(std::move(system)) {}

  std::string name() const override { return info_.name; }
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
    std::array<J, n> q, momentum;
    for (int i = 0; i < n; ++i) q[i] = J::variable(x.q[i], i), momentum[i] = J::variable(p[i], n + i);
    std::array<J, n> w = times(system_.inverse_mass, momentum);
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

  // The user's step in scalar S, with q'' = M⁻¹ F(q) from the force in S.
  template <class S, class Force>
  void advance(std::array<S, n>& q, std::array<S, n>& w, const S& h, const Force& force) const {
    auto acceleration = [&](const std::array<S, n>& at) { return times(system_.inverse_mass, force(at)); };
    method_.step(q, w, h, acceleration);
  }

  RegisteredMap info_;
  Method method_;
  SeparableSystem<T, n> system_;
};

}  // namespace vivv
