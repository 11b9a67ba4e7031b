// Time in L (core/lagrangian/lagrangian.hpp: at_time; Marsden & West, Acta Numerica 2001, §4): a
// formula L that uses t, sized at run time, in double, float128 and MPFR, on two systems whose
// solutions are known in closed form:
//   - a driven oscillator, L = v²/2 − x²/2 + F x cos(Ωt): x'' = −x + F cos(Ωt);
//   - the Caldirola–Kanai oscillator, L = e^{γt} (v²/2 − x²/2): x'' = −x − γx', which only the
//     term ∂²L/∂w∂t of d/dt ∂L/∂w makes damped.
// Checked: every rule that is a sum of L on the segment evaluates L at its points' times
// t_b + f·h, in its value (against the formula written out here) and in its Legendre transforms
// (the sparse path against dense jets); the Euler–Lagrange acceleration holds ∂²L/∂w∂t, and the
// inverse Legendre transform leaves the entries in t out; the DEL
// from t_0 ≠ 0 converges at the rule's order (midpoint 2, Galerkin of degree 2 on 2 Gauss nodes 4);
// the exact discrete Lagrangian and the expansion of L_d − L_d^E in h start at the segment's time
// (against the closed forms' action and momenta; the rule with its time at t_b shows E_2 ≠ 0).
// Negative control: the same run with the rules' times h/2 late — the bug of a quadrature point at
// t_k + h/2 where t_k belongs — converges at order 1, and the order check below rejects it.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cases/formula_parser.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/qxq/del_evolution.hpp"
#include "core/qxq/discrete_lagrangian.hpp"
#include "core/structure/energy.hpp"
#include "core/formulas/formula_discretization.hpp"
#include "core/numerics/quadrature.hpp"
#include "references/exact_discrete_lagrangian.hpp"
#include "references/lagrangian_error_expansion.hpp"
#include "references/taylor_reference.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(TimeDependentTest, Scalars);

FormulaSystemDefinition time_dependent(const std::string& text, std::vector<std::pair<std::string, std::string>> parameters) {
  FormulaSystemDefinition definition{"time-dependent", text, parse_formula(text), {"x"}, {"v"}, std::move(parameters),
                                     {}, nullptr};
  definition.time_dependent = true;
  return definition;
}

// F = 1/2, Ω = 3/2; γ = 3/10.
FormulaSystemDefinition driven() { return time_dependent("v^2/2 - x^2/2 + F*x*cos(W*t)", {{"F", "0.5"}, {"W", "1.5"}}); }
FormulaSystemDefinition caldirola_kanai() { return time_dependent("exp(g*t)*(v^2/2 - x^2/2)", {{"g", "0.3"}}); }

// (x, x') at t of each from (x0, v0) at t0.
template <class T>
std::pair<T, T> driven_motion(const T& t0, const T& x0, const T& v0, const T& t) {
  using std::cos, std::sin;
  const T F = T(1) / 2, W = T(3) / 2, forced = F / (1 - W * W);
  // x = a cos t + b sin t + forced·cos(Ωt), a and b from x(t0) and x'(t0).
  const T rx = x0 - forced * cos(W * t0), rv = v0 + forced * W * sin(W * t0);
  const T a = rx * cos(t0) - rv * sin(t0), b = rx * sin(t0) + rv * cos(t0);
  return {a * cos(t) + b * sin(t) + forced * cos(W * t), -a * sin(t) + b * cos(t) - forced * W * sin(W * t)};
}

template <class T>
std::pair<T, T> caldirola_kanai_motion(const T& t0, const T& x0, const T& v0, const T& t) {
  using std::cos, std::exp, std::sin, std::sqrt;
  const T g = T(3) / 10, w = sqrt(1 - g * g / 4), s = t - t0;
  const T a = x0, b = (v0 + g * x0 / 2) / w, decay = exp(-g * s / 2);
  const T x = decay * (a * cos(w * s) + b * sin(w * s));
  return {x, -g / 2 * x + decay * w * (-a * sin(w * s) + b * cos(w * s))};
}

template <class T>
T driven_solution(const T& t0, const T& x0, const T& v0, const T& t) {
  return driven_motion(t0, x0, v0, t).first;
}

template <class T>
T caldirola_kanai_solution(const T& t0, const T& x0, const T& v0, const T& t) {
  return caldirola_kanai_motion(t0, x0, v0, t).first;
}

template <class T>
QxQDiscretization<T> rule(QxQRule kind, const T& parameter = T(1) / 2) {
  QxQDiscretization<T> d;
  d.rule = kind;
  d.parameter = parameter;
  return d;
}

