// No NaN or infinity ever passes (docs/claims.md, "No NaN passes"): the reductions every claim
// uses keep a NaN instead of dropping it (std::max(1, NaN) is 1), and a measured value or
// tolerance that is not finite throws NonFiniteMeasurement, which makes the claim `error`.
#include "harness/verdicts/finite_measurement.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "core/structure/symplectic.hpp"
#include "harness/claims/claim.hpp"
#include "tests/test_scalars.hpp"

namespace vivv {
namespace {

VIVV_SCALAR_TEST_SUITE(FiniteMeasurementTest, AllScalars);

TYPED_TEST(FiniteMeasurementTest, NanMaxAndNanMinKeepANaNInEitherPlace) {
  using T = TypeParam;
  using std::isnan;
  const T nan = std::numeric_limits<T>::quiet_NaN();
  EXPECT_TRUE(isnan(nan_max(T(1), nan)));
  EXPECT_TRUE(isnan(nan_max(nan, T(1))));
  EXPECT_TRUE(isnan(nan_min(T(1), nan)));
  EXPECT_TRUE(isnan(nan_min(nan, T(1))));
  EXPECT_TRUE(isnan(nan_max({T(1), T(5), nan, T(2)})));
  // Numbers as std::max and std::min give them.
  EXPECT_EQ(nan_max(T(1), T(2)), T(2));
  EXPECT_EQ(nan_min(T(1), T(2)), T(1));
  EXPECT_EQ(nan_max({T(1), T(5), T(2)}), T(5));
  const T infinity = std::numeric_limits<T>::infinity();
  EXPECT_EQ(nan_max(T(1), infinity), infinity);
}

TYPED_TEST(FiniteMeasurementTest, MaxEntryOfAMatrixWithANaNIsNaN) {
  using T = TypeParam;
  using std::isnan;
  Matrix<T, 2, 2> a;
  a << T(1), T(-7), std::numeric_limits<T>::quiet_NaN(), T(2);
  EXPECT_TRUE(isnan(max_entry<T, 2, 2>(a)));
  a(1, 0) = T(3);
  EXPECT_EQ((max_entry<T, 2, 2>(a)), T(7));
}

TYPED_TEST(FiniteMeasurementTest, RequireFiniteThrowsForNaNAndInfinitiesOnly) {
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN(), infinity = std::numeric_limits<T>::infinity();
  EXPECT_NO_THROW(require_finite(T(0), "x"));
  EXPECT_NO_THROW(require_finite((std::numeric_limits<T>::max)(), "x"));
  for (const T& bad : {nan, infinity, T(-infinity)}) {
    try {
      require_finite(bad, "the defect at h = 0.5");
      ADD_FAILURE() << "no throw";
    } catch (const NonFiniteMeasurement& error) {
      EXPECT_NE(std::string(error.what()).find("the defect at h = 0.5 is "), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("not a finite number"), std::string::npos) << error.what();
    }
  }
}

// A per-step identity check cannot hold on a NaN (NaN <= tol is false, but a claim must err, not
// fail) nor on an infinite tolerance (inf <= inf is true: it would pass anything).
TYPED_TEST(FiniteMeasurementTest, APerStepCheckRefusesANonFiniteValueOrTolerance) {
  using T = TypeParam;
  const T nan = std::numeric_limits<T>::quiet_NaN(), infinity = std::numeric_limits<T>::infinity();
  PerStepCheck<T> check;
  EXPECT_TRUE(check.add(T(1) / 8, T(1) / 1000, T(1) / 100));
  EXPECT_THROW(check.add(T(1) / 16, nan, T(1) / 100), NonFiniteMeasurement);
  EXPECT_THROW(check.add(T(1) / 16, infinity, infinity), NonFiniteMeasurement);
  EXPECT_THROW(check.add(T(1) / 16, T(0), infinity), NonFiniteMeasurement);
  EXPECT_EQ(check.values.size(), 1u);
}

// The planted bug of the process test (a double program's Jacobian with every entry 1e160): in
// double JᵀΩJ overflows, and the defect is NaN, not a number that a tolerance could pass.
TEST(FiniteMeasurement, AnOverflowingJacobianHasANaNDefectInDouble) {
  Matrix<double, 2, 2> jacobian;
  jacobian << 1e160, 1e160, 1e160, 1e160;
  EXPECT_TRUE(std::isnan((symplecticity_defect<double, 2>(jacobian))));
}

}  // namespace
}  // namespace vivv
