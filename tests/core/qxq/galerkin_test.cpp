// Galerkin discrete Lagrangians (core/qxq/galerkin.hpp), in double, quad and MPFR:
// degree 1 with one Gauss node is the midpoint rule and with two Lobatto nodes
// the trapezoid rule; the envelope-theorem momenta and the Schur-complement
// second derivatives agree with differences of the extremized value; and on
// the paper's nonlinear example L_d agrees with the exact discrete Lagrangian
// to O(h^{r+1}), r = min(2s, quadrature order) (a degree-3 curve with three
// Lobatto nodes is held at order 4, not 6).
#include "core/qxq/galerkin.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cases/systems.hpp"
#include "core/qxq/discrete_lagrangian.hpp"
#include "references/exact_discrete_lagrangian.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(GalerkinTest, Scalars);

template <class T, int n>
T largest_difference(const DiscreteLegendre<T, n>& a, const DiscreteLegendre<T, n>& b) {
  using std::abs;
  using std::max;
  T d = abs(T(a.value - b.value));
  d = max(d, T((a.p_begin - b.p_begin).cwiseAbs().maxCoeff()));
  d = max(d, T((a.p_end - b.p_end).cwiseAbs().maxCoeff()));
  d = max(d, T((a.dp_begin_dq_b - b.dp_begin_dq_b).cwiseAbs().maxCoeff()));
  d = max(d, T((a.dp_begin_dq_e - b.dp_begin_dq_e).cwiseAbs().maxCoeff()));
  d = max(d, T((a.dp_end_dq_b - b.dp_end_dq_b).cwiseAbs().maxCoeff()));
  d = max(d, T((a.dp_end_dq_e - b.dp_end_dq_e).cwiseAbs().maxCoeff()));
  return d;
}

TYPED_TEST(GalerkinTest, DegreeOneIsTheMidpointAndTrapezoidRules) {
  using T = TypeParam;
  ChargedParticle<T> system;  // 2 coordinates, w and q coupled
  const Vector<T, 2> q_b(T(1) / 3, T(-1) / 4), q_e(T(2) / 5, T(1) / 7);
  const T h = T(1) / 10;
  QxQDiscretization<T> midpoint, trapezoid;
  trapezoid.rule = QxQRule::trapezoid;
  // The Hessian blocks are of size 1/h: compare them at their own scale.
  const T tolerance = this->working_tolerance() / h;
  EXPECT_LE(largest_difference(galerkin_legendre(system, GalerkinRule<T>({1, false, 1}), q_b, q_e, h),
                               discrete_legendre(system, midpoint, q_b, q_e, h)),
            tolerance);
  EXPECT_LE(largest_difference(galerkin_legendre(system, GalerkinRule<T>({1, true, 2}), q_b, q_e, h),
                               discrete_legendre(system, trapezoid, q_b, q_e, h)),
            tolerance);
}

