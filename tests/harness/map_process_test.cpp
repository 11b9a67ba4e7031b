// The digit count of protocol vivv-map/1's numbers (harness/map_process.hpp): what decides
// whether a map program's answer carries the precision it was asked for.
#include "harness/map_process.hpp"

#include <gtest/gtest.h>

namespace vivv {
namespace {

TEST(SignificantDigits, CountsTheMantissaFromItsFirstNonzeroDigitWithTrailingZeros) {
  EXPECT_EQ(significant_digits("1.2500e-3"), 5);
  EXPECT_EQ(significant_digits("-0.00125"), 3);
  EXPECT_EQ(significant_digits("0.500000"), 6);
  EXPECT_EQ(significant_digits("+120"), 3);
  EXPECT_EQ(significant_digits("5.0000000000000000000e-1"), 20);
  EXPECT_EQ(significant_digits("1.1205268002004255614"), 20);
  EXPECT_EQ(significant_digits(".5"), 1);
  EXPECT_EQ(significant_digits("5."), 1);
}

TEST(SignificantDigits, ZeroHasNoneToCount) {
  EXPECT_EQ(significant_digits("0"), 0);
  EXPECT_EQ(significant_digits("-0.000e+00"), 0);
}

TEST(SignificantDigits, RefusesWhatIsNotADecimalNumber) {
  for (const char* text : {"", "-", ".", "e5", "1e", "1e+", "1.2.3", "nan", "inf", "0x1p3", "1,5",
                           " 1", "1 ", "1e1234567890", "1.5f"})
    EXPECT_EQ(significant_digits(text), -1) << "'" << text << "'";
}

}  // namespace
}  // namespace vivv
