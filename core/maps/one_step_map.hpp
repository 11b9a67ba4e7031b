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
  // The time of the states the next calls start from (a map of an L that depends on time, whose
  // step from x depends on x's time as well as on x): t is the absolute time, t0 + the time along
  // the run, and steps() and trajectory() advance it by h a step. A map that takes the time (a
  // program: "t" in its requests, docs/process-protocol.md) keeps it for the calls that follow;
  // an autonomous map ignores it. Whoever steps a map of a timed L says the time before each call
  // from a state of another time (harness/claims: map_at).
  virtual void set_time(const T& t) const { (void)t; }
  // ∂(q', p')/∂(q, p) at x.
  virtual Matrix<T, twice(n), twice(n)> jacobian(const State<T, n>& x, const T& h) const = 0;
  // ∂(q', p')/∂(q, p) at x applied to each of `directions` (vectors on (q, p)): J·v, for checks that
  // need J only through products (symplecticity's probes above its dense limit). A map that can
  // form J·v without J overrides it (a program: differences along v, a few requests each, where J
  // takes some for each of the 2n coordinates); last_jacobian_unit() is then the products' relative
  // rounding, relative to max(1, the largest |J·v|/|v|).
  virtual std::vector<Vector<T, twice(n)>> jacobian_along(const State<T, n>& x, const T& h,
                                                          const std::vector<Vector<T, twice(n)>>& directions) const {
    const Matrix<T, twice(n), twice(n)> j = jacobian(x, h);
    std::vector<Vector<T, twice(n)>> out;
    out.reserve(directions.size());
    for (const Vector<T, twice(n)>& v : directions) out.push_back(j * v);
    return out;
  }
  // Φ_h^count(x) at once, where the map can take several steps a call cheaper than one at a time
  // (a program that took up the protocol's "steps" extension: only the last state crosses its
  // pipe); nullopt where it cannot, or where a state on the way left the finite numbers or the
  // problem's scale: the caller then takes the steps one at a time, which says where.
  virtual std::optional<State<T, n>> steps(const State<T, n>& /*x*/, const T& /*h*/, long /*count*/) const {
    return std::nullopt;
  }
  // x_1 … x_count, every state of `count` steps from x, at once where the map can (a program that
  // took up the protocol's "steps" and "trajectory" extensions: the states cross its pipe a batch at
  // a time, not a request a step); nullopt as for steps(), and the caller then takes the steps one
  // at a time.
  virtual std::optional<std::vector<State<T, n>>> trajectory(const State<T, n>& /*x*/, const T& /*h*/,
                                                             long /*count*/) const {
    return std::nullopt;
  }
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
  // The largest noise measured in its answers so far, relative to their size and in units of
  // double's ε (answer_noise, last_jacobian_unit): a few for a program that rounds like a double,
  // 10^7 for one whose answers carry float32 noise; nullopt where the map measures none.
  virtual std::optional<double> answer_noise_in_ulps() const { return std::nullopt; }
  // The evaluations the map says its steps have made so far (a program that took up the protocol's
  // extension "evaluations": forces, or L, counted in the program): the work-precision diagram's
  // cost of a map whose work vivv does not see; nullopt where the map does not report them.
  virtual std::optional<long> reported_evaluations() const { return std::nullopt; }
  // How jacobian() computes it, for the report.
  virtual std::string jacobian_method() const {
    return "forward-mode automatic differentiation of one step of " + name() +
           " in first-order jets over (q, p), w = M^-1 p";
  }
};

// The Jacobian's scalar: a value and its gradient in the 2n variables (q, p).
template <class T, int n>
using PhaseJet = Jet<T, twice(n), 1>;

// L(q, w) = ½ wᵀ M w − V(q): the mass matrix, its inverse and the force F(q) = −∇V(q).
template <class T, int n>
struct SeparableSystem {
  Matrix<T, n, n> mass, inverse_mass;
  std::function<Coordinates<T, n>(const Coordinates<T, n>&)> force;
  std::function<Coordinates<PhaseJet<T, n>, n>(const Coordinates<PhaseJet<T, n>, n>&)> force_jet;
  int size() const { return static_cast<int>(mass.rows()); }
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
    Coordinates<T, n> q = as_point<T, n>(x.q), w = as_point<T, n>(x.w);
    derived().advance(q, w, h, system_.force);
    return State<T, n>{as_vector<T, n>(q), as_vector<T, n>(w)};
  }

  // Rows of the result: the gradients of q' and of p' = M w' over (q, p).
  Matrix<T, twice(n), twice(n)> jacobian(const State<T, n>& x, const T& h) const override {
    using J = PhaseJet<T, n>;
    const int size = system_.size();
    const Vector<T, n> p = system_.mass * x.w;
    Coordinates<J, n> q = make_point<J, n>(size), momentum = make_point<J, n>(size);
    for (int i = 0; i < size; ++i)
      q[i] = J::variable(x.q[i], i, 2 * size), momentum[i] = J::variable(p[i], size + i, 2 * size);
    Coordinates<J, n> w = times(system_.inverse_mass, momentum);
    derived().advance(q, w, J(h), system_.force_jet);
    const Coordinates<J, n> p_next = times(system_.mass, w);
    Matrix<T, twice(n), twice(n)> jacobian(2 * size, 2 * size);
    for (int i = 0; i < size; ++i) {
      const J q_i = with_size(q[i], 2 * size), p_i = with_size(p_next[i], 2 * size);
      for (int j = 0; j < 2 * size; ++j) jacobian(i, j) = q_i.gradient[j], jacobian(size + i, j) = p_i.gradient[j];
    }
    return jacobian;
  }

 protected:
  const SeparableSystem<T, n>& system() const { return system_; }

  // A·v for a matrix in T and a vector in S.
  template <class P>
  static P times(const Matrix<T, n, n>& a, const P& v) {
    using S = typename P::value_type;
    const int size = static_cast<int>(v.size());
    P r = v;
    for (int i = 0; i < size; ++i) {
      r[i] = S(0);
      for (int j = 0; j < size; ++j) r[i] += S(a(i, j)) * v[j];
    }
    return r;
  }

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }
  SeparableSystem<T, n> system_;
};

// F(q) = ∂L/∂q(q, 0) in scalar S (T or a jet over it), by one more first-order jet.
template <LagrangianSystem System, class P>
P force_at(const System& system, const P& q) {
  using S = typename P::value_type;
  constexpr int N = System::dimension;
  const int n = static_cast<int>(q.size());
  using J = Jet<S, N, 1>;
  Coordinates<J, N> jet_q = make_point<J, N>(n), jet_w = make_point<J, N>(n);
  for (int i = 0; i < n; ++i) {
    jet_q[i] = J::variable(q[i], i, n);
    jet_w[i] = J(S(0));
  }
  const J L = with_size(J(system.lagrangian(jet_q, jet_w)), n);
  P force = q;
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
      for (int r = 0; r < m.rows(); ++r)
        for (int c = 0; c < m.cols(); ++c) {
          using std::abs, std::isnan;
          const T value = isnan(m(r, c)) ? std::numeric_limits<T>::infinity() : T(abs(m(r, c)));
          if (value > largest) largest = value, i = r, j = c;
        }
      name = m.rows() == 1
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
  separable.force = [system](const Coordinates<T, n>& q) { return force_at(system, q); };
  separable.force_jet = [system](const Coordinates<PhaseJet<T, n>, n>& q) { return force_at(system, q); };
  return separable;
}

}  // namespace vivv
