// One-step maps vivv did not write: x_{k+1} = Φ_h(x_k) on (q, w), e.g. a stepper of another
// library, checked by the claims that apply to maps (global-order, symplecticity,
// energy-behaviour, discrete-noether). The contract is what those claims measure:
//   step(x, h)      Φ_h(x), in the working precision;
//   jacobian(x, h)  ∂(q', p')/∂(q, p) of the map on (q, p), p = FL(q, w);
//   order()         the order r the map's authors state: |Φ_h − F_h| = O(h^{r+1}).
//
// The first adapters (core/maps/odeint_map.hpp) step a separable system
//   L(q, w) = ½ wᵀ M w − V(q),  M constant,
// so p = M w and q'' = M⁻¹ F(q) with F = −∇V = ∂L/∂q(q, 0): what a Störmer–Verlet or
// Runge–Kutta–Nyström stepper takes. SeparableSystem carries M and F, the latter in the
// working precision and in first-order jets over (q, p), through which the map's Jacobian is
// computed exactly (no finite differences).
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/autodiff/jet.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "core/lagrangian/state.hpp"

namespace vivv {

// A map's state far beyond the problem's scale: the run at step size `h` diverged, and vivv
// stopped it before computing with the state (a huge but representable q makes cos(q) take
// minutes). Claims record it as an inconclusive verdict at that h (harness/claims/claim.hpp).
struct MapDiverged : std::runtime_error {
  MapDiverged(const std::string& what, std::string h_) : std::runtime_error(what), h(std::move(h_)) {}
  std::string h;  // the step size, a decimal
};

// A map whose Jacobian cannot be measured (a program that does not compute with the digits
// the Jacobian's differences need): the claims that need it record the verdict "error" with
// this message, and every other claim is judged (harness/claims/claim.hpp).
struct UnmeasurableJacobian : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <class T, int n>
struct OneStepMap {
  virtual ~OneStepMap() = default;
  virtual std::string name() const = 0;
  virtual int order() const = 0;
  // Φ_h(x) on (q, w).
  virtual State<T, n> step(const State<T, n>& x, const T& h) const = 0;
  // ∂(q', p')/∂(q, p) at x.
  virtual Matrix<T, 2 * n, 2 * n> jacobian(const State<T, n>& x, const T& h) const = 0;
  // The relative rounding of jacobian()'s entries: ε of T for a Jacobian computed exactly (jets,
  // the implicit function theorem, a program's own), larger for one by differences at a width
  // the map's precision allows (a double program: about ε^(2/3)). symplecticity's tolerance is
  // a multiple of it.
  virtual T jacobian_unit() const { return epsilon<T>(); }
  // The relative rounding of the last jacobian()'s entries: jacobian_unit(), or more where the map
  // measured more (a double program whose answers carry an implicit solver's noise).
  virtual T last_jacobian_unit() const { return jacobian_unit(); }
  // The spread of the rounding in one step's answer from x, where the map measures it (a program
  // that computes in double): local-order's floor is then the map's own rounding.
  virtual std::optional<T> answer_noise(const State<T, n>& x, const T& h) const {
    (void)x, (void)h;
    return std::nullopt;
  }
  // How jacobian() computes it, for the report.
  virtual std::string jacobian_method() const {
    return "forward-mode automatic differentiation of one step of " + name() +
           " in first-order jets over (q, p), w = M^-1 p";
  }
};

// The Jacobian's scalar: a value and its gradient in the 2n variables (q, p).
template <class T, int n>
using PhaseJet = Jet<T, 2 * n, 1>;

// L(q, w) = ½ wᵀ M w − V(q): the mass matrix, its inverse and the force F(q) = −∇V(q).
template <class T, int n>
struct SeparableSystem {
  Matrix<T, n, n> mass, inverse_mass;
  std::function<std::array<T, n>(const std::array<T, n>&)> force;
  std::function<std::array<PhaseJet<T, n>, n>(const std::array<PhaseJet<T, n>, n>&)> force_jet;
};

// A one-step map on a separable system given by Derived::advance(q, w, h, force) in any scalar
// S (advancing (q, w) in place, the force F(q) in S): the step in T, and the Jacobian on (q, p)
// by running the same code in first-order jets over (q, p), w = M⁻¹ p. Odeint's steppers and
// the maps a program registers (core/maps/odeint_map.hpp, core/maps/user_map.hpp) are such maps.
template <class Derived, class T, int n>
class SeparableMap : public OneStepMap<T, n> {
 public:
  explicit SeparableMap(SeparableSystem<T, n> system) : system_(std::move(system)) {}

  State<T, n> step(const State<T, n>& x, const T& h) const override {
    std::array<T, n> q, w;
    for (int i = 0; i < n; ++i) q[i] = x.q[i], w[i] = x.w[i];
    derived().advance(q, w, h, system_.force);
    State<T, n> next;
    for (int i = 0; i < n; ++i) next.q[i] = q[i], next.w[i] = w[i];
    return next;
  }

