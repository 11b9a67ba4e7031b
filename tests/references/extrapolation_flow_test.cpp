#include "references/extrapolation_flow.hpp"

#include <chrono>
#include <cmath>
#include <string>

#include "cases/systems.hpp"
#include "references/closed_forms.hpp"
#include "references/reference_flow.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(ExtrapolationFlowTest, Scalars);

// Canonical angular momentum J = q1 p2 − q2 p1, p = dL/dw: conserved by rotation symmetry.
template <class System>
auto canonical_angular_momentum(const System& system, const State<typename System::Scalar, 2>& v) {
  using T = typename System::Scalar;
  Vector<T, 2> p = momentum(system, v.q, v.w);
  return T(v.q[0] * p[1] - v.q[1] * p[0]);
}

// y' = y from y(0) = 1 gives eᵗ, forward and backward, to the tolerance (the
// generic first-order integrator, local tolerance as extrapolation_flow uses it).
TYPED_TEST(ExtrapolationFlowTest, IntegratesTheExponentialForwardAndBackward) {
  using T = TypeParam;
  using std::exp;
  const T tolerance = testing::reference_tolerance<T>();
  auto field = [](const Vector<T, 1>& y) { return y; };
  for (T t : {T(3), T(-5) / 2}) {
    auto solution =
        gragg_bulirsch_stoer<T, 1>(field, Vector<T, 1>(T(1)), t, local_tolerance_for(tolerance));
    EXPECT_LE(abs(T(solution.y[0] - exp(t))), tolerance * (1 + exp(t))) << "t = " << to_decimal(t);
    EXPECT_GE(solution.report.steps, 1);
    EXPECT_GT(solution.report.function_evaluations, solution.report.steps);
    EXPECT_LE(solution.report.highest_column, solution.report.max_columns);
  }
}

// The last step lands exactly on t: a tiny t (one step) and a t that is not a
// multiple of any step agree with the closed form.
TYPED_TEST(ExtrapolationFlowTest, LandsExactlyOnTheRequestedTime) {
  using T = TypeParam;
  using std::pow;
  const T tolerance = testing::reference_tolerance<T>();
  HarmonicOscillator<T> system;
  State<T, 1> start;
  start.q[0] = 1;
  start.w[0] = T(1) / 3;
  for (T t : {T(pow(T(10), -12)), T(T(22) / 7), T(T(-13) / 3)}) {
    auto result = extrapolation_flow(system, start, t, tolerance);
    EXPECT_TRUE(
        within_tolerance(result.state, harmonic_oscillator_flow(system, start, t), tolerance))
        << "t = " << to_decimal<T>(t);
  }
  auto zero = extrapolation_flow(system, start, T(0), tolerance);
  EXPECT_EQ(zero.state.q[0], start.q[0]);
  EXPECT_EQ(zero.report.steps, 0);
}

// Forward to t, then back to 0, returns to the start within twice the tolerance.
TYPED_TEST(ExtrapolationFlowTest, ForwardThenBackwardReturnsToTheStart) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  PaperExample<T> system;
  State<T, 1> start;
  start.q[0] = T(1) / 2;
  start.w[0] = T(-3) / 4;
  const T t = 4;
  State<T, 1> there = extrapolation_flow(system, start, t, tolerance).state;
  State<T, 1> back = extrapolation_flow(system, there, T(-t), tolerance).state;
  EXPECT_TRUE(within_tolerance(back, start, T(2 * tolerance)))
      << "distance " << to_decimal<T>(state_distance(back, start));
}

// The charged particle in a magnetic field and a harmonic trap: the flow
// conserves the energy and the canonical angular momentum to the tolerance.
TYPED_TEST(ExtrapolationFlowTest, ChargedParticleConservesEnergyAndAngularMomentum) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  ChargedParticle<T> system;
  system.set({T(3) / 2, T(1) / 2});
  State<T, 2> start;
  start.q << T(1), T(-1) / 2;
  start.w << T(1) / 4, T(3) / 4;
  State<T, 2> end = extrapolation_flow(system, start, T(8), tolerance).state;
  T energy_start = energy(system, start.q, start.w), energy_end = energy(system, end.q, end.w);
  EXPECT_LE(abs(T(energy_end - energy_start)), tolerance * (1 + abs(energy_start)));
  T momentum_start = canonical_angular_momentum(system, start), momentum_end = canonical_angular_momentum(system, end);
  EXPECT_LE(abs(T(momentum_end - momentum_start)), tolerance * (1 + abs(momentum_start)));
  EXPECT_GT(state_distance(start, end), T(1) / 10);  // it did move
}

