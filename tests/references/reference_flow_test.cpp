#include "references/reference_flow.hpp"

#include <cmath>
#include <string>

#include "cases/systems.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(ReferenceFlowTest, Scalars);

// A system the facade does not recognize: the harmonic oscillator behind a
// wrapper, as the harness's wrappers (twin terms, shifted forces) look to it.
template <class T>
struct WrappedOscillator {
  using Scalar = T;
  static constexpr int dimension = 1;
  HarmonicOscillator<T> inner;
  template <class S>
  S lagrangian(const Point<S, 1>& q, const Point<S, 1>& w) const {
    return inner.lagrangian(q, w);
  }
};

TYPED_TEST(ReferenceFlowTest, ClosedFormsAreUsedWhereTheyExist) {
  using T = TypeParam;
  Pendulum<T> pendulum;
  ReferenceFlow<Pendulum<T>> flow(pendulum, testing::reference_tolerance<T>());
  static_assert(ReferenceFlow<Pendulum<T>>::closed_form);
  static_assert(ReferenceFlow<HarmonicOscillator<T>>::closed_form);
  static_assert(!ReferenceFlow<PaperExample<T>>::closed_form);
  static_assert(!ReferenceFlow<WrappedOscillator<T>>::closed_form);
  EXPECT_EQ(flow.method(), "closed form: Jacobi elliptic functions (Boost.Math sn, cn, F)");
  EXPECT_EQ(flow.tolerance(), closed_form_tolerance<T>());
  EXPECT_NE(flow.cross_check().find("estimate_error"), std::string::npos);
  State<T, 1> start;
  start.q[0] = T(1) / 2;
  start.w[0] = T(-1);
  State<T, 1> a = flow.advance(start, T(3)), b = pendulum_flow(pendulum, start, T(3));
  EXPECT_EQ(a.q[0], b.q[0]);
  EXPECT_EQ(a.w[0], b.w[0]);
  // The independent check (extrapolation at 100 ulps locally) is at least as
  // accurate as any extrapolation reference claims to be.
  EXPECT_LE(flow.estimate_error(start, T(3)), minimum_flow_tolerance<T>());
}

// Without a closed form the facade integrates, and estimate_error — a rerun
// at a 1e-10 tighter local tolerance, or the working-precision floor — shows
// the result within the tolerance (the paper's example, L not separable).
TYPED_TEST(ReferenceFlowTest, ExtrapolationAgreesWithATighterRerunOnANonSeparableSystem) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  PaperExample<T> system;
  ReferenceFlow<PaperExample<T>> flow(system, tolerance);
  EXPECT_EQ(flow.tolerance(), tolerance);
  EXPECT_EQ(flow.method().rfind("Gragg–Bulirsch–Stoer extrapolation, tol ", 0), 0u)
      << flow.method();
  EXPECT_NE(flow.cross_check().find("estimate_error"), std::string::npos);
  State<T, 1> start;
  start.q[0] = T(3) / 2;
  start.w[0] = T(1) / 2;
  const T t = 5;
  State<T, 1> end = flow.advance(start, t);
  T estimate = flow.estimate_error(start, t);
  EXPECT_LE(estimate, tolerance * (1 + max_norm<T, 1>(end.q)));
  EXPECT_GT(state_distance(start, end), T(1) / 10);  // it did move
}

TYPED_TEST(ReferenceFlowTest, WrappedSystemsUseTheExtrapolationFlow) {
  using T = TypeParam;
  const T tolerance = testing::reference_tolerance<T>();
  WrappedOscillator<T> wrapped;
  wrapped.inner.omega = 2;
  ReferenceFlow<WrappedOscillator<T>> flow(wrapped, tolerance);
  State<T, 1> start;
  start.q[0] = 1;
  start.w[0] = T(1) / 4;
  const T t = T(-7) / 2;
  EXPECT_TRUE(within_tolerance(flow.advance(start, t),
                               harmonic_oscillator_flow(wrapped.inner, start, t), tolerance));
}

// A tolerance below what the working precision supports is raised, and the
// facade says so rather than claiming an accuracy it cannot deliver.
TYPED_TEST(ReferenceFlowTest, ToleranceBelowTheFloorIsRaisedAndReported) {
  using T = TypeParam;
  ReferenceFlow<PaperExample<T>> flow(PaperExample<T>{}, epsilon<T>());
  EXPECT_EQ(flow.tolerance(), minimum_flow_tolerance<T>());
  EXPECT_NE(flow.method().find("requested"), std::string::npos) << flow.method();
  EXPECT_THROW(ReferenceFlow<PaperExample<T>>(PaperExample<T>{}, T(0)), std::invalid_argument);
}

}  // namespace
}  // namespace vivv
