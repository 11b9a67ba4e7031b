// The Taylor-series reference flow (issue 3): tapes, coefficients, and flows
// checked against closed forms, time reversal, a tighter run, energy, and a
// deliberately wrong coefficient that these checks must catch.
#include "references/taylor_flow.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <tuple>

#include "cases/catalogue.hpp"
#include "core/qxq/modified_equation.hpp"
#include "references/closed_forms.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

// 10^−e in T, without passing through a double.
using testing::ten_to_minus;

// |a − b| relative to 1 + |b|, maximized over q and w.
template <class T, int n>
T relative_distance(const State<T, n>& a, const State<T, n>& b) {
  using std::abs;
  using std::max;
  T d = 0;
  for (int i = 0; i < n; ++i) {
    d = max(d, T(abs(a.q[i] - b.q[i]) / (1 + abs(b.q[i]))));
    d = max(d, T(abs(a.w[i] - b.w[i]) / (1 + abs(b.w[i]))));
  }
  return d;
}

template <class T>
State<T, 1> state1(const T& q, const T& w) {
  State<T, 1> v;
  v.q[0] = q;
  v.w[0] = w;
  return v;
}

// The tape of every catalogue system reproduces euler_lagrange_acceleration.
template <class System>
void expect_tape_matches_acceleration(const System& system, unsigned seed) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  Tape<T> tape = euler_lagrange_tape(system);
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> pick(-400, 400);
  for (int trial = 0; trial < 5; ++trial) {
    Vector<T, n> q, w;
    std::vector<T> x(2 * n);
    for (int i = 0; i < n; ++i) {
      q[i] = T(pick(random)) / 1000;
      w[i] = T(pick(random)) / 1000;
      x[i] = q[i], x[n + i] = w[i];
    }
    Vector<T, n> expected = euler_lagrange_acceleration(system, q, w);
    std::vector<T> got = tape.evaluate(x);
    for (int i = 0; i < n; ++i)
      EXPECT_LE(abs(got[i] - expected[i]), 64 * epsilon<T>() * (1 + abs(expected[i])))
          << typeid(System).name() << " component " << i;
  }
}

TEST(TaylorTapeTest, EveryCatalogueSystemMatchesTheEulerLagrangeAcceleration) {
  PrecisionGuard guard(40);
  std::apply([](auto... system) { (expect_tape_matches_acceleration(system, 7), ...); },
             CatalogueSystems<mpfr_real>{});
  std::apply([](auto... system) { (expect_tape_matches_acceleration(system, 8), ...); },
             CatalogueSystems<double>{});
  ForceShifted<PaperExample<double>> shifted;
  shifted.c = {0.25};
  expect_tape_matches_acceleration(shifted, 9);
}

TEST(TaylorTapeTest, FoldingLeavesThePendulumTapeSmall) {
  // q'' = −k sin q: the sin/cos pair and one scaling (the rest folds away or is pruned).
  Tape<double> tape = euler_lagrange_tape(Pendulum<double>{});
  EXPECT_LE(tape.operations(), 4) << "pendulum tape has " << tape.operations() << " operations";
  Tape<double> oscillator = euler_lagrange_tape(HarmonicOscillator<double>{});
  EXPECT_LE(oscillator.operations(), 1);
}

TEST(TaylorExpansionTest, HarmonicOscillatorCoefficientsAreTheCosineSeries) {
  // q = cos t: q_k = (−1)^{k/2}/k! for even k, 0 for odd k.
  TaylorExpansion<double> expansion(euler_lagrange_tape(HarmonicOscillator<double>{}));
  double x0 = 1, v0 = 0;
  expansion.expand(&x0, &v0, 12);
  double factorial = 1;
  for (int k = 0; k <= 12; ++k) {
    if (k > 0) factorial *= k;
    double expected = k % 2 ? 0.0 : (k % 4 == 0 ? 1 : -1) / factorial;
    EXPECT_NEAR(expansion.position(0, k), expected, 1e-16) << k;
  }
}

