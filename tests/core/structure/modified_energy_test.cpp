// The modified energies of core/structure/modified_energy.hpp, checked before the
// modified-energy claim relies on them, in double, quad and MPFR:
// - on the harmonic oscillator the DELs rotate by exactly 2·arctan(h/2)
//   (midpoint) and 2·arcsin(h/2) (trapezoid) per step, and H̃'s coefficients
//   reproduce that frequency and the map's quadratic invariant up to O(h⁴);
// - on the pendulum H̃ is conserved to O(h⁴) and H to O(h²);
// - negative control: H₂ with a wrong sign is conserved only to O(h²).
#include "core/structure/modified_energy.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cases/systems.hpp"
#include "core/qxq/del_evolution.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(ModifiedEnergyTest, Scalars);

template <class T>
QxQDiscretization<T> plain_rule(QxQRule r) {
  QxQDiscretization<T> d;
  d.rule = r;
  return d;
}

// H̃ = a p² + b q² on the oscillator: ω̃ = 2√(ab) and the invariant's ratio b/a.
template <class T>
std::pair<T, T> oscillator_form(const ModifiedEnergyForm& form, const T& h) {
  using std::sqrt;
  const T a = T(1) / 2 + form.pUp * h * h / 24, b = T(1) / 2 + form.UU * h * h / 24;
  return {2 * sqrt(T(a * b)), b / a};
}

TYPED_TEST(ModifiedEnergyTest, TheOscillatorsExactFrequenciesFixTheCoefficients) {
  using T = TypeParam;
  using std::abs;
  using std::asin;
  using std::atan;
  using std::cos;
  using std::log2;
  HarmonicOscillator<T> oscillator;
  for (QxQRule r : {QxQRule::midpoint, QxQRule::trapezoid}) {
    SCOPED_TRACE(rule_name(r));
    const ModifiedEnergyForm form = modified_energy_form(r);
    const ModifiedEnergyForm wrong_sign{-form.pUp, -form.UU};
    T frequency_gap[2], invariant_gap[2], wrong_gap[2];
    for (int i = 0; i < 2; ++i) {
      const T h = T(1) / (8 << i);
      // The map's rotation per step, from one DEL step: q_{k+1} + q_{k−1} = 2 cos θ q_k.
      const T theta = r == QxQRule::midpoint ? T(2 * atan(h / 2)) : T(2 * asin(h / 2));
      const Vector<T, 1> q0(T(1) / 3), q1(T(1) / 2);
      const auto [q2, report] = del_step(oscillator, matched_scheme(plain_rule<T>(r)), q0, q1, h);
      EXPECT_LE(abs(T((q2[0] + q0[0]) / (2 * q1[0]) - cos(theta))), this->working_tolerance());
      // The exact quadratic invariant's ratio: 1 (midpoint keeps H), 1 − h²/4 (trapezoid).
      const T ratio = r == QxQRule::midpoint ? T(1) : T(1 - h * h / 4);
      const auto [omega, b_over_a] = oscillator_form(form, h);
      frequency_gap[i] = abs(T(omega - theta / h));
      invariant_gap[i] = abs(T(b_over_a - ratio));
      wrong_gap[i] = abs(T(oscillator_form(wrong_sign, h).first - theta / h));
    }
    // O(h⁴): halving h divides the gaps by about 16; the wrong sign leaves O(h²), about 4.
    EXPECT_NEAR(static_cast<double>(log2(T(frequency_gap[0] / frequency_gap[1]))), 4, 0.2);
    if (r == QxQRule::trapezoid)
      EXPECT_NEAR(static_cast<double>(log2(T(invariant_gap[0] / invariant_gap[1]))), 4, 0.2);
    else
      EXPECT_LE(invariant_gap[1], this->working_tolerance());
    EXPECT_NEAR(static_cast<double>(log2(T(wrong_gap[0] / wrong_gap[1]))), 2, 0.2);
  }
}

// max_k |H̃_k − H̃_0| and max_k |H_k − H_0| over T = 20 on the pendulum at step h.
template <class T>
std::pair<T, T> pendulum_drifts(QxQRule r, const ModifiedEnergyForm& form, const T& h) {
  using std::abs;
  using std::max;
  Pendulum<T> pendulum;
  const int N = static_cast<int>(20 / static_cast<double>(h));
  const Vector<T, 1> q0(T(11) / 10), q1(T(11) / 10 + h / 4);
  const auto trajectory = del_trajectory(pendulum, matched_scheme(plain_rule<T>(r)), q0, q1, h, N);
  T H0 = 0, modified0 = 0, H_drift = 0, modified_drift = 0;
  for (int k = 0; k < N; ++k) {
    const Vector<T, 1> p = discrete_legendre(pendulum, plain_rule<T>(r), trajectory.q[k], trajectory.q[k + 1], h).p_begin;
    const ModifiedEnergy<T> E = modified_energy(pendulum, form, trajectory.q[k], p, h);
    if (k == 0) H0 = E.H, modified0 = E.modified;
    H_drift = max(H_drift, T(abs(T(E.H - H0))));
    modified_drift = max(modified_drift, T(abs(T(E.modified - modified0))));
  }
  return {modified_drift, H_drift};
}

TYPED_TEST(ModifiedEnergyTest, OnThePendulumHTildeIsConservedToOrderFourAndHToOrderTwo) {
  using T = TypeParam;
  using std::log2;
  for (QxQRule r : {QxQRule::midpoint, QxQRule::trapezoid}) {
    SCOPED_TRACE(rule_name(r));
    const ModifiedEnergyForm form = modified_energy_form(r);
    const ModifiedEnergyForm wrong_sign{-form.pUp, -form.UU};
    const auto [modified_coarse, H_coarse] = pendulum_drifts<T>(r, form, T(1) / 8);
    const auto [modified_fine, H_fine] = pendulum_drifts<T>(r, form, T(1) / 16);
    EXPECT_NEAR(static_cast<double>(log2(T(modified_coarse / modified_fine))), 4, 0.3);
    EXPECT_NEAR(static_cast<double>(log2(T(H_coarse / H_fine))), 2, 0.3);
    const T wrong_coarse = pendulum_drifts<T>(r, wrong_sign, T(1) / 8).first;
    const T wrong_fine = pendulum_drifts<T>(r, wrong_sign, T(1) / 16).first;
    EXPECT_NEAR(static_cast<double>(log2(T(wrong_coarse / wrong_fine))), 2, 0.3);
  }
}

TYPED_TEST(ModifiedEnergyTest, OnlyUnitMassSeparableLagrangiansQualify) {
  using T = TypeParam;
  const Vector<T, 2> q(T(1) / 2, T(1) / 4), w(T(1) / 3, T(-1) / 5);
  const std::vector<State<T, 2>> samples = {{q, w}, {w, q}};
  EXPECT_EQ(unit_mass_defect(Kepler<T>{}, samples), "");
  EXPECT_EQ(unit_mass_defect(HenonHeiles<T>{}, samples), "");
  EXPECT_NE(unit_mass_defect(ChargedParticle<T>{}, samples), "");  // B couples w and q
  EXPECT_NE(unit_mass_defect(DoublePendulum<T>{}, samples), "");
  EXPECT_THROW(modified_energy_form(QxQRule::alpha), std::invalid_argument);
}

}  // namespace
}  // namespace vivv
