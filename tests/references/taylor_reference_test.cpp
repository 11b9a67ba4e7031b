// The Taylor flow as a drop-in reference (issue 3): ReferenceFlow's interface,
// the tolerance it claims, its cross-check, and dense output that does not
// depend on the order of the calls.
#include "references/taylor_reference.hpp"

#include <gtest/gtest.h>

#include "cases/systems.hpp"
#include "references/closed_forms.hpp"
#include "references/reference_flow.hpp"

namespace vivv {
namespace {

TEST(TaylorReferenceTest, ClaimsItsToleranceAgainstTheClosedForm) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  const T requested = pow(T(10), -50);
  Pendulum<T> pendulum;
  TaylorReference<Pendulum<T>> reference(pendulum, requested);
  EXPECT_EQ(reference.tolerance(), requested);
  State<T, 1> start;
  start.q[0] = T(1);
  start.w[0] = T(1) / 2;
  std::vector<T> times;
  for (int N : {1, 2, 5, 10, 40}) times.push_back(T(10) / N);
  times.push_back(T(-4));
  auto states = reference.advance_many(start, times);
  for (std::size_t i = 0; i < times.size(); ++i) {
    EXPECT_TRUE((within_tolerance<T, 1>(states[i], pendulum_flow(pendulum, start, times[i]),
                                       reference.tolerance())))
        << "t = " << times[i];
  }
  EXPECT_LE(reference.estimate_error(start, T(10)), reference.tolerance());
  EXPECT_NE(reference.method().find("Taylor"), std::string::npos);
  EXPECT_NE(reference.cross_check().find("estimate_error"), std::string::npos);
  EXPECT_GT(reference.report().steps, 0);
}

// The pendulum's start of the tests below: q = 1, w = 1/2.
template <class T>
State<T, 1> pendulum_start() {
  State<T, 1> start;
  start.q[0] = T(1);
  start.w[0] = T(1) / 2;
  return start;
}

// 10⁻¹², or the flow's floor where that is higher (double).
template <class T>
T tolerance_at_least_the_floor() {
  return T(1e-12) > TaylorReference<Pendulum<T>>::floor() ? T(1e-12) : TaylorReference<Pendulum<T>>::floor();
}

// At the floor of a hardware scalar (10⁴ ε) the check's step tolerance cannot go below the flow's
// (both 10 ε): a check at the same tolerance and order took the same steps and agreed to the bit,
// so estimate_error was exactly 0 and checked nothing (a Lennard-Jones cluster's float128
// reference reported 0 at T). The check must be another integration: nonzero, within tolerance.
template <class T>
void expect_an_independent_check() {
  Pendulum<T> pendulum;
  TaylorReference<Pendulum<T>> reference(pendulum, TaylorReference<Pendulum<T>>::floor());
  State<T, 1> start;
  start.q[0] = T(1);
  start.w[0] = T(1) / 2;
  const T estimate = reference.estimate_error(start, T(10));
  EXPECT_GT(estimate, 0) << scalar_name<T>();
  EXPECT_LE(estimate, reference.tolerance()) << scalar_name<T>();
  EXPECT_NE(reference.cross_check().find("order " + std::to_string(reference.order() + 6)), std::string::npos)
      << reference.cross_check();
}
TEST(TaylorReferenceTest, ItsCheckAtTheFloorIsAnotherIntegration) {
  expect_an_independent_check<double>();
  expect_an_independent_check<long double>();
  expect_an_independent_check<quad>();
}

// The cross-check begun on its own thread (start_check, beside the flow's integration) is the same
// integration as the one estimate_error runs inline: the same estimate to the bit, in each scalar.
// A check begun for another end is not taken for this one; a reference destroyed while its check
// runs stops it (the destructor returns).
template <class T>
void expect_the_concurrent_check_to_be_the_inline_one() {
  Pendulum<T> pendulum;
  const State<T, 1> start = pendulum_start<T>();
  TaylorReference<Pendulum<T>> inline_check(pendulum, tolerance_at_least_the_floor<T>());
  TaylorReference<Pendulum<T>> concurrent(pendulum, inline_check.tolerance());
  concurrent.start_check(start, T(10));
  concurrent.advance(start, T(10));
  const T estimate = concurrent.estimate_error(start, T(10));
  EXPECT_EQ(estimate, inline_check.estimate_error(start, T(10))) << scalar_name<T>();
  EXPECT_GT(estimate, 0) << scalar_name<T>();
  TaylorReference<Pendulum<T>> other_end(pendulum, inline_check.tolerance());
  other_end.start_check(start, T(5));
  EXPECT_EQ(other_end.estimate_error(start, T(10)), estimate) << scalar_name<T>();
  {
    TaylorReference<Pendulum<T>> abandoned(pendulum, inline_check.tolerance());
    abandoned.start_check(start, T(1000));
  }
}
TEST(TaylorReferenceTest, ItsConcurrentCheckIsTheInlineOne) {
  expect_the_concurrent_check_to_be_the_inline_one<double>();
  expect_the_concurrent_check_to_be_the_inline_one<long double>();
  expect_the_concurrent_check_to_be_the_inline_one<quad>();
}

// Answers kept (keep_answers) and told to a fresh flow (recall, what --reference-cache does between
// runs) are what it returns, to the bit and without integrating: no step taken for the states asked
// before nor for the cross-check at T, while a question not asked before integrates. The memo is
// trusted as it is — a recalled state that is wrong is returned — which is why the cache's key holds
// the executable's hash.
template <class T>
void expect_recalled_answers_to_be_returned() {
  Pendulum<T> pendulum;
  const State<T, 1> start = pendulum_start<T>();
  const T tolerance = tolerance_at_least_the_floor<T>();
  TaylorReference<Pendulum<T>> first(pendulum, tolerance);
  first.keep_answers();
  const std::vector<T> times = {T(1) / 3, T(2), T(-1)};
  const std::vector<State<T, 1>> states = first.advance_many(start, times);
  const T estimate = first.estimate_error(start, T(2));
  const auto [advanced, checked] = first.answers();
  EXPECT_EQ(advanced.size(), times.size()) << scalar_name<T>();
  EXPECT_EQ(checked.size(), 1u) << scalar_name<T>();

  TaylorReference<Pendulum<T>> second(pendulum, tolerance);
  second.recall(advanced, checked);
  for (std::size_t i = 0; i < times.size(); ++i) {
    const State<T, 1> again = second.advance(start, times[i]);
    EXPECT_EQ(again.q[0], states[i].q[0]) << scalar_name<T>();
    EXPECT_EQ(again.w[0], states[i].w[0]) << scalar_name<T>();
  }
  EXPECT_EQ(second.estimate_error(start, T(2)), estimate) << scalar_name<T>();
  EXPECT_EQ(second.report().steps, 0) << scalar_name<T>();
  second.advance(start, T(3));
  EXPECT_GT(second.report().steps, 0) << scalar_name<T>();

  auto wrong = advanced;
  wrong[0].state.q[0] += 1;
  auto wrong_check = checked;
  wrong_check[0].state.q[0] += 1;
  TaylorReference<Pendulum<T>> misled(pendulum, tolerance);
  misled.recall(wrong, wrong_check);
  EXPECT_EQ(misled.advance(start, wrong[0].t).q[0], wrong[0].state.q[0]) << scalar_name<T>();
  EXPECT_GT(misled.estimate_error(start, T(2)), T(1) / 2) << scalar_name<T>();  // the check was not run
}
TEST(TaylorReferenceTest, RecalledAnswersAreReturnedWithoutIntegrating) {
  expect_recalled_answers_to_be_returned<double>();
  expect_recalled_answers_to_be_returned<long double>();
  expect_recalled_answers_to_be_returned<quad>();
  PrecisionGuard guard(40);
  expect_recalled_answers_to_be_returned<mpfr_real>();
}

TEST(TaylorReferenceTest, ValueDependsOnlyOnStartAndTime) {
  PrecisionGuard guard(61);
  using T = mpfr_real;
  PaperExample<T> paper;
  State<T, 1> start;
  start.q[0] = T(7) / 10;
  start.w[0] = T(-3) / 10;
  TaylorReference<PaperExample<T>> long_first(paper, pow(T(10), -50));
  TaylorReference<PaperExample<T>> short_first(paper, pow(T(10), -50));
  State<T, 1> a_long = long_first.advance(start, T(10));
  State<T, 1> a_short = long_first.advance(start, T(1) / 3);
  State<T, 1> b_short = short_first.advance(start, T(1) / 3);
  State<T, 1> b_long = short_first.advance(start, T(10));
  EXPECT_EQ(a_short.q[0], b_short.q[0]);
  EXPECT_EQ(a_short.w[0], b_short.w[0]);
  EXPECT_EQ(a_long.q[0], b_long.q[0]);
  EXPECT_EQ(a_long.w[0], b_long.w[0]);
  // Copies share the cached trajectories, as ReferenceFlow's copies share nothing but are equal.
  TaylorReference<PaperExample<T>> copy = long_first;
  EXPECT_EQ(copy.advance(start, T(10)).q[0], a_long.q[0]);
  // And it agrees with the Gragg–Bulirsch–Stoer stop-gap to the latter's tolerance.
  ReferenceFlow<PaperExample<T>> stop_gap(paper, pow(T(10), -40));
  EXPECT_TRUE((within_tolerance<T, 1>(a_long, stop_gap.advance(start, T(10)), stop_gap.tolerance())));
}

TEST(TaylorReferenceTest, ToleranceBelowTheFloorIsRaisedAndSaidSo) {
  using T = quad;
  TaylorReference<HarmonicOscillator<T>> reference(HarmonicOscillator<T>{}, pow(T(10), -40));
  EXPECT_EQ(reference.tolerance(), TaylorReference<HarmonicOscillator<T>>::floor());
  EXPECT_NE(reference.method().find("requested"), std::string::npos);
}

}  // namespace
}  // namespace vivv
