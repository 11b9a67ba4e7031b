#include "core/numerics/scalar.hpp"

#include <gtest/gtest.h>

namespace vivv {
namespace {

TEST(Scalar, DecimalStringsRoundTripInMpfrWithoutPassingThroughDouble) {
  PrecisionGuard guard(60);
  mpfr_real third = from_decimal<mpfr_real>("0.333333333333333333333333333333333333333333333333333333333333");
  mpfr_real back = from_decimal<mpfr_real>(to_decimal(third));
  EXPECT_EQ(third, back);
  // A double would keep only ~16 of these digits.
  EXPECT_LT(abs(third - mpfr_real(1) / 3), mpfr_real("1e-59"));
}

TEST(Scalar, PrecisionGuardRestoresThePreviousPrecision) {
  unsigned before = mpfr_real::default_precision();
  {
    PrecisionGuard guard(100);
    EXPECT_GE(precision_bits<mpfr_real>(), 332);
  }
  EXPECT_EQ(mpfr_real::default_precision(), before);
}

TEST(Scalar, MalformedDecimalIsRejected) {
  EXPECT_THROW(from_decimal<double>("1.5x"), std::invalid_argument);
  EXPECT_THROW(from_decimal<quad>("abc"), std::invalid_argument);
  PrecisionGuard guard(30);
  EXPECT_THROW(from_decimal<mpfr_real>("1..2"), std::invalid_argument);
}

// A subnormal double is a valid value (std::stod refused it with a bare "stod"); a value that
// overflows or underflows to 0 is out of range, naming the text and the range.
TEST(Scalar, SubnormalDecimalsAreReadAndOutOfRangeOnesNamed) {
  EXPECT_EQ(from_decimal<double>("1e-320"), std::strtod("1e-320", nullptr));
  EXPECT_GT(from_decimal<double>("1e-320"), 0.0);
  EXPECT_GT(from_decimal<long double>("1e-4940"), 0.0L);
  EXPECT_EQ(from_decimal<double>("0"), 0.0);
  EXPECT_EQ(from_decimal<double>("-0.0"), 0.0);
  for (const char* text : {"1e400", "-1e400", "1e-400"}) {
    try {
      from_decimal<double>(text);
      ADD_FAILURE() << text << " was read";
    } catch (const std::out_of_range& error) {
      EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("double"), std::string::npos) << error.what();
    }
  }
  EXPECT_THROW(from_decimal<long double>("1e5000"), std::out_of_range);
  EXPECT_THROW(from_decimal<double>(" 1"), std::invalid_argument);
}

// float128 and MPFR round a decimal beyond their range to infinity or zero without a word; read
// through from_decimal, such a number is out of range, named with the scalar, while the largest
// and smallest in range and every form of zero are read.
TEST(Scalar, QuadAndMpfrNameTheirRangeToo) {
  for (const char* text : {"1e5000", "-1e5000", "1e-5000"}) {
    try {
      from_decimal<quad>(text);
      ADD_FAILURE() << text << " was read in float128";
    } catch (const std::out_of_range& error) {
      EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("float128"), std::string::npos) << error.what();
    }
  }
  EXPECT_GT(from_decimal<quad>("1e4900"), quad(0));
  EXPECT_GT(from_decimal<quad>("1e-4960"), quad(0));  // subnormal
  EXPECT_EQ(from_decimal<quad>("0.000e-99999"), quad(0));
  PrecisionGuard guard(40);
  for (const char* text : {"1e999999999", "-1.0e999999999", "1e-999999999"}) {
    try {
      from_decimal<mpfr_real>(text);
      ADD_FAILURE() << text << " was read in MPFR";
    } catch (const std::out_of_range& error) {
      EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("mpfr"), std::string::npos) << error.what();
    }
  }
  EXPECT_GT(from_decimal<mpfr_real>("1e300000000"), mpfr_real(1));  // within MPFR's exponent range
  EXPECT_EQ(from_decimal<mpfr_real>("-0e5"), mpfr_real(0));
}

TEST(Scalar, EigenSolvesInQuadAndMpfr) {
  PrecisionGuard guard(50);
  Matrix<mpfr_real, 2, 2> a;
  a << 2, 1, 1, 3;
  Vector<mpfr_real, 2> b(mpfr_real(1), mpfr_real(2));
  Vector<mpfr_real, 2> x = a.partialPivLu().solve(b);
  EXPECT_LT((max_norm<mpfr_real, 2>(a * x - b)), mpfr_real("1e-48"));
  Matrix<quad, 2, 2> aq;
  aq << 2, 1, 1, 3;
  Vector<quad, 2> bq(quad(1), quad(2));
  Vector<quad, 2> xq = aq.partialPivLu().solve(bq);
  EXPECT_LT((max_norm<quad, 2>(aq * xq - bq)), quad(1e-32));
}

}  // namespace
}  // namespace vivv

namespace vivv {
namespace {

// A NaN component makes the max norm NaN in every scalar: std::max alone would drop it and
// report the other components' maximum (a blown-up run once measured an error of 0 that way).
template <class T>
void expect_nan_norm() {
  Vector<T, 3> v;
  v << T(1), std::numeric_limits<T>::quiet_NaN(), T(2);
  using std::isnan;
  EXPECT_TRUE(isnan(max_norm<T, 3>(v))) << scalar_name<T>();
  v[1] = T(-3);
  EXPECT_EQ((max_norm<T, 3>(v)), T(3)) << scalar_name<T>();
}

TEST(Scalar, MaxNormPropagatesNaN) {
  PrecisionGuard guard(40);
  expect_nan_norm<double>();
  expect_nan_norm<quad>();
  expect_nan_norm<mpfr_real>();
}

}  // namespace
}  // namespace vivv
