#include "references/closed_forms.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "references/extrapolation_flow.hpp"
#include "references/reference_flow.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(ClosedFormsTest, Scalars);

template <class T>
State<T, 1> state(const std::string& q, const std::string& w) {
  State<T, 1> v;
  v.q[0] = from_decimal<T>(q);
  v.w[0] = from_decimal<T>(w);
  return v;
}

// Pendulum states covering every branch, w0 < 0 and q0 outside (−π, π).
struct PendulumCase {
  std::string k, q0, w0, t;
  PendulumMotion motion;
};
const std::vector<PendulumCase>& pendulum_cases() {
  static const std::vector<PendulumCase> cases = {
      {"1", "1", "0", "10", PendulumMotion::libration},
      {"1", "-2.5", "0.5", "-7", PendulumMotion::libration},     // amplitude near π
      {"1", "7", "1", "-10", PendulumMotion::libration},         // q0 − 2π = 0.72
      {"1", "3.5", "0", "5", PendulumMotion::libration},         // q0 − 2π = −2.78
      {"2.25", "0.5", "-2.5", "10", PendulumMotion::libration},  // w0 < 0
      {"1", "0.5", "-2.5", "10", PendulumMotion::rotation},      // w0 < 0
      {"1", "-9", "-2.25", "6", PendulumMotion::rotation},       // q0 + 2π = −2.72
      {"0.5", "2", "1.75", "-8", PendulumMotion::rotation},
  };
  return cases;
}

// The harmonic oscillator's closed form and the extrapolation flow agree to the tolerance.
TYPED_TEST(ClosedFormsTest, HarmonicOscillatorMatchesTheExtrapolationFlow) {
  using T = TypeParam;
  HarmonicOscillator<T> system;
  system.omega = T(3) / 2;
  const T tolerance = testing::reference_tolerance<T>();
  for (const auto& [q0, w0, t] : std::vector<std::array<std::string, 3>>{
           {"1", "0", "2.5"}, {"-0.25", "2", "-1.75"}, {"3", "-1", "6"}}) {
    SCOPED_TRACE("q0 = " + q0 + ", w0 = " + w0 + ", t = " + t);
    State<T, 1> start = state<T>(q0, w0);
    State<T, 1> closed = harmonic_oscillator_flow(system, start, from_decimal<T>(t));
    State<T, 1> integrated = extrapolation_flow(system, start, from_decimal<T>(t), tolerance).state;
    EXPECT_TRUE(within_tolerance(integrated, closed, tolerance))
        << "distance " << to_decimal<T>(state_distance(integrated, closed));
    // E = ½ w² + ½ ω² q² is conserved by the closed form to working precision.
    T energy_start = energy(system, start.q, start.w),
      energy_end = energy(system, closed.q, closed.w);
    EXPECT_LE(abs(T(energy_end - energy_start)), this->working_tolerance() * (1 + energy_start));
  }
  // ω = 0 is free motion.
  system.omega = 0;
  State<T, 1> free = harmonic_oscillator_flow(system, state<T>("1", "-2"), T(3));
  EXPECT_EQ(free.q[0], T(-5));
  EXPECT_EQ(free.w[0], T(-2));
}

// The pendulum's closed form takes the expected branch, conserves the energy
// ½ w² + k (1 − cos q) to working precision, and agrees with the
// extrapolation flow to the reference tolerance (at 200 bits: 1e-50).
TYPED_TEST(ClosedFormsTest, PendulumMatchesTheExtrapolationFlowOnEveryBranch) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  for (const auto& c : pendulum_cases()) {
    SCOPED_TRACE("k = " + c.k + ", q0 = " + c.q0 + ", w0 = " + c.w0 + ", t = " + c.t);
    Pendulum<T> system;
    system.k = from_decimal<T>(c.k);
    State<T, 1> start = state<T>(c.q0, c.w0);
    const T t = from_decimal<T>(c.t);
    PendulumMotion motion;
    State<T, 1> closed = pendulum_flow(system, start, t, &motion);
    EXPECT_EQ(motion, c.motion);
    T energy_start = energy(system, start.q, start.w),
      energy_end = energy(system, closed.q, closed.w);
    EXPECT_LE(abs(T(energy_end - energy_start)), this->working_tolerance() * (1 + energy_start));
    State<T, 1> integrated = extrapolation_flow(system, start, t, tolerance).state;
    EXPECT_TRUE(within_tolerance(integrated, closed, tolerance))
        << "distance " << to_decimal<T>(state_distance(integrated, closed)) << ", tolerance "
        << to_decimal<T>(tolerance);
  }
}

