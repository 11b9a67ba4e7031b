// The signed leading coefficient of L_d − L_d^E from the Taylor expansion
// (references/lagrangian_error_expansion.hpp) against the measured signed error
// of core/qxq/discrete_lagrangian.hpp, on the harmonic oscillator, whose L_d^E has a
// closed form: every rule and a twin term, in double, quad and MPFR. Negative
// control: the expansion of β = 0.3 against the measured error of β = 0.7 (a
// swapped weight, which keeps the order) is rejected. A rule written as a formula
// expands, from its tape, to its built-in twin's coefficients; a formula with a
// pole in h is refused, not expanded.
#include "references/lagrangian_error_expansion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cases/formula_parser.hpp"
#include "cases/systems.hpp"
#include "core/formulas/formula_discretization.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

template <class T>
class LagrangianErrorExpansionTest : public testing::ScalarTest<T> {
 protected:
  // Built on use, after SetUp has set the MPFR working precision (a member initializer would
  // run before it, at the default precision).
  static HarmonicOscillator<T> oscillator() {
    HarmonicOscillator<T> system;
    system.omega = T(3) / 2;
    return system;
  }
  static T q0() { return T(1) / 3; }
  static T w0() { return T(-1) / 2; }

  // (L_d − L_d^E)(q(0), q(h); h) / h^p for the discretization d, measured: L_d by the code,
  // L_d^E = ω((q_b² + q_e²) cos ωh − 2 q_b q_e) / (2 sin ωh), q(h) in closed form.
  T measured_coefficient(const QxQDiscretization<T>& d, const T& h, int p) const {
    using std::cos, std::pow, std::sin;
    const T omega = oscillator().omega, q_begin = q0();
    const T q_end = q_begin * cos(omega * h) + w0() / omega * sin(omega * h);
    const T exact =
        omega * ((q_begin * q_begin + q_end * q_end) * cos(omega * h) - 2 * q_begin * q_end) / (2 * sin(omega * h));
    const T discrete = discrete_lagrangian(oscillator(), d, Point<T, 1>{q_begin}, Point<T, 1>{q_end}, h);
    return (discrete - exact) / pow(h, p);
  }
  std::vector<T> expansion(const QxQDiscretization<T>& d, int terms) const {
    return lagrangian_error_expansion(oscillator(), d, Vector<T, 1>(q0()), Vector<T, 1>(w0()), terms);
  }
  // |C_measured(h) − C| at h = 1/32, 1/64, 1/128.
  std::vector<T> distances(const QxQDiscretization<T>& predicted, const QxQDiscretization<T>& measured) const {
    using std::abs;
    const int r = predicted.nominal_order();
    const T leading = expansion(predicted, r + 3)[r + 1];
    std::vector<T> out;
    for (int N : {32, 64, 128}) out.push_back(abs(T(measured_coefficient(measured, T(1) / N, r + 1) - leading)));
    return out;
  }
};
TYPED_TEST_SUITE(LagrangianErrorExpansionTest, testing::Scalars, testing::ScalarNames);

template <class T>
QxQDiscretization<T> rule(QxQRule r, const T& parameter = T(1) / 2) {
  QxQDiscretization<T> d;
  d.rule = r;
  d.parameter = parameter;
  return d;
}

TYPED_TEST(LagrangianErrorExpansionTest, LeadingCoefficientMatchesTheMeasuredSignedError) {
  using T = TypeParam;
  using std::abs;
  std::vector<QxQDiscretization<T>> rules = {
      rule<T>(QxQRule::left_rectangle), rule<T>(QxQRule::right_rectangle), rule<T>(QxQRule::midpoint),
      rule<T>(QxQRule::trapezoid),      rule(QxQRule::alpha, T(3) / 10),   rule(QxQRule::weighted, T(3) / 10)};
  auto twin = rule<T>(QxQRule::midpoint);
  twin.twin = TwinTerm<T>{{T(2)}, 1};
  rules.push_back(twin);
  for (std::size_t i = 0; i < rules.size(); ++i) {
    const int r = rules[i].nominal_order();
    const auto coefficients = this->expansion(rules[i], r + 3);
    // Order r: E_0 … E_r vanish, E_{r+1} does not (on this orbit).
    for (int k = 0; k <= r; ++k)
      EXPECT_LE(abs(coefficients[k]), this->working_tolerance()) << "rule " << i << ", E_" << k;
    EXPECT_GT(abs(coefficients[r + 1]), T(1) / 1000) << "rule " << i;
    // (L_d − L_d^E)/h^{r+1} → E_{r+1} at order 1.
    const auto d = this->distances(rules[i], rules[i]);
    for (std::size_t k = 0; k + 1 < d.size(); ++k)
      EXPECT_GT(d[k] / d[k + 1], T(17) / 10) << "rule " << i << " at step " << k;
    EXPECT_LT(d.back(), abs(coefficients[r + 1]) / 4) << "rule " << i;
  }
}