// Momenta and second derivatives against central differences of the extremized value (step
// δ = ε^(1/4) for the value, so that the O(δ²) truncation and the ε/δ rounding meet far below
// the tolerance ε^(1/3)).
TYPED_TEST(GalerkinTest, EnvelopeTheoremMomentaMatchDifferencesOfTheExtremizedValue) {
  using T = TypeParam;
  using std::abs;
  using std::cbrt;
  using std::sqrt;
  PaperExample<T> system;
  system.m = T(1) / 2;
  const T h = T(1) / 5;
  const Vector<T, 1> q_b(T(3) / 10), q_e(T(11) / 20);
  const T delta = sqrt(sqrt(epsilon<T>()));
  const T tolerance = cbrt(epsilon<T>());
  for (const GalerkinSpec& spec : {GalerkinSpec{3, false, 3}, GalerkinSpec{4, true, 5}}) {
    SCOPED_TRACE(spec.describe());
    const GalerkinRule<T> rule(spec);
    const auto d = galerkin_legendre(system, rule, q_b, q_e, h);
    auto at = [&](const T& b, const T& e) {
      return galerkin_legendre(system, rule, Vector<T, 1>(b), Vector<T, 1>(e), h);
    };
    const T dL_db = (at(q_b[0] + delta, q_e[0]).value - at(q_b[0] - delta, q_e[0]).value) / (2 * delta);
    const T dL_de = (at(q_b[0], q_e[0] + delta).value - at(q_b[0], q_e[0] - delta).value) / (2 * delta);
    EXPECT_LE(abs(T(d.p_begin[0] + dL_db)), tolerance);
    EXPECT_LE(abs(T(d.p_end[0] - dL_de)), tolerance);
    const T dp_begin_de = (at(q_b[0], q_e[0] + delta).p_begin[0] - at(q_b[0], q_e[0] - delta).p_begin[0]) / (2 * delta);
    const T dp_end_db = (at(q_b[0] + delta, q_e[0]).p_end[0] - at(q_b[0] - delta, q_e[0]).p_end[0]) / (2 * delta);
    const T dp_end_de = (at(q_b[0], q_e[0] + delta).p_end[0] - at(q_b[0], q_e[0] - delta).p_end[0]) / (2 * delta);
    EXPECT_LE(abs(T(d.dp_begin_dq_e(0, 0) - dp_begin_de)), tolerance / h);
    EXPECT_LE(abs(T(d.dp_end_dq_b(0, 0) - dp_end_db)), tolerance / h);
    EXPECT_LE(abs(T(d.dp_end_dq_e(0, 0) - dp_end_de)), tolerance / h);
    // Mixed blocks of one L_d: ∂p_end/∂q_b = −∂p_begin/∂q_e.
    EXPECT_LE(abs(T(d.dp_end_dq_b(0, 0) + d.dp_begin_dq_e(0, 0))), this->working_tolerance() / h);
  }
}

// log2 of |L_d − L_d^E| at h over the same at h/2, along the paper example's solution.
double observed_local_order(const GalerkinSpec& spec, const mpfr_real& h) {
  using T = mpfr_real;
  PaperExample<T> system;
  using std::pow;
  ExactDiscreteLagrangian<PaperExample<T>> exact(system, T(pow(T(10), -55)));
  const GalerkinRule<T> rule(spec);
  const Vector<T, 1> q0(T(1) / 2);
  auto error = [&](const T& step) {
    // Any nearby end point: L_d^E is the exact action of the solution between the two.
    const T q_e = q0[0] + T(3) / 4 * step;
    const auto reference = exact(q0, Vector<T, 1>(q_e), step);
    using std::abs;
    return abs(T(galerkin_legendre(system, rule, q0, Vector<T, 1>(q_e), step).value - reference.value));
  };
  using std::log2;
  return static_cast<double>(log2(T(error(h) / error(h / 2))));
}

TEST(GalerkinOrder, LocalErrorAgainstTheExactDiscreteLagrangianIsOfOrderRPlusOne) {
  PrecisionGuard guard(60);
  for (const GalerkinSpec& spec : {GalerkinSpec{1, false, 1}, GalerkinSpec{2, false, 2}, GalerkinSpec{2, true, 3},
                                   GalerkinSpec{3, false, 3}}) {
    SCOPED_TRACE(spec.describe());
    EXPECT_NEAR(observed_local_order(spec, mpfr_real(1) / 8), spec.predicted_order() + 1, 0.3);
  }
  // The quadrature caps the order: three Lobatto nodes (exact to degree 3) hold a cubic curve
  // (order 6 with enough nodes) at order 4.
  const GalerkinSpec starved{3, true, 3};
  EXPECT_EQ(starved.predicted_order(), 4);
  EXPECT_NEAR(observed_local_order(starved, mpfr_real(1) / 8), 5, 0.3);
}

}  // namespace
}  // namespace vivv
