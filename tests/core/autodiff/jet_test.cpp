// The jets' in-place arithmetic and the narrower jets built on it (core/autodiff/jet.hpp,
// core/lagrangian/lagrangian.hpp, core/qxq/discrete_lagrangian.hpp, core/autodiff/tape.hpp): a jet in w alone and a
// first-order jet give the very entries of the full second-order jet, bit for bit; a product of
// a jet with itself is the product of two copies; the Hessian is exactly symmetric; and a formula
// tape's reused jet buffer never carries an earlier working precision into a later one.
#include "core/autodiff/jet.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cases/formula_parser.hpp"
#include "cases/systems.hpp"
#include "core/qxq/discrete_lagrangian.hpp"
#include "core/formulas/formula_system.hpp"
#include "core/lagrangian/lagrangian.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(JetTest, Scalars);

template <class T, int n>
std::pair<Vector<T, n>, Vector<T, n>> state() {
  Vector<T, n> q, w;
  for (int i = 0; i < n; ++i) q[i] = T(3 + i) / 7, w[i] = T(2 - 3 * i) / 5;
  return {q, w};
}

// ∂L/∂w and ∂²L/∂w² from a jet in w alone are the full jet's, bit for bit; the momentum is the
// full jet's gradient entries.
template <class System>
void expect_velocity_jet_is_exact(const System& system) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  const auto [q, w] = state<T, n>();
  const auto full = lagrangian_derivatives(system, q, w);
  const auto narrow = lagrangian_in_velocity<2>(system, q, w);
  EXPECT_EQ(narrow.value, full.value);
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(narrow.gradient[i], full.dL_dw[i]) << i;
    for (int j = 0; j < n; ++j)
      EXPECT_EQ(narrow.second(i, j), full.d2L_dw2(i, j)) << i << ", " << j;
  }
  const Vector<T, n> p = momentum(system, q, w);
  for (int i = 0; i < n; ++i) EXPECT_EQ(p[i], full.dL_dw[i]) << i;
}

TYPED_TEST(JetTest, AJetInVelocityAloneGivesTheFullJetsEntries) {
  using T = TypeParam;
  expect_velocity_jet_is_exact(Pendulum<T>{});
  expect_velocity_jet_is_exact(PaperExample<T>{});
  expect_velocity_jet_is_exact(RelativisticParticle<T>{});
  expect_velocity_jet_is_exact(ChargedParticle<T>{});
  expect_velocity_jet_is_exact(Kepler<T>{});
  expect_velocity_jet_is_exact(DoublePendulum<T>{});
}

// p_begin and p_end from first-order jets are discrete_legendre's, bit for bit, for every rule
// the jets evaluate.
TYPED_TEST(JetTest, FirstOrderDiscreteMomentaAreTheFullJetsMomenta) {
  using T = TypeParam;
  const DoublePendulum<T> system;
  const auto [q_b, w] = state<T, 2>();
  const Vector<T, 2> q_e = q_b + w / 10;
  const T h = T(1) / 10;
  for (QxQRule rule : {QxQRule::midpoint, QxQRule::trapezoid, QxQRule::alpha,
                       QxQRule::left_rectangle, QxQRule::right_rectangle, QxQRule::weighted}) {
    QxQDiscretization<T> d;
    d.rule = rule;
    d.parameter = T(3) / 10;
    const auto full = discrete_legendre(system, d, q_b, q_e, h);
    const auto momenta = discrete_momenta(system, d, q_b, q_e, h);
    EXPECT_EQ(momenta.value, full.value) << rule_name(rule);
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(momenta.p_begin[i], full.p_begin[i]) << rule_name(rule) << " " << i;
      EXPECT_EQ(momenta.p_end[i], full.p_end[i]) << rule_name(rule) << " " << i;
    }
  }
}

// What a DEL step's Newton reads, p_begin and ∂p_begin/∂q_e, from the jet that keeps only the
// q_b–q_e block of the Hessian: discrete_legendre's entries bit for bit, for every rule the jets
// evaluate, a twin term and a formula system. The comparison sees the rounding level: one ulp more
// in q_e changes the result.
template <class System>
void expect_block_jet_is_exact(const System& system, const std::string& label) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  const auto [q_b, w] = state<T, n>();
  const Vector<T, n> q_e = q_b + w / 10;
  const T h = T(1) / 10;
  for (QxQRule rule : {QxQRule::midpoint, QxQRule::trapezoid, QxQRule::alpha,
                       QxQRule::left_rectangle, QxQRule::right_rectangle, QxQRule::weighted}) {
    for (bool twin : {false, true}) {
      QxQDiscretization<T> d;
      d.rule = rule;
      d.parameter = T(3) / 10;
      if (twin) d.twin = TwinTerm<T>{std::vector<T>(n, T(2) / 3), 1};
      const auto full = discrete_legendre(system, d, q_b, q_e, h);
      const auto block = begin_momentum(system, d, q_b, q_e, h);
      for (int i = 0; i < n; ++i) {
        EXPECT_EQ(block.p_begin[i], full.p_begin[i]) << label << " " << rule_name(rule) << " " << i;
        for (int j = 0; j < n; ++j)
          EXPECT_EQ(block.dp_begin_dq_e(i, j), full.dp_begin_dq_e(i, j))
              << label << " " << rule_name(rule) << " " << i << ", " << j;
      }
    }
  }
  QxQDiscretization<T> midpoint;
  midpoint.rule = QxQRule::midpoint;
  Vector<T, n> nudged = q_e;
  using std::abs;
  nudged[0] += 2 * epsilon<T>() * abs(nudged[0]);
  EXPECT_NE(begin_momentum(system, midpoint, q_b, nudged, h).p_begin,
            begin_momentum(system, midpoint, q_b, q_e, h).p_begin)
      << label;
}

