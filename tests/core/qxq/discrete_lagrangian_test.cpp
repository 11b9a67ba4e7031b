#include "core/qxq/discrete_lagrangian.hpp"

#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "tests/core/qxq/paper_discrete_lagrangian.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

template <class T>
class DiscreteLagrangianTest : public testing::ScalarTest<T> {
 protected:
  static QxQDiscretization<T> paper_discretization(const T& a) { return testing::paper_discrete_lagrangian(a); }
};
TYPED_TEST_SUITE(DiscreteLagrangianTest, testing::Scalars, testing::ScalarNames);

// Paper §2.3: for L_h = h L(q−, (q+ − q−)/h) + a h (q+ − q−),
//   F+L_h = g(q−)(q+ − q−)/h + a h,
//   F−L_h = g(q−)(q+ − q−)/h + h V'(q−) + a h − g'(q−)(q+ − q−)²/(2h).
TYPED_TEST(DiscreteLagrangianTest, PaperPrintedLegendreTransformsEqualAutomaticDifferentiation) {
  using T = TypeParam;
  using std::sin;
  PaperExample<T> system;
  std::mt19937 random(11);
  for (int trial = 0; trial < 20; ++trial) {
    T a = this->uniform(random, -2, 2), h = this->uniform(random, 1, 2) / 16;
    Vector<T, 1> q_minus(this->uniform(random, -2, 2));
    Vector<T, 1> q_plus(q_minus[0] + h * this->uniform(random, -2, 2));
    auto legendre = discrete_legendre(system, this->paper_discretization(a), q_minus, q_plus, h);
    T x = q_minus[0], delta = q_plus[0] - q_minus[0];
    T g = system.g(x), dg = 2 * system.g2 * x, dV = system.k * sin(x) + system.m * x;
    T f_plus = g * delta / h + a * h;
    T f_minus = g * delta / h + h * dV + a * h - dg * delta * delta / (2 * h);
    T tolerance = this->working_tolerance() * 16;
    EXPECT_LE(abs(T(legendre.p_end[0] - f_plus)), tolerance);
    EXPECT_LE(abs(T(legendre.p_begin[0] - f_minus)), tolerance);
  }
}

// Negative control for the comparison above: a sign slip in the printed
// F−L_h (−h V' instead of +h V') is detected at the same tolerance.
TYPED_TEST(DiscreteLagrangianTest, PaperLegendreComparisonDetectsASignSlip) {
  using T = TypeParam;
  using std::sin;
  PaperExample<T> system;
  T h = T(1) / 8;
  Vector<T, 1> q_minus(T(1) / 2), q_plus(T(5) / 8);
  auto legendre = discrete_legendre(system, this->paper_discretization(T(1)), q_minus, q_plus, h);
  T x = q_minus[0], delta = q_plus[0] - q_minus[0];
  T g = system.g(x), dg = 2 * system.g2 * x, dV = system.k * sin(x);
  T wrong = g * delta / h - h * dV + h - dg * delta * delta / (2 * h);
  EXPECT_GT(abs(T(legendre.p_begin[0] - wrong)), this->working_tolerance() * 16);
}

// Identities between rules, which order claims cannot see (a swapped weight β ↔ 1 − β keeps
// every order): weighted β = 0 is the left rectangle, β = 1 the right one, β = 1/2 the
// trapezoid; alpha α = 0 is the left rectangle, α = 1/2 the midpoint, α = 1 the right
// rectangle. L_d, p_begin and p_end agree to working precision at random points; the
// swapped pairs (β = 0 against the right rectangle) do not.
TYPED_TEST(DiscreteLagrangianTest, RulesWithSpecialParametersAreTheNamedRules) {
  using T = TypeParam;
  using std::abs;
  auto rule = [](QxQRule r, const T& parameter = T(1) / 2) {
    QxQDiscretization<T> d;
    d.rule = r;
    d.parameter = parameter;
    return d;
  };
  struct Identity {
    QxQDiscretization<T> general, named;
    bool equal;
  };
  const std::vector<Identity> identities = {
      {rule(QxQRule::weighted, T(0)), rule(QxQRule::left_rectangle), true},
      {rule(QxQRule::weighted, T(1)), rule(QxQRule::right_rectangle), true},
      {rule(QxQRule::weighted, T(1) / 2), rule(QxQRule::trapezoid), true},
      {rule(QxQRule::alpha, T(0)), rule(QxQRule::left_rectangle), true},
      {rule(QxQRule::alpha, T(1) / 2), rule(QxQRule::midpoint), true},
      {rule(QxQRule::alpha, T(1)), rule(QxQRule::right_rectangle), true},
      {rule(QxQRule::weighted, T(0)), rule(QxQRule::right_rectangle), false},  // β ↔ 1 − β
      {rule(QxQRule::alpha, T(0)), rule(QxQRule::right_rectangle), false},     // α ↔ 1 − α
  };
  PaperExample<T> system;
  std::mt19937 random(5);
  for (std::size_t i = 0; i < identities.size(); ++i) {
    T largest = 0;
    for (int trial = 0; trial < 10; ++trial) {
      T h = this->uniform(random, 1, 2) / 8;
      Vector<T, 1> q_b(this->uniform(random, -2, 2)), q_e(q_b[0] + h * this->uniform(random, -2, 2));
      auto one = discrete_legendre(system, identities[i].general, q_b, q_e, h);
      auto two = discrete_legendre(system, identities[i].named, q_b, q_e, h);
      using std::max;
      largest = max({largest, T(abs(T(one.value - two.value))), T(abs(T(one.p_begin[0] - two.p_begin[0]))),
                     T(abs(T(one.p_end[0] - two.p_end[0])))});
    }
    if (identities[i].equal)
      EXPECT_LE(largest, this->working_tolerance() * 16) << "identity " << i;
    else
      EXPECT_GT(largest, T(1) / 1000) << "swapped pair " << i;
  }
}