// Negative control: the same agreement check fails for a wrong flow, the
// closed form of a pendulum whose k is off by 1000 tolerances.
TYPED_TEST(ClosedFormsTest, AgreementCheckRejectsAPendulumWithPerturbedK) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  Pendulum<T> system, perturbed;
  perturbed.k = system.k * (1 + 1000 * tolerance);
  State<T, 1> start = state<T>("1", "0");
  const T t = 10;
  State<T, 1> integrated = extrapolation_flow(system, start, t, tolerance).state;
  EXPECT_TRUE(within_tolerance(integrated, pendulum_flow(system, start, t), tolerance));
  EXPECT_FALSE(within_tolerance(integrated, pendulum_flow(perturbed, start, t), tolerance));
}

// The closed form agrees with itself at 100 digits to closed_form_tolerance
// times (1 + ‖DF_t‖), the flow's conditioning measured at 100 digits: a few
// ulps of T before the unavoidable amplification of the rounded input.
TYPED_TEST(ClosedFormsTest, PendulumIsAccurateToWorkingPrecisionAgainst100Digits) {
  using T = TypeParam;
  for (const auto& c : pendulum_cases()) {
    SCOPED_TRACE("k = " + c.k + ", q0 = " + c.q0 + ", w0 = " + c.w0 + ", t = " + c.t);
    Pendulum<T> system;
    system.k = from_decimal<T>(c.k);
    State<T, 1> end = pendulum_flow(system, state<T>(c.q0, c.w0), from_decimal<T>(c.t));
    const std::string q = to_decimal<T>(end.q[0]), w = to_decimal<T>(end.w[0]);
    const std::string tolerance = to_decimal<T>(closed_form_tolerance<T>());
    // The decimal inputs as T rounded them, so both computations start from the same state.
    const std::string k = to_decimal<T>(system.k);
    const std::string q0 = to_decimal<T>(from_decimal<T>(c.q0));
    const std::string w0 = to_decimal<T>(from_decimal<T>(c.w0));

    PrecisionGuard guard(100);
    Pendulum<mpfr_real> accurate_system;
    accurate_system.k = mpfr_real(k);
    State<mpfr_real, 1> start = state<mpfr_real>(q0, w0), computed = state<mpfr_real>(q, w);
    const mpfr_real t(c.t);
    State<mpfr_real, 1> accurate = pendulum_flow(accurate_system, start, t);
    const mpfr_real delta("1e-40");
    State<mpfr_real, 1> shifted_q = start, shifted_w = start;
    shifted_q.q[0] += delta;
    shifted_w.w[0] += delta;
    mpfr_real conditioning =
        (state_distance(pendulum_flow(accurate_system, shifted_q, t), accurate) +
         state_distance(pendulum_flow(accurate_system, shifted_w, t), accurate)) /
        delta;
    EXPECT_TRUE(
        within_tolerance(computed, accurate, mpfr_real(mpfr_real(tolerance) * (1 + conditioning))))
        << "distance " << state_distance(computed, accurate) << ", conditioning " << conditioning;
  }
}

// F_{−t} ∘ F_t = identity, up to the closed form's tolerance times the conditioning (≲ 4 here).
TYPED_TEST(ClosedFormsTest, PendulumForwardThenBackwardReturnsToTheStart) {
  using T = TypeParam;
  Pendulum<T> system;
  for (const auto& [q0, w0] : std::vector<std::array<std::string, 2>>{
           {"1", "0"}, {"0.3", "-0.8"}, {"-1.25", "1"}, {"0.5", "2.5"}, {"-20", "-3"}}) {
    SCOPED_TRACE("q0 = " + q0 + ", w0 = " + w0);
    State<T, 1> start = state<T>(q0, w0);
    const T t = T(5) / 2;
    State<T, 1> back = pendulum_flow(system, pendulum_flow(system, start, t), T(-t));
    EXPECT_TRUE(within_tolerance(back, start, T(4 * closed_form_tolerance<T>())))
        << "distance " << to_decimal<T>(state_distance(back, start));
  }
}