TEST(TaylorExpansionTest, EveryRecurrenceMatchesFiniteTaylorCoefficients) {
  // x'' = f(x) for f built from every op; the order-2 coefficient must be f(x0)/2 and the
  // order-3 one f'(x0) v0 / 6 — and the whole series must agree with a fine integration below.
  using T = double;
  TapeRecording<T> recording(2);
  TapeScalar<T> x = recording.input(0), v = recording.input(1);
  TapeScalar<T> f = sin(x) * cos(v) + exp(x) / (2 + v * v) - log(3 + x) + sqrt(4 + x * v) +
                    pow(2 + x, T(1) / 3) - 1 / (5 + x) + (x - v) * (x + v);
  Tape<T> tape = recording.finish({f});
  auto f_of = [](T a, T b) {
    return std::sin(a) * std::cos(b) + std::exp(a) / (2 + b * b) - std::log(3 + a) +
           std::sqrt(4 + a * b) + std::cbrt(2 + a) - 1 / (5 + a) + (a - b) * (a + b);
  };
  TaylorExpansion<T> expansion(tape);
  T x0 = T(3) / 10, v0 = -T(1) / 5;
  expansion.expand(&x0, &v0, 8);
  EXPECT_NEAR(expansion.position(0, 2), f_of(x0, v0) / 2, 1e-15);
  // d/dt f(x, x') = f_x v + f_v f: central differences.
  const T d = 1e-6;
  T fx = (f_of(x0 + d, v0) - f_of(x0 - d, v0)) / (2 * d);
  T fv = (f_of(x0, v0 + d) - f_of(x0, v0 - d)) / (2 * d);
  EXPECT_NEAR(expansion.position(0, 3), (fx * v0 + fv * f_of(x0, v0)) / 6, 1e-9);
}

// Pendulum and oscillator against their closed forms, forward and backward, libration and rotation.
template <class T>
void expect_closed_forms(const T& tolerance, const T& step_tolerance) {
  Pendulum<T> pendulum;
  HarmonicOscillator<T> oscillator;
  oscillator.omega = T(3) / 2;
  TaylorFlow<Pendulum<T>> pendulum_flow_taylor(pendulum, step_tolerance);
  TaylorFlow<HarmonicOscillator<T>> oscillator_flow(oscillator, step_tolerance);
  for (const auto& start : {state1<T>(T(1), T(0)), state1<T>(T(-1) / 2, T(5) / 2)}) {
    for (const T& t : {T(10), T(-7), T(1) / 3}) {
      State<T, 1> expected = pendulum_flow(pendulum, start, t);
      State<T, 1> got = pendulum_flow_taylor.advance(start, t);
      EXPECT_LE((relative_distance<T, 1>(got, expected)), tolerance)
          << "pendulum t = " << t << " error " << relative_distance<T, 1>(got, expected);
      State<T, 1> expected_oscillator = harmonic_oscillator_flow(oscillator, start, t);
      State<T, 1> got_oscillator = oscillator_flow.advance(start, t);
      EXPECT_LE((relative_distance<T, 1>(got_oscillator, expected_oscillator)), tolerance)
          << "oscillator t = " << t;
    }
  }
}

TEST(TaylorFlowTest, QuadMatchesClosedForms) {
  expect_closed_forms<quad>(ten_to_minus<quad>(28), ten_to_minus<quad>(31));
}
TEST(TaylorFlowTest, Mpfr200BitsMatchesClosedForms) {
  PrecisionGuard guard(61);
  expect_closed_forms<mpfr_real>(ten_to_minus<mpfr_real>(50), ten_to_minus<mpfr_real>(53));
}
TEST(TaylorFlowTest, Mpfr400BitsMatchesClosedForms) {
  PrecisionGuard guard(121);
  expect_closed_forms<mpfr_real>(ten_to_minus<mpfr_real>(110), ten_to_minus<mpfr_real>(113));
}