// The relativistic particle (L not quadratic in w) near the speed of light:
// substeps that overshoot |w| < 1 are retried with a smaller step, and the
// energy γ m + ½ k q² is conserved. A state with |w| = 1 is singular: an error.
TYPED_TEST(ExtrapolationFlowTest, RelativisticParticleNearTheSpeedOfLight) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  RelativisticParticle<T> system;
  system.k = 4;
  State<T, 1> start;
  start.q[0] = 0;
  start.w[0] = T(999) / 1000;
  auto result = extrapolation_flow(system, start, T(3), tolerance);
  T energy_start = energy(system, start.q, start.w);
  T energy_end = energy(system, result.state.q, result.state.w);
  EXPECT_LE(abs(T(energy_end - energy_start)), tolerance * (1 + energy_start));
  EXPECT_LT(abs(result.state.w[0]), T(1));
  start.w[0] = 1;
  EXPECT_THROW(extrapolation_flow(system, start, T(1), tolerance), SingularLagrangianError);
}

// Negative control: a flow run at too loose a local tolerance (the square root
// of the reference tolerance) fails the agreement check the real one passes.
TYPED_TEST(ExtrapolationFlowTest, AgreementCheckRejectsALooseTolerance) {
  using T = TypeParam;
  using std::sqrt;
  const T tolerance = testing::reference_tolerance<T>();
  Pendulum<T> system;
  State<T, 1> start;
  start.q[0] = 2;
  start.w[0] = T(1) / 2;
  const T t = 10;
  State<T, 1> exact = pendulum_flow(system, start, t);
  EXPECT_TRUE(
      within_tolerance(extrapolation_flow(system, start, t, tolerance).state, exact, tolerance));
  ExtrapolationOptions<T> loose_options;
  loose_options.local_tolerance = sqrt(tolerance);
  State<T, 1> loose = extrapolation_flow(system, start, t, tolerance, loose_options).state;
  EXPECT_FALSE(within_tolerance(loose, exact, tolerance))
      << "distance " << to_decimal<T>(state_distance(loose, exact));
}

TYPED_TEST(ExtrapolationFlowTest, FailuresAreErrorsNotResults) {
  using T = TypeParam;
  Pendulum<T> system;
  State<T, 1> start;
  start.q[0] = 1;
  start.w[0] = 0;
  ExtrapolationOptions<T> options;
  options.max_steps = 3;
  try {
    extrapolation_flow(system, start, T(100), testing::reference_tolerance<T>(), options);
    ADD_FAILURE() << "three steps cannot reach t = 100";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("steps"), std::string::npos) << error.what();
  }
  // Below the working-precision floor: refused up front.
  EXPECT_THROW(extrapolation_flow(system, start, T(1), T(minimum_flow_tolerance<T>() / 2)),
               std::invalid_argument);
  auto field = [](const Vector<T, 1>& y) { return y; };
  EXPECT_THROW((gragg_bulirsch_stoer<T, 1>(field, Vector<T, 1>(T(1)), T(1),
                                           T(minimum_local_tolerance<T>() / 2))),
               std::invalid_argument);
}

// The brief's target: the pendulum to 1e-50 over [0, 10] at 200 bits, well
// under a second; the time and the work are recorded as test properties.
TEST(ExtrapolationFlow, PendulumTo1e50At200BitsOverTenTimeUnits) {
  PrecisionGuard guard(60);
  ASSERT_GE(precision_bits<mpfr_real>(), 200);
  Pendulum<mpfr_real> system;
  State<mpfr_real, 1> start;
  start.q[0] = 1;
  start.w[0] = 0;
  const mpfr_real tolerance("1e-50"), t(10);
  auto begin = std::chrono::steady_clock::now();
  auto result = extrapolation_flow(system, start, t, tolerance);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  EXPECT_TRUE(within_tolerance(result.state, pendulum_flow(system, start, t), tolerance));
  ::testing::Test::RecordProperty("seconds", std::to_string(seconds));
  ::testing::Test::RecordProperty("steps", std::to_string(result.report.steps));
  ::testing::Test::RecordProperty("rejected_steps", std::to_string(result.report.rejected_steps));
  ::testing::Test::RecordProperty("function_evaluations",
                                  std::to_string(result.report.function_evaluations));
  ::testing::Test::RecordProperty("highest_column", std::to_string(result.report.highest_column));
}

// The extrapolation flow fails as fast: y'' = −10⁸ y to t = 10⁴ would need millions of
// steps; it stops at the thousandth, having evaluated the field for those only.
TEST(ExtrapolationFlowFailFast, AMotionTooFastForItsTFailsAfterAThousandSteps) {
  long evaluations = 0;
  auto field = [&](const Vector<double, 2>& y) {
    ++evaluations;
    return Vector<double, 2>(y[1], -1e8 * y[0]);
  };
  try {
    gragg_bulirsch_stoer<double, 2>(field, Vector<double, 2>(1.0, 0.0), 1e4, 1e-10);
    ADD_FAILURE() << "reached t = 1e4";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("flow would need about"), std::string::npos) << message;
    EXPECT_NE(message.find("(1000 steps reached t = "), std::string::npos) << message;
  }
  // About 65 evaluations a step here: a thousand steps, not the limit's hundred thousand.
  EXPECT_LT(evaluations, 200000);
  evaluations = 0;
  EXPECT_NO_THROW((gragg_bulirsch_stoer<double, 2>(field, Vector<double, 2>(1.0, 0.0), 1e-2, 1e-10)));
}

}  // namespace
}  // namespace vivv