// F_t(q0 + 2πj, w0) = F_t(q0, w0) + (2πj, 0).
TYPED_TEST(ClosedFormsTest, PendulumCommutesWithFullTurns) {
  using T = TypeParam;
  const T two_pi = 2 * boost::math::constants::pi<T>();
  Pendulum<T> system;
  for (int turns : {3, -2}) {
    for (const auto& [q0, w0] :
         std::vector<std::array<std::string, 2>>{{"1", "0.25"}, {"-0.5", "-2.5"}}) {
      State<T, 1> start = state<T>(q0, w0), turned = start;
      turned.q[0] += turns * two_pi;
      State<T, 1> expected = pendulum_flow(system, start, T(3));
      expected.q[0] += turns * two_pi;
      EXPECT_TRUE(within_tolerance(pendulum_flow(system, turned, T(3)), expected,
                                   closed_form_tolerance<T>()))
          << "turns " << turns << ", q0 = " << q0;
    }
  }
}

// On the separatrix (κ = 1 exactly: q0 = 0, w0 = 2√k) the closed form is
// q = 2 atan(sinh(√k t)); it matches the extrapolation flow forward and backward.
TYPED_TEST(ClosedFormsTest, PendulumSeparatrixMatchesTheExtrapolationFlow) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  for (const auto& [k, w0] : std::vector<std::array<std::string, 2>>{{"1", "2"}, {"4", "-4"}}) {
    SCOPED_TRACE("k = " + k + ", w0 = " + w0);
    Pendulum<T> system;
    system.k = from_decimal<T>(k);
    State<T, 1> start = state<T>("0", w0);
    for (T t : {T(4), T(-3)}) {
      PendulumMotion motion;
      State<T, 1> closed = pendulum_flow(system, start, t, &motion);
      EXPECT_EQ(motion, PendulumMotion::separatrix);
      EXPECT_TRUE(within_tolerance(extrapolation_flow(system, start, t, tolerance).state, closed,
                                   tolerance));
    }
  }
}

// Rest at the bottom stays there; k = 0 is free motion; k < 0 (the inverted
// pendulum) is the pendulum in q − π, checked against the extrapolation flow.
TYPED_TEST(ClosedFormsTest, PendulumSpecialCases) {
  using T = TypeParam;
  Pendulum<T> system;
  PendulumMotion motion;
  State<T, 1> rest = pendulum_flow(system, state<T>("0", "0"), T(7), &motion);
  EXPECT_EQ(motion, PendulumMotion::rest);
  EXPECT_EQ(rest.q[0], T(0));
  EXPECT_EQ(rest.w[0], T(0));

  system.k = 0;
  State<T, 1> free = pendulum_flow(system, state<T>("1", "0.5"), T(-4), &motion);
  EXPECT_EQ(motion, PendulumMotion::free);
  EXPECT_EQ(free.q[0], T(-1));
  EXPECT_EQ(free.w[0], T(1) / 2);

  system.k = T(-1);
  const T tolerance = testing::reference_tolerance<T>();
  State<T, 1> start = state<T>("0.25", "0.5");
  State<T, 1> closed = pendulum_flow(system, start, T(2), &motion);
  EXPECT_EQ(motion, PendulumMotion::rotation);  // seen from the inverted pendulum's top
  EXPECT_TRUE(within_tolerance(extrapolation_flow(system, start, T(2), tolerance).state, closed,
                               tolerance));
}

TYPED_TEST(ClosedFormsTest, NonFiniteInputIsADomainError) {
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  Pendulum<T> pendulum;
  HarmonicOscillator<T> oscillator;
  State<T, 1> bad = state<T>("1", "0");
  bad.w[0] = nan;
  EXPECT_THROW(pendulum_flow(pendulum, bad, T(1)), std::domain_error);
  EXPECT_THROW(harmonic_oscillator_flow(oscillator, bad, T(1)), std::domain_error);
  EXPECT_THROW(pendulum_flow(pendulum, state<T>("1", "0"), inf), std::domain_error);
  pendulum.k = nan;
  EXPECT_THROW(pendulum_flow(pendulum, state<T>("1", "0"), T(1)), std::domain_error);
}

// Kepler states at pericentre of eccentricity e (μ = 1, a = 1), rotated by an angle
// so that both components move: q0 = (1 − e) R(φ) e1, w0 = √((1 + e)/(1 − e)) R(φ) e2.
template <class T>
State<T, 2> kepler_pericentre(const T& e, const T& angle) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  State<T, 2> start;
  const T r = 1 - e, v = sqrt(T((1 + e) / (1 - e)));
  start.q << r * cos(angle), r * sin(angle);
  start.w << -v * sin(angle), v * cos(angle);
  return start;
}