TEST(TaylorFlowTest, ForwardThenBackwardReturnsToTheStart) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(50);
  PaperExample<T> paper;
  TaylorFlow<PaperExample<T>> flow(paper, tolerance);
  State<T, 1> start = state1<T>(T(7) / 10, T(-3) / 10);
  State<T, 1> there = flow.advance(start, T(10));
  State<T, 1> back = flow.advance(there, T(-10));
  EXPECT_LE((relative_distance<T, 1>(back, start)), tolerance);
  EXPECT_GT((relative_distance<T, 1>(there, start)), T(1) / 100);  // it did move
}

// A run at +64 bits (20 more digits) and a 1e-20 tighter tolerance agrees to the looser one.
template <class System>
void expect_tighter_run_agrees(const std::vector<std::string>& q, const std::vector<std::string>& w) {
  constexpr int n = System::dimension;
  using T = mpfr_real;
  for (const char* t_text : {"5", "-3"}) {
    std::vector<std::string> coarse(2 * n), fine(2 * n);
    auto run = [&](int digits, int exponent, std::vector<std::string>& out) {
      PrecisionGuard guard(digits);
      System system;
      State<T, n> start;
      for (int i = 0; i < n; ++i) start.q[i] = T(q[i]), start.w[i] = T(w[i]);
      TaylorFlow<System> flow(system, ten_to_minus<T>(exponent));
      State<T, n> end = flow.advance(start, T(t_text));
      for (int i = 0; i < n; ++i) out[i] = to_decimal(end.q[i]), out[n + i] = to_decimal(end.w[i]);
    };
    run(61, 50, coarse);
    run(61 + 20, 70, fine);
    PrecisionGuard guard(81);
    for (int i = 0; i < 2 * n; ++i) {
      T a(coarse[i]), b(fine[i]);
      EXPECT_LE(abs(a - b), ten_to_minus<T>(50) * (1 + abs(b)))
          << typeid(System).name() << " t = " << t_text << " component " << i;
    }
  }
}

TEST(TaylorFlowTest, RunAtSixtyFourMoreBitsAgreesToTheTolerance) {
  expect_tighter_run_agrees<PaperExample<mpfr_real>>({"0.7"}, {"-0.3"});
  expect_tighter_run_agrees<RelativisticParticle<mpfr_real>>({"0.3"}, {"0.4"});
  expect_tighter_run_agrees<ChargedParticle<mpfr_real>>({"0.3", "-0.2"}, {"0.1", "0.4"});
}

// max over t of |E(F_t(v)) − E(v)| on a dense grid of [−10, 10], relative to the largest
// |p·w| met (the size of the terms that cancel in E: Kepler's orbit from this state has
// eccentricity 0.99 and reaches speeds near 30 at pericentre).
template <class System>
typename System::Scalar energy_drift(const System& system,
                                     TaylorFlow<System>& flow) {
  using T = typename System::Scalar;
  constexpr int n = System::dimension;
  using std::abs;
  using std::max;
  State<T, n> start;
  for (int i = 0; i < n; ++i) start.q[i] = T(3 + i) / 10, start.w[i] = T(4 - i) / 10;
  // Hénon–Heiles from that state has energy 0.27 > 1/6 and escapes to infinity in finite
  // time: start it inside its bounded region instead.
  if constexpr (std::is_same_v<System, HenonHeiles<T>>) start.q /= 3, start.w /= 3;
  std::vector<T> times;
  for (int j = -40; j <= 40; ++j) times.push_back(T(j) / 4);
  const T e0 = energy(system, start.q, start.w);
  T drift = 0, scale = 1;
  for (const auto& v : flow.advance_many(start, times)) {
    drift = max(drift, T(abs(energy(system, v.q, v.w) - e0)));
    scale = max(scale, T(abs(T(momentum(system, v.q, v.w).dot(v.w)))));
  }
  return drift / scale;
}

