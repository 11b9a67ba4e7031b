// Boost.Odeint's steppers as one-step maps (core/maps/odeint_map.hpp): a third-party velocity Verlet
// agrees with vivv's own trapezoid variational integrator to working precision, the Jacobian
// computed by jets through the stepper is its derivative, the symplectic steppers have
// JᵀΩJ = Ω to working precision and the classical Runge–Kutta method does not (the negative
// control), the check symplecticity runs tells a stepper's Jacobian from that of a step of h/2,
// and a Lagrangian that is not ½ wᵀMw − V(q) is refused. The systems are formulas sized at run
// time, as vivv runs every system: the maps are the library's own instantiations
// (harness/CMakeLists.txt), one per scalar.
#include "core/maps/odeint_map.hpp"

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/structure/symplectic.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

// L written as a formula in q1, q2, w1, w2, sized at run time in T.
template <class T>
FormulaSystem<T, any_size> plane_system(const std::string& text) {
  return make_formula_system<T, any_size>({"test", text, parse_formula(text), {"q1", "q2"}, {"w1", "w2"}, {}, {}, nullptr});
}

// A separable system with a non-diagonal mass: L = ½ wᵀMw − V(q), M = [[2, 1/2], [1/2, 1]],
// V = (x² + y²)/2 + x²y − y³/3 (Hénon–Heiles).
template <class T>
FormulaSystem<T, any_size> massive_henon_heiles() {
  return plane_system<T>("(2*w1^2 + w1*w2 + w2^2)/2 - (q1^2 + q2^2)/2 - q1^2*q2 + q2^3/3");
}

// Not separable: a magnetic term couples q and w.
template <class T>
FormulaSystem<T, any_size> magnetic_plane() {
  return plane_system<T>("(w1^2 + w2^2)/2 + (q1*w2 - q2*w1)/2 - (q1^2 + q2^2)/2");
}

// (q1, q2, w1, w2) as a state of two coordinates.
template <class T>
State<T, any_size> plane_state(const T& q1, const T& q2, const T& w1, const T& w2) {
  State<T, any_size> x{Vector<T, any_size>(2), Vector<T, any_size>(2)};
  x.q << q1, q2;
  x.w << w1, w2;
  return x;
}

// One step of `map` on (q, p): (q, p) ↦ (q', p') with w = M⁻¹p, p' = M w'.
template <class T, class Map>
Vector<T, any_size> step_on_phase(const Map& map, const SeparableSystem<T, any_size>& separable, const T& h,
                                  const Vector<T, any_size>& y) {
  State<T, any_size> s{y.head(2), separable.inverse_mass * y.tail(2)};
  const State<T, any_size> next = map->step(s, h);
  Vector<T, any_size> out(4);
  out << next.q, separable.mass * next.w;
  return out;
}

template <class T>
class OdeintMapTest : public testing::ScalarTest<T> {
 protected:
  FormulaSystem<T, any_size> system;
  State<T, any_size> initial;
  void SetUp() override {
    testing::ScalarTest<T>::SetUp();
    system = massive_henon_heiles<T>();
    initial = plane_state<T>(T(1) / 10, T(1) / 5, T(3) / 10, -T(1) / 10);
  }
  std::shared_ptr<const OneStepMap<T, any_size>> stepper(const std::string& name) const {
    return make_odeint_map<T, any_size>(name, separable_form(system, initial));
  }
};
TYPED_TEST_SUITE(OdeintMapTest, testing::Scalars, testing::ScalarNames);

// q_k and p_k = M w_k of odeint's velocity_verlet equal the trapezoid DEL's q_k and
// p_begin(q_k, q_k+1), started by p_begin(q_0, q_1) = M w_0, over 64 steps.
TYPED_TEST(OdeintMapTest, VelocityVerletIsTheTrapezoidVariationalIntegrator) {
  using T = TypeParam;
  const T h = T(1) / 8;
  const int N = 64;
  DelScheme<T> trapezoid;
  trapezoid.future.rule = QxQRule::trapezoid;
  trapezoid.past = trapezoid.future;
  const Vector<T, any_size> q1 = start_from_momentum(this->system, trapezoid.future, this->initial.q, this->initial.w, h);
  const auto del = del_trajectory(this->system, trapezoid, this->initial.q, q1, h, N);
  const auto verlet = this->stepper("velocity_verlet");
  const Matrix<T, any_size, any_size> mass = separable_form(this->system, this->initial).mass;
  State<T, any_size> x = this->initial;
  const T tolerance = T(N) * this->working_tolerance();
  for (int k = 0; k < N; ++k) {
    const Vector<T, any_size> p = discrete_legendre(this->system, trapezoid.future, del.q[k], del.q[k + 1], h).p_begin;
    EXPECT_LE((max_norm<T, any_size>(Vector<T, any_size>(del.q[k] - x.q))), tolerance) << "q at step " << k;
    EXPECT_LE((max_norm<T, any_size>(Vector<T, any_size>(p - mass * x.w))), tolerance) << "p at step " << k;
    x = verlet->step(x, h);
  }
}