template <class T>
T kepler_energy(const State<T, 2>& v) {
  using std::sqrt;
  return v.w.squaredNorm() / 2 - 1 / sqrt(T(v.q.squaredNorm()));
}
template <class T>
T angular_momentum(const State<T, 2>& v) {
  return v.q[0] * v.w[1] - v.q[1] * v.w[0];
}

// Kepler's closed form agrees with the extrapolation flow from eccentricity 0 to 0.9, off
// pericentre too (t = 2.3 starts the second case mid-orbit), and conserves energy and
// angular momentum to working precision.
TYPED_TEST(ClosedFormsTest, KeplerMatchesTheExtrapolationFlow) {
  using T = TypeParam;
  using std::abs;
  Kepler<T> system;
  const T tolerance = testing::reference_tolerance<T>();
  for (const auto& [e, t] : std::vector<std::array<std::string, 2>>{{"0", "3"}, {"0.5", "7.5"}, {"0.9", "-4"}}) {
    SCOPED_TRACE("e = " + e + ", t = " + t);
    const State<T, 2> start = kepler_pericentre<T>(from_decimal<T>(e), T(1) / 3);
    const State<T, 2> mid = kepler_flow(system, start, T(23) / 10);
    for (const State<T, 2>& from : {start, mid}) {
      const State<T, 2> closed = kepler_flow(system, from, from_decimal<T>(t));
      const State<T, 2> integrated = extrapolation_flow(system, from, from_decimal<T>(t), tolerance).state;
      // An eccentric orbit amplifies errors by its conditioning, here at most about 100.
      EXPECT_TRUE(within_tolerance(integrated, closed, T(100 * tolerance)))
          << "distance " << to_decimal<T>(state_distance(integrated, closed));
      EXPECT_LE(abs(T(kepler_energy(closed) - kepler_energy(from))), 100 * this->working_tolerance());
      EXPECT_LE(abs(T(angular_momentum(closed) - angular_momentum(from))), 100 * this->working_tolerance());
    }
  }
}

// After whole periods 2π (a = 1, μ = 1) the orbit is back where it started; half a period
// from pericentre is apocentre, at −(1 + e)/(1 − e) times the pericentre position.
TYPED_TEST(ClosedFormsTest, KeplerReturnsAfterAPeriodAndReachesApocentreAfterHalf) {
  using T = TypeParam;
  const T pi = boost::math::constants::pi<T>();
  Kepler<T> system;
  const T e = T(1) / 2;
  const State<T, 2> start = kepler_pericentre<T>(e, T(1) / 3);
  const State<T, 2> around = kepler_flow(system, start, T(3 * 2 * pi));
  EXPECT_LE(state_distance(around, start), 100 * this->working_tolerance());
  const State<T, 2> half = kepler_flow(system, start, pi);
  const Vector<T, 2> apocentre = -(1 + e) / (1 - e) * start.q;
  EXPECT_LE(T((half.q - apocentre).cwiseAbs().maxCoeff()), 100 * this->working_tolerance());
}

// Negative controls: the agreement check fails for a Kepler flow whose μ is off by 1000
// tolerances, and an orbit that is not bound is a domain error, not a wrong answer.
TYPED_TEST(ClosedFormsTest, KeplerRejectsAPerturbedMuAndUnboundOrbits) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  Kepler<T> system, perturbed;
  perturbed.mu = 1 + 1000 * tolerance;
  const State<T, 2> start = kepler_pericentre<T>(T(1) / 2, T(0));
  const T t = 5;
  const State<T, 2> integrated = extrapolation_flow(system, start, t, tolerance).state;
  EXPECT_TRUE(within_tolerance(integrated, kepler_flow(system, start, t), T(100 * tolerance)));
  EXPECT_FALSE(within_tolerance(integrated, kepler_flow(perturbed, start, t), T(100 * tolerance)));
  State<T, 2> escaping = start;
  escaping.w[1] = 2;  // |w|² / 2 − 1/|q| = 2 − 2 = 0: parabolic
  EXPECT_THROW(kepler_flow(system, escaping, t), std::domain_error);
  State<T, 2> radial = start;
  radial.w << T(1) / 2, 0;  // zero angular momentum: through q = 0
  EXPECT_THROW(kepler_flow(system, radial, t), std::domain_error);
}

}  // namespace
}  // namespace vivv