  // Rows of the result: the gradients of q' and of p' = M w' over (q, p).
  Matrix<T, 2 * n, 2 * n> jacobian(const State<T, n>& x, const T& h) const override {
    using J = PhaseJet<T, n>;
    const Vector<T, n> p = system_.mass * x.w;
    std::array<J, n> q, momentum;
    for (int i = 0; i < n; ++i) q[i] = J::variable(x.q[i], i), momentum[i] = J::variable(p[i], n + i);
    std::array<J, n> w = times(system_.inverse_mass, momentum);
    derived().advance(q, w, J(h), system_.force_jet);
    const std::array<J, n> p_next = times(system_.mass, w);
    Matrix<T, 2 * n, 2 * n> jacobian;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < 2 * n; ++j) jacobian(i, j) = q[i].gradient[j], jacobian(n + i, j) = p_next[i].gradient[j];
    return jacobian;
  }

 protected:
  const SeparableSystem<T, n>& system() const { return system_; }

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

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }
  SeparableSystem<T, n> system_;
};

// F(q) = ∂L/∂q(q, 0) in scalar S (T or a jet over it), by one more first-order jet.
template <LagrangianSystem System, class S>
std::array<S, System::dimension> force_at(const System& system, const std::array<S, System::dimension>& q) {
  constexpr int n = System::dimension;
  using J = Jet<S, n, 1>;
  Point<J, n> jet_q, jet_w;
  for (int i = 0; i < n; ++i) {
    jet_q[i] = J::variable(q[i], i);
    jet_w[i] = J(S(0));
  }
  const J L = system.lagrangian(jet_q, jet_w);
  std::array<S, n> force;
  for (int i = 0; i < n; ++i) force[i] = L.gradient[i];
  return force;
}

// Where `system` is not of the form ½ wᵀ M w − V(q) with M constant, as far as the states
// `samples` show: ∂²L/∂w∂q ≠ 0, or ∂²L/∂w² differing from its value at the first sample, by
// more than 1000 ε relative to the size of M, or not finite.
template <class T, int n>
struct SeparabilityDefect {
  std::string quantity;  // the entry, "d2L/dw_2 dq_1", or "the change of d2L/dw_1 dw_1 from the
                         // initial state"
  T size;                // its largest entry
  State<T, n> at;
};

template <LagrangianSystem System>
std::optional<SeparabilityDefect<typename System::Scalar, System::dimension>> separability_defect(
    const System& system, const std::vector<State<typename System::Scalar, System::dimension>>& samples) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  using std::max;
  const auto first = lagrangian_derivatives(system, samples.front().q, samples.front().w);
  const T allowed = 1000 * epsilon<T>() * max(T(1), T(first.d2L_dw2.cwiseAbs().maxCoeff()));
  for (const auto& x : samples) {
    const auto d = lagrangian_derivatives(system, x.q, x.w);
    // The entry named by its components (1-based): d2L/dw_2 dq_1, not "the first components".
    const auto entry = [](const Matrix<T, n, n>& m, const std::string& row,
                          const std::string& column, std::string& name) {
      int i = 0, j = 0;
      T largest = -1;
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
          using std::abs, std::isnan;
          const T value = isnan(m(r, c)) ? std::numeric_limits<T>::infinity() : T(abs(m(r, c)));
          if (value > largest) largest = value, i = r, j = c;
        }
      name = n == 1
                 ? row + " " + column
                 : row + "_" + std::to_string(i + 1) + " " + column + "_" + std::to_string(j + 1);
      return m(i, j);
    };
    std::string name;
    const T mixed = d.d2L_dwdq.cwiseAbs().maxCoeff();
    const Matrix<T, n, n> change = d.d2L_dw2 - first.d2L_dw2;
    const T varying = change.cwiseAbs().maxCoeff();
    // Written so that a NaN (a sample outside L's domain) is a defect too, never a pass.
    if (!(mixed <= allowed)) {
      const T value = entry(d.d2L_dwdq, "d2L/dw", "dq", name);
      return SeparabilityDefect<T, n>{name, value, x};
    }
    if (!(varying <= allowed)) {
      const T value = entry(change, "d2L/dw", "dw", name);
      return SeparabilityDefect<T, n>{"the change of " + name + " from the initial state", value,
                                      x};
    }
  }
  return std::nullopt;
}

// The separable form of `system` (mass from ∂²L/∂w² at `at`), for the map adapters.
template <LagrangianSystem System>
SeparableSystem<typename System::Scalar, System::dimension> separable_form(
    const System& system, const State<typename System::Scalar, System::dimension>& at) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  SeparableSystem<T, n> separable;
  separable.mass = lagrangian_derivatives(system, at.q, at.w).d2L_dw2;
  separable.inverse_mass = separable.mass.inverse();
  separable.force = [system](const std::array<T, n>& q) { return force_at(system, q); };
  separable.force_jet = [system](const std::array<PhaseJet<T, n>, n>& q) { return force_at(system, q); };
  return separable;
}

}  // namespace vivv