TYPED_TEST(LagrangianErrorExpansionTest, ASwappedWeightIsSeenAlthoughItKeepsTheOrder) {
  using T = TypeParam;
  const auto predicted = rule(QxQRule::weighted, T(3) / 10), swapped = rule(QxQRule::weighted, T(7) / 10);
  ASSERT_EQ(predicted.nominal_order(), swapped.nominal_order());
  const auto d = this->distances(predicted, swapped);
  // The distance does not shrink with h: the signs of the leading coefficients differ.
  EXPECT_LT(d[0] / d[2], T(3) / 2);
  const T leading = this->expansion(predicted, 4)[2];
  using std::abs;
  EXPECT_GT(d[2], abs(leading));
}

// The formula's expansion is the built-in rule's, coefficient by coefficient, on the pendulum
// (sin inside L) — with the divisions by h the formula makes — and with a twin term.
TYPED_TEST(LagrangianErrorExpansionTest, AFormulaExpandsToItsBuiltInTwin) {
  using T = TypeParam;
  using std::abs, std::max;
  Pendulum<T> pendulum;
  const Vector<T, 1> q0(T(7) / 10), w0(T(-2) / 5);
  auto formula = [&](const std::string& text) {
    return expression_discretization(pendulum, text, parse_formula(text), {}, 2);
  };
  std::vector<std::pair<QxQDiscretization<T>, QxQDiscretization<T>>> twins = {
      {rule<T>(QxQRule::midpoint), formula("h*L((qb + qe)/2, (qe - qb)/h)")},
      {rule(QxQRule::weighted, T(3) / 10),
       formula("h*(0.7*L(qb, (qe - qb)/h) + 0.3*L(qe, (qe - qb)/h))")},
      {rule<T>(QxQRule::left_rectangle), formula("h*L(qb, (qe - qb)/h)")}};
  auto with_twin = twins[0];
  with_twin.first.twin = with_twin.second.twin = TwinTerm<T>{{T(2)}, 1};
  twins.push_back(with_twin);
  for (std::size_t i = 0; i < twins.size(); ++i) {
    const auto built_in = lagrangian_error_expansion(pendulum, twins[i].first, q0, w0, 6);
    const auto written = lagrangian_error_expansion(pendulum, twins[i].second, q0, w0, 6);
    ASSERT_EQ(written.size(), built_in.size());
    for (std::size_t k = 0; k < built_in.size(); ++k)
      EXPECT_LE(abs(T(written[k] - built_in[k])),
                this->working_tolerance() * max(T(1), T(abs(built_in[k]))))
          << "pair " << i << ", E_" << k;
  }
  // A swapped weight written as a formula is a different coefficient (the control).
  const auto swapped = lagrangian_error_expansion(
      pendulum, formula("h*(0.3*L(qb, (qe - qb)/h) + 0.7*L(qe, (qe - qb)/h))"), q0, w0, 4);
  const auto weighted = lagrangian_error_expansion(pendulum, twins[1].first, q0, w0, 4);
  EXPECT_GT(abs(T(swapped[2] - weighted[2])), abs(weighted[2]) / 2);
}

TYPED_TEST(LagrangianErrorExpansionTest, AFormulaWithAPoleInHIsRefusedNotExpanded) {
  using T = TypeParam;
  Pendulum<T> pendulum;
  const Vector<T, 1> q0(T(7) / 10), w0(T(-2) / 5);
  for (const std::string text :
       {"h*L(qb, (qe - qb)/h) + 1/h", "h*L(qb, (qe - qb)/h^2)", "sqrt((qe[1] - qb[1])^2)"}) {
    const auto d = expression_discretization(pendulum, text, parse_formula(text), {}, 1);
    EXPECT_THROW(lagrangian_error_expansion(pendulum, d, q0, w0, 4), std::domain_error) << text;
  }
}

}  // namespace
}  // namespace vivv
