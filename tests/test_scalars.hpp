// Scalar types the important paths are tested in, and a fixture that sets the
// MPFR working precision for each test.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "core/numerics/scalar.hpp"

namespace vivv::testing {

using Scalars = ::testing::Types<double, quad, mpfr_real>;
// The run-time-size and sparse paths are tested in long double too.
using AllScalars = ::testing::Types<double, long double, quad, mpfr_real>;

// Readable typed-test names: "double", "float128", "mpfr" instead of Boost's type names.
struct ScalarNames {
  template <class T>
  static std::string GetName(int) {
    std::string name = scalar_name<T>();
    for (auto& c : name)
      if (c == ' ') c = '_';
    return name;
  }
};

// MPFR tests run at 60 decimal digits (~200 bits) unless a test says otherwise.
template <class T>
class ScalarTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if constexpr (is_mpfr_v<T>) guard_ = std::make_unique<PrecisionGuard>(60);
  }
  // A few hundred ulps: what "to working precision" means in these tests.
  static T working_tolerance() { return T(512) * epsilon<T>(); }
  // Uniform in [low, high], exactly representable in every scalar type.
  static T uniform(std::mt19937& random, int low, int high) {
    std::uniform_int_distribution<int> numerator(low * 1024, high * 1024);
    return T(numerator(random)) / 1024;
  }

 private:
  std::unique_ptr<PrecisionGuard> guard_;
};

// A typed test suite `Name` over `ScalarList` (Scalars or AllScalars): the ScalarTest fixture,
// readable names.
#define VIVV_SCALAR_TEST_SUITE(Name, ScalarList)          \
  template <class T>                                      \
  class Name : public ::vivv::testing::ScalarTest<T> {};  \
  TYPED_TEST_SUITE(Name, ::vivv::testing::ScalarList, ::vivv::testing::ScalarNames)

// The tolerance the harness asks of a reference at T's precision:
// 10^−(digits − 10), ten guard digits.
template <class T>
T reference_tolerance() {
  using std::pow;
  int digits = static_cast<int>((precision_bits<T>() - 1) * 0.30102999566398120);
  return pow(T(10), -(digits - 10));
}

// 10^−e in T.
template <class T>
T ten_to_minus(int e) {
  using std::pow;
  return pow(T(10), -e);
}

// m! in T.
template <class T>
T factorial(int m) {
  T result = 1;
  for (int i = 2; i <= m; ++i) result *= i;
  return result;
}

}  // namespace vivv::testing