TYPED_TEST(JetTest, TheDelStepsBlockJetGivesTheFullJetsEntries) {
  using T = TypeParam;
  expect_block_jet_is_exact(Pendulum<T>{}, Pendulum<T>::name);
  expect_block_jet_is_exact(PaperExample<T>{}, PaperExample<T>::name);
  expect_block_jet_is_exact(RelativisticParticle<T>{}, RelativisticParticle<T>::name);
  expect_block_jet_is_exact(ChargedParticle<T>{}, ChargedParticle<T>::name);
  expect_block_jet_is_exact(Kepler<T>{}, Kepler<T>::name);
  expect_block_jet_is_exact(DoublePendulum<T>{}, DoublePendulum<T>::name);
  const std::string text =
      "(1 + q1^2/4)*w1^2/2 + w1*w2*cos(q1 - q2)/3 + w2^2/2 - sqrt(1 + q1^2 + q2^2)";
  const FormulaSystemDefinition definition{
      "formula", text, parse_formula(text), {"q1", "q2"}, {"w1", "w2"}, {}, {}, nullptr};
  expect_block_jet_is_exact(make_formula_system<T, 2>(definition), "formula");
}

// A tape computes a sine and the cosine of the same argument as one pair, from one sine and one
// cosine of its value: each is the jet's own sin or cos bit for bit, whether the formula uses both
// or one of them.
TYPED_TEST(JetTest, ATapesSineCosinePairIsTheJetsSineAndCosine) {
  using T = TypeParam;
  using J = Jet<T, 2>;
  const Point<J, 1> q{J::variable(T(3) / 10, 0)}, w{J::variable(T(7) / 10, 1)};
  const auto expect_same = [&](const std::string& text, const J& expected) {
    const FormulaSystemDefinition definition{
        "formula", text, parse_formula(text), {"q"}, {"w"}, {}, {}, nullptr};
    const J formula = make_formula_system<T, 1>(definition).lagrangian(q, w);
    EXPECT_EQ(formula.value, expected.value) << text;
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(formula.gradient[i], expected.gradient[i]) << text << " " << i;
      for (int j = 0; j < 2; ++j)
        EXPECT_EQ(formula.second(i, j), expected.second(i, j)) << text << " " << i << ", " << j;
    }
  };
  expect_same("sin(q*w) * cos(q*w)", sin(q[0] * w[0]) * cos(q[0] * w[0]));
  expect_same("cos(q*w)", cos(q[0] * w[0]));
  expect_same("sin(q*w)", sin(q[0] * w[0]));
}

// The in-place product: u *= u is u * (a copy of u), and every Hessian is exactly symmetric.
TYPED_TEST(JetTest, TheInPlaceProductOfAJetWithItselfIsTheProductOfTwoCopies) {
  using T = TypeParam;
  using J = Jet<T, 3>;
  J u = J::variable(T(3) / 10, 0) * J::variable(T(7) / 10, 1) + sin(J::variable(T(1) / 3, 2));
  u = u / (J::variable(T(2), 0) + 1);
  J self = u, copy = u;
  self *= self;
  copy *= J(u);
  EXPECT_EQ(self.value, copy.value);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(self.gradient[i], copy.gradient[i]) << i;
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(self.second(i, j), copy.second(i, j)) << i << ", " << j;
      EXPECT_EQ(self.second(i, j), self.second(j, i)) << i << ", " << j;
    }
  }
  // (u²)' = 2 u u': the product is the product, not merely consistent with itself.
  using std::abs;
  EXPECT_LE(abs(T(self.gradient[1] - 2 * u.value * u.gradient[1])),
            this->working_tolerance() * abs(self.gradient[1]));
}

// A formula system's jets come from a buffer kept between evaluations. Evaluated at 30 digits and
// then at 100, the second result is accurate to 100 digits: the buffer of 30-digit numbers is not
// reused at the higher precision.
TEST(FormulaTapeBuffer, APrecisionChangeDoesNotCarryTheEarlierPrecision) {
  const std::string text = "sin(q)*w^2/3 + exp(q*w)";
  const FormulaSystemDefinition definition{"formula", text,   parse_formula(text), {"q"}, {"w"}, {},
                                           {},        nullptr};
  using J = Jet<mpfr_real, 2>;
  const auto evaluate = [&] {
    const auto system = make_formula_system<mpfr_real, 1>(definition);
    const Point<J, 1> q{J::variable(mpfr_real(1) / 3, 0)}, w{J::variable(mpfr_real(2) / 7, 1)};
    return system.lagrangian(q, w);
  };
  {
    PrecisionGuard low(30);
    evaluate();
  }
  PrecisionGuard high(100);
  const J value = evaluate();
  const mpfr_real q = mpfr_real(1) / 3, w = mpfr_real(2) / 7;
  // ∂L/∂w = 2 sin(q) w / 3 + q exp(q w)
  const mpfr_real expected = 2 * sin(q) * w / 3 + q * exp(q * w);
  EXPECT_LE(abs(mpfr_real(value.gradient[1] - expected)), mpfr_real("1e-95"));
  EXPECT_LE(abs(mpfr_real(value.value - (sin(q) * w * w / 3 + exp(q * w)))), mpfr_real("1e-95"));
}

}  // namespace
}  // namespace vivv