template <class T>
QxQDiscretization<T> galerkin(int degree, int nodes) {
  QxQDiscretization<T> d;
  d.rule = QxQRule::galerkin;
  d.galerkin = std::make_shared<const GalerkinRule<T>>(GalerkinSpec{degree, false, nodes});
  return d;
}

TYPED_TEST(TimeDependentTest, RulesEvaluateLAtTheirPointsTimes) {
  using T = TypeParam;
  using V = Vector<T, any_size>;
  const auto system = at_time(make_formula_system<T, any_size>(driven()), T(7) / 10);
  ASSERT_TRUE(depends_on_time(system));
  const T h = T(1) / 8, t_b = T(7) / 10;
  const V q_b = V::Constant(1, T(3) / 10), q_e = V::Constant(1, T(1) / 5);
  const auto L = [&](const T& t, const T& x) {
    using std::cos;
    const T v = (q_e[0] - q_b[0]) / h;
    return v * v / 2 - x * x / 2 + x * cos(T(3) / 2 * t) / 2;
  };
  const auto point = [&](const T& f) { return (1 - f) * q_b[0] + f * q_e[0]; };
  const T alpha = T(3) / 10;
  struct Case {
    QxQDiscretization<T> discretization;
    T expected;
  };
  const std::vector<Case> cases = {
      {rule<T>(QxQRule::left_rectangle), h * L(t_b, q_b[0])},
      {rule<T>(QxQRule::right_rectangle), h * L(t_b + h, q_e[0])},
      {rule<T>(QxQRule::midpoint), h * L(t_b + h / 2, point(T(1) / 2))},
      {rule<T>(QxQRule::alpha, alpha), h * L(t_b + alpha * h, point(alpha))},
      {rule<T>(QxQRule::trapezoid), h / 2 * (L(t_b, q_b[0]) + L(t_b + h, q_e[0]))},
      {rule<T>(QxQRule::weighted, alpha), h * ((1 - alpha) * L(t_b, q_b[0]) + alpha * L(t_b + h, q_e[0]))},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(rule_name(c.discretization.rule));
    const T value = discrete_lagrangian(system, c.discretization, as_point<T, any_size>(q_b), as_point<T, any_size>(q_e), h);
    EXPECT_LE(abs(T(value - c.expected)), this->working_tolerance()) << value << " vs " << c.expected;
    // The Legendre transforms: the sparse path (L's tape with t as an input) against dense jets
    // (L at the points' times, t a constant).
    const auto sparse = discrete_momenta(system, c.discretization, q_b, q_e, h);
    const auto dense = discrete_lagrangian_jet<1>(system, c.discretization, q_b, q_e, h);
    EXPECT_LE(abs(T(sparse.value - c.expected)), this->working_tolerance());
    EXPECT_LE(abs(T(sparse.p_begin[0] + dense.gradient[0])), this->working_tolerance());
    EXPECT_LE(abs(T(sparse.p_end[0] - dense.gradient[1])), this->working_tolerance());
    // A different start time moves every point's time: L_d changes (F cos(Ωt) is not constant).
    EXPECT_GT(abs(T(discrete_momenta(at_time(system, t_b + h / 2), c.discretization, q_b, q_e, h).value - value)),
              T(1) / 100000);
  }
}

TYPED_TEST(TimeDependentTest, EulerLagrangeAccelerationHoldsTheTimeDerivativeOfTheMomentum) {
  using T = TypeParam;
  using V = Vector<T, any_size>;
  const T t = T(7) / 10, g = T(3) / 10;
  const auto system = at_time(make_formula_system<T, any_size>(caldirola_kanai()), t);
  const V q = V::Constant(1, T(2) / 5), w = V::Constant(1, T(-3) / 10);
  const V a = euler_lagrange_acceleration(system, q, w);
  EXPECT_LE(abs(T(a[0] - (-q[0] - g * w[0]))), this->working_tolerance()) << a[0];
  using std::exp;
  EXPECT_LE(abs(T(momentum(system, q, w)[0] - exp(g * t) * w[0])), this->working_tolerance());
  // The inverse Legendre transform reads ∂²L/∂w² alone, not the entries in t: w from p = e^{γt} w.
  const V p = V::Constant(1, T(exp(g * t) * w[0]));
  EXPECT_LE(abs(T(velocity_for_momentum(system, q, p, V::Constant(1, T(0)))[0] - w[0])), this->working_tolerance());
}