TEST(TaylorFlowTest, EnergyIsConservedForEveryCatalogueSystem) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(50);
  auto check = [&](auto system) {
    using System = decltype(system);
    TaylorFlow<System> flow(system, tolerance);
    T drift = energy_drift(system, flow);
    EXPECT_LE(drift, tolerance) << System::name << " drift " << drift;
  };
  std::apply([&](auto... system) { (check(system), ...); }, CatalogueSystems<T>{});
  // The force-shifted Lagrangian of the mismatched DEL is conservative too.
  ForceShifted<PaperExample<T>> shifted;
  shifted.c = {T(1) / 4};
  TaylorFlow<ForceShifted<PaperExample<T>>> flow(shifted, tolerance);
  EXPECT_LE(energy_drift(shifted, flow), tolerance);
}

TEST(TaylorFlowTest, DenseOutputEqualsStepsEndingAtEachTime) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(50);
  Pendulum<T> pendulum;
  TaylorFlow<Pendulum<T>> flow(pendulum, tolerance);
  State<T, 1> start = state1<T>(T(1), T(1) / 2);
  std::vector<T> times;
  for (int N : {3, 7, 10, 64}) times.push_back(T(10) / N);
  for (int j = 1; j <= 5; ++j) times.push_back(T(j) / 7 - T(3) / 2);  // some backward
  times.push_back(T(10));
  auto dense = flow.advance_many(start, times);
  for (std::size_t i = 0; i < times.size(); ++i) {
    State<T, 1> expected = pendulum_flow(pendulum, start, times[i]);
    EXPECT_LE((relative_distance<T, 1>(dense[i], expected)), tolerance) << "t = " << times[i];
    EXPECT_LE((relative_distance<T, 1>(dense[i], flow.advance(start, times[i]))), tolerance);
  }
}

// Negative control: a wrong sign in one coefficient of the sin/cos recurrence (order 3) must be
// caught by the closed-form comparison and by energy conservation.
TEST(TaylorFlowTest, NegativeControlWrongSeriesCoefficientIsCaught) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T tolerance = ten_to_minus<T>(50);
  for (int fault : {3, 20}) {
    Pendulum<T> pendulum;
    TaylorFlow<Pendulum<T>> flow(pendulum, tolerance);
    flow.integrator().expansion().fault_order = fault;
    State<T, 1> start = state1<T>(T(1), T(0));
    State<T, 1> got = flow.advance(start, T(10));
    EXPECT_GT((relative_distance<T, 1>(got, pendulum_flow(pendulum, start, T(10)))), tolerance)
        << "closed form misses the fault at order " << fault;
    EXPECT_GT(energy_drift(pendulum, flow), tolerance)
        << "energy misses the fault at order " << fault;
  }
}

// A motion too fast for its T fails after a thousand steps, saying how many it would need,
// instead of running to the step limit: the pendulum with k = 10⁸ (period 6·10⁻⁴) over
// T = 10⁴ needs some 10⁸ steps. Negative control: the same flow reaches a T it can.
TEST(TaylorFlowTest, AMotionTooFastForItsTFailsAfterAThousandSteps) {
  Pendulum<double> fast;
  fast.k = 1e8;
  TaylorFlow<Pendulum<double>> flow(fast, 1e-12);
  State<double, 1> start = state1<double>(1.0, 0.0);
  try {
    flow.advance(start, 1e4);
    ADD_FAILURE() << "reached t = 1e4";
  } catch (const std::runtime_error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("the Taylor-series flow would need about"), std::string::npos) << message;
    EXPECT_NE(message.find("(1000 steps reached t = "), std::string::npos) << message;
    EXPECT_NE(message.find("take a smaller T"), std::string::npos) << message;
  }
  EXPECT_LT(flow.report().steps, 1100);
  TaylorFlow<Pendulum<double>> reachable(fast, 1e-12);
  EXPECT_NO_THROW(reachable.advance(start, 1e-2));
}

}  // namespace
}  // namespace vivv