// JᵀΩJ = Ω to working precision for the three symplectic steppers; far from it for runge_kutta4.
TYPED_TEST(OdeintMapTest, SymplecticStepsAndTheRungeKuttaControl) {
  using T = TypeParam;
  const T h = T(1) / 4;
  for (const auto& info : odeint_steppers()) {
    const T defect = symplecticity_defect<T, any_size>(this->stepper(info.name)->jacobian(this->initial, h));
    if (info.symplectic)
      EXPECT_LE(defect, this->working_tolerance()) << info.name;
    else
      EXPECT_GT(defect, T(1) / 1000000000) << info.name << ": a defect of order h^5 expected";
  }
}

// The jets' Jacobian equals central differences of the map on (q, p) with step δ = 10^-20 at
// 60 digits: an O(δ²) = 10^-40 difference, against a tolerance of 10^-30.
TEST(OdeintMapJacobian, IsTheDerivativeOfTheStep) {
  PrecisionGuard guard(60);
  using T = mpfr_real;
  const auto system = massive_henon_heiles<T>();
  const State<T, any_size> x = plane_state<T>(T(1) / 10, T(1) / 5, T(3) / 10, -T(1) / 10);
  const auto separable = separable_form(system, x);
  const T h = T(1) / 4, delta = testing::ten_to_minus<T>(20);
  auto on_phase = [&](const auto& map, const Vector<T, any_size>& y) {
    return step_on_phase(map, separable, h, y);
  };
  Vector<T, any_size> y(4);
  y << x.q, separable.mass * x.w;
  for (const auto& info : odeint_steppers()) {
    const auto map = make_odeint_map<T, any_size>(info.name, separable);
    const Matrix<T, any_size, any_size> jacobian = map->jacobian(x, h);
    for (int j = 0; j < 4; ++j) {
      Vector<T, any_size> plus = y, minus = y;
      plus[j] += delta, minus[j] -= delta;
      const Vector<T, any_size> column = (on_phase(map, plus) - on_phase(map, minus)) / (2 * delta);
      EXPECT_LE((max_norm<T, any_size>(Vector<T, any_size>(column - jacobian.col(j)))), testing::ten_to_minus<T>(30))
          << info.name << ", column " << j;
    }
  }
}

// The check symplecticity runs on the step it judges (compare_with_differences), in every scalar:
// each stepper's Jacobian agrees with central differences of its own step on (q, p); the
// Jacobian of a step of h/2 — the seeded fault that once went unseen — and that of another
// stepper are rejected.
TYPED_TEST(OdeintMapTest, TheJacobianCheckTellsTheStepItBelongsTo) {
  using T = TypeParam;
  const T h = T(1) / 4;
  const auto separable = separable_form(this->system, this->initial);
  Vector<T, any_size> y(4);
  y << this->initial.q, separable.mass * this->initial.w;
  auto check = [&](const auto& map, const Matrix<T, any_size, any_size>& jacobian) {
    auto on_phase = [&](const Vector<T, any_size>& x) { return step_on_phase(map, separable, h, x); };
    return compare_with_differences<T, any_size>(on_phase, y, jacobian, Vector<T, any_size>(y.cwiseAbs()));
  };
  for (const auto& info : odeint_steppers()) {
    const auto map = this->stepper(info.name);
    const auto right = check(map, map->jacobian(this->initial, h));
    EXPECT_TRUE(right.holds) << info.name << ": " << right.mismatch << " > " << right.allowed;
    const auto half = check(map, map->jacobian(this->initial, h / 2));
    EXPECT_FALSE(half.holds) << info.name << ": " << half.mismatch << " <= " << half.allowed;
  }
  const auto verlet = this->stepper("velocity_verlet"), rk4 = this->stepper("runge_kutta4");
  const auto other = check(verlet, rk4->jacobian(this->initial, h));
  EXPECT_FALSE(other.holds) << other.mismatch << " <= " << other.allowed;
}

// A magnetic term makes d2L/dw dq nonzero: refused, naming the entry by its components (±B/2 at
// (1, 2) and (2, 1)); the separable system passes.
TEST(OdeintMapSeparability, RefusesACoupledLagrangian) {
  const State<double, any_size> x = plane_state<double>(0.5, 0.25, 0.125, -0.5);
  const auto defect = separability_defect(magnetic_plane<double>(), std::vector<State<double, any_size>>{x});
  ASSERT_TRUE(defect.has_value());
  EXPECT_TRUE(defect->quantity == "d2L/dw_1 dq_2" || defect->quantity == "d2L/dw_2 dq_1")
      << defect->quantity;
  EXPECT_FALSE(separability_defect(massive_henon_heiles<double>(), std::vector<State<double, any_size>>{x, x}).has_value());
}

}  // namespace
}  // namespace vivv