// The order observed between N and 2N steps of the DEL from (x0, v0) at t0 over [t0, t0 + 2], with
// the rules' times `late`·h after where they belong.
template <class T>
double observed_order(const FormulaSystemDefinition& definition, T (*solution)(const T&, const T&, const T&, const T&),
                      const QxQDiscretization<T>& discretization, int steps, const T& late = T(0)) {
  using V = Vector<T, any_size>;
  const auto system = make_formula_system<T, any_size>(definition);
  const T t0 = T(3) / 10, x0 = T(1) / 2, v0 = T(-1) / 5, span = 2;
  const V q0 = V::Constant(1, x0), w0 = V::Constant(1, v0);
  auto error = [&](int n) {
    const T h = span / n;
    // The start's momentum is the system's at t0; the rules run `late`.
    const V q1 = next_configuration(at_time(system, t0 + late * h), discretization, q0,
                                    V(momentum(at_time(system, t0), q0, w0)), V(q0 + h * w0), h, "start");
    const auto run = del_trajectory(at_time(system, t0 + late * h), matched_scheme(discretization), q0, q1, h, n);
    using std::abs;
    return abs(T(run.q.back()[0] - solution(t0, x0, v0, t0 + span)));
  };
  using std::log2;
  return static_cast<double>(log2(T(error(steps) / error(2 * steps))));
}

TYPED_TEST(TimeDependentTest, DelConvergesAtTheRulesOrderFromAnyStartTime) {
  using T = TypeParam;
  for (const bool damped : {false, true}) {
    SCOPED_TRACE(damped ? "Caldirola-Kanai" : "driven");
    const FormulaSystemDefinition definition = damped ? caldirola_kanai() : driven();
    T (*solution)(const T&, const T&, const T&, const T&) = damped ? caldirola_kanai_solution<T> : driven_solution<T>;
    EXPECT_NEAR(observed_order<T>(definition, solution, rule<T>(QxQRule::midpoint), 40), 2.0, 0.1);
    EXPECT_NEAR(observed_order<T>(definition, solution, rule<T>(QxQRule::trapezoid), 40), 2.0, 0.1);
    EXPECT_NEAR(observed_order<T>(definition, solution, galerkin<T>(2, 2), 10), 4.0, 0.25);
    // Negative control: the midpoint rule's point at t_k + h where t_k + h/2 belongs, an O(h)
    // error in the force: order 1.
    const double late = observed_order<T>(definition, solution, rule<T>(QxQRule::midpoint), 40, T(1) / 2);
    EXPECT_NEAR(late, 1.0, 0.2);
  }
}

// The Taylor reference of an L that depends on t integrates (q, t) with t' = 1 from the system's
// time: against the closed forms, forward and backward, from t0 = 0.3 and from t0 = 10⁶. Its
// error is about 10⁻⁶ of its tolerance at either t0 with the time left out of the step control's
// norms (TaylorIntegrator::clock); counted among the coordinates, t = 10⁶ loosened the control a
// million times: 5 times the tolerance in double, 0.02 of it in MPFR (measured when this test was
// written). Hence the bound of a hundredth of the tolerance, which both would break.
TYPED_TEST(TimeDependentTest, TaylorReferenceFollowsTheClosedFormsFromTheSystemsTime) {
  using T = TypeParam;
  using V = Vector<T, any_size>;
  const T x0 = T(1) / 2, v0 = T(-1) / 5;
  const State<T, any_size> start{V::Constant(1, x0), V::Constant(1, v0)};
  for (const bool damped : {false, true}) {
    SCOPED_TRACE(damped ? "Caldirola-Kanai" : "driven");
    for (const T& t0 : {T(3) / 10, T(1000000)}) {
      if (damped && t0 > 1) continue;  // e^{γt} overflows nothing, but is 10^130: the driven case suffices
      const auto system = at_time(make_formula_system<T, any_size>(damped ? caldirola_kanai() : driven()), t0);
      const T tolerance = testing::reference_tolerance<T>();
      const TaylorReference<FormulaSystem<T, any_size>> reference(system, tolerance);
      for (const T& span : {T(5), T(-2)}) {
        const State<T, any_size> end = reference.advance(start, span);
        const auto [x, v] = damped ? caldirola_kanai_motion(t0, x0, v0, T(t0 + span)) : driven_motion(t0, x0, v0, T(t0 + span));
        using std::abs;
        const T bound = reference.tolerance() / 100;
        EXPECT_LE(abs(T(end.q[0] - x)), bound * (1 + abs(x))) << "t0 " << t0 << ", span " << span;
        EXPECT_LE(abs(T(end.w[0] - v)), bound * (1 + abs(v))) << "t0 " << t0 << ", span " << span;
      }
      // The reference's own cross-check agrees.
      EXPECT_LE(reference.estimate_error(start, T(5)), reference.tolerance());
    }
  }
}