// The twin term shifts both Legendre transforms by exactly a·h^s (paper §2.3).
TYPED_TEST(DiscreteLagrangianTest, TwinTermShiftsBothTransformsByAHToTheS) {
  using T = TypeParam;
  Pendulum<T> system;
  for (QxQRule rule : {QxQRule::left_rectangle, QxQRule::midpoint, QxQRule::trapezoid}) {
    for (int power : {1, 2, 3}) {
      QxQDiscretization<T> plain;
      plain.rule = rule;
      QxQDiscretization<T> twinned = plain;
      T a = T(7) / 4, h = T(1) / 10;
      twinned.twin = TwinTerm<T>{{a}, power};
      Vector<T, 1> q_b(T(1) / 3), q_e(T(2) / 5);
      auto without = discrete_legendre(system, plain, q_b, q_e, h);
      auto with = discrete_legendre(system, twinned, q_b, q_e, h);
      using std::pow;
      T shift = a * pow(h, power);
      EXPECT_LE(abs(T(with.p_end[0] - without.p_end[0] - shift)), this->working_tolerance());
      EXPECT_LE(abs(T(with.p_begin[0] - without.p_begin[0] - shift)), this->working_tolerance());
    }
  }
}

// Paper eq. 2.5: the DEL step solves the printed equation to working precision.
TYPED_TEST(DiscreteLagrangianTest, DelStepSolvesThePaperPrintedEquation) {
  using T = TypeParam;
  using std::sin;
  PaperExample<T> system;
  T a = 1, h = T(1) / 20;
  auto scheme = matched_scheme(this->paper_discretization(a));
  Vector<T, 1> q0(T(1) / 2), q1(T(1) / 2 + h / 3);
  auto [q2, report] = del_step(system, scheme, q0, q1, h);
  ASSERT_TRUE(report.converged) << report.failure;
  auto g = [&](const T& q) { return system.g(q); };
  T dg = 2 * system.g2 * q1[0], dV = system.k * sin(q1[0]);
  T left = g(q1[0]) * (q2[0] - q1[0]) / h + h * dV + a * h -
           dg * (q2[0] - q1[0]) * (q2[0] - q1[0]) / (2 * h);
  T right = g(q0[0]) * (q1[0] - q0[0]) / h + a * h;
  EXPECT_LE(abs(T(left - right)), this->working_tolerance() * 16);
  // The DEL equation at the returned q2 (the step itself does not evaluate it there).
  const Vector<T, 1> residual =
      p_begin(system, scheme.future, q1, q2, h) - p_end(system, scheme.past, q0, q1, h);
  EXPECT_LE(abs(residual[0]), this->working_tolerance());
}

// A non-regular discrete Lagrangian is a solver error, never a silent last
// iterate: L = w − q²/2 is linear in w, so the left-rectangle
// L_d = (q_e − q_b) − h q_b²/2 has ∂²L_d/∂q_b∂q_e = 0.
template <class T>
struct LinearInVelocity {
  using Scalar = T;
  static constexpr int dimension = 1;
  template <class S>
  S lagrangian(const Point<S, 1>& q, const Point<S, 1>& w) const {
    return w[0] - q[0] * q[0] / 2;
  }
};

TYPED_TEST(DiscreteLagrangianTest, NonRegularDiscreteLagrangianIsASolverError) {
  using T = TypeParam;
  QxQDiscretization<T> left;
  left.rule = QxQRule::left_rectangle;
  auto scheme = matched_scheme(left);
  Vector<T, 1> q0(T(1)), q1(T(1));
  EXPECT_THROW(del_trajectory(LinearInVelocity<T>{}, scheme, q0, q1, T(1) / 10, 4), SolverError);
}

}  // namespace
}  // namespace vivv