// The exact discrete Lagrangian of an L that depends on t starts its segment at the system's time
// t_b: on the driven oscillator, L_d^E(q_b, q_e; h) against the action of the closed-form solution
// through q_b at t_b and q_e at t_b + h (its own Gauss–Legendre quadrature of 24 nodes), and the end
// momenta against that solution's; on the Caldirola–Kanai oscillator p = e^{γt} v, so p_end read at
// t_b in place of t_b + h is off by e^{γh}. And the expansion of L_d − L_d^E in h (lagrangian-order's
// exact coefficients) starts there: the midpoint rule's E_0 … E_2 vanish and its E_3 is the measured
// (L_d − L_d^E)/h³ in the limit; the rule with its time at t_b (an expression) has E_2 ≠ 0.
TYPED_TEST(TimeDependentTest, ExactDiscreteLagrangianAndItsExpansionStartAtTheSegmentsTime) {
  using T = TypeParam;
  using V = Vector<T, any_size>;
  using std::abs, std::cos, std::exp, std::pow, std::sin;
  const T t_b = T(7) / 10, q_b = T(1) / 2, w_b = T(-1) / 5;
  const T tolerance = testing::reference_tolerance<T>();
  const auto driven_system = at_time(make_formula_system<T, any_size>(driven()), t_b);
  for (const T& h : {T(1) / 2, T(1) / 8}) {
    const T q_e = driven_solution(t_b, q_b, w_b, T(t_b + h));
    ExactDiscreteLagrangian<FormulaSystem<T, any_size>> exact(driven_system, tolerance);
    const auto value = exact(V::Constant(1, q_b), V::Constant(1, q_e), h);
    ASSERT_TRUE(value.converged);
    const auto quadrature = gauss_legendre<T>(24);
    const T action = integrate(quadrature, t_b, T(t_b + h), [&](const T& t) {
      const auto [x, v] = driven_motion(t_b, q_b, w_b, t);
      return T(v * v / 2 - x * x / 2 + x * cos(T(3) / 2 * t) / 2);
    });
    const T bound = 1000 * tolerance;
    EXPECT_LE(abs(T(value.value - action)), bound) << "h " << h;
    EXPECT_LE(abs(T(value.p_begin[0] - w_b)), bound) << "h " << h;
    EXPECT_LE(abs(T(value.p_end[0] - driven_motion(t_b, q_b, w_b, T(t_b + h)).second)), bound) << "h " << h;
  }
  const auto damped = at_time(make_formula_system<T, any_size>(caldirola_kanai()), t_b);
  const T h = T(1) / 4;
  const auto [x_e, v_e] = caldirola_kanai_motion(t_b, q_b, w_b, T(t_b + h));
  ExactDiscreteLagrangian<FormulaSystem<T, any_size>> exact(damped, tolerance);
  const auto value = exact(V::Constant(1, q_b), V::Constant(1, x_e), h);
  ASSERT_TRUE(value.converged);
  const T g = T(3) / 10;
  EXPECT_LE(abs(T(value.p_begin[0] - exp(g * t_b) * w_b)), 1000 * tolerance);
  EXPECT_LE(abs(T(value.p_end[0] - exp(g * (t_b + h)) * v_e)), 1000 * tolerance);

  // The expansion, from (q_b, w_b) at t_b.
  const V q0 = V::Constant(1, q_b), w0 = V::Constant(1, w_b);
  const auto midpoint = lagrangian_error_expansion(driven_system, rule<T>(QxQRule::midpoint), q0, w0, 4);
  for (int k = 0; k <= 2; ++k) EXPECT_LE(abs(midpoint[k]), 100 * epsilon<T>()) << "E_" << k;
  const T small = T(1) / 64;
  const T q_small = driven_solution(t_b, q_b, w_b, T(t_b + small));
  ExactDiscreteLagrangian<FormulaSystem<T, any_size>> exact_small(driven_system, tolerance);
  const T measured = (discrete_lagrangian(driven_system, rule<T>(QxQRule::midpoint), as_point<T, any_size>(q0),
                                          as_point<T, any_size>(V::Constant(1, q_small)), small) -
                      exact_small(q0, V::Constant(1, q_small), small).value) / pow(small, 3);
  // (L_d − L_d^E)/h³ = E_3 + O(h).
  EXPECT_LE(abs(T(measured - midpoint[3])), abs(midpoint[3]) / 10 + T(small)) << measured << " vs " << midpoint[3];
  const std::string late = "h*L((qb + qe)/2, (qe - qb)/h, t)";
  const auto at_start = lagrangian_error_expansion(
      driven_system, expression_discretization(driven_system, late, parse_formula(late), {}, 2), q0, w0, 4);
  EXPECT_LE(abs(at_start[0]), 100 * epsilon<T>());
  EXPECT_LE(abs(at_start[1]), 100 * epsilon<T>());
  EXPECT_GT(abs(at_start[2]), T(1) / 100) << "the time at t_b where t_b + h/2 belongs shows in E_2";
}

}  // namespace
}  // namespace vivv
