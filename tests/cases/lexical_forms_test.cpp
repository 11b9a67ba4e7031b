// The textual forms of numbers and names (cases/lexical_forms.hpp): what each accepts and refuses,
// and text of a million characters read without recursion (std::regex, which these replace,
// ended vivv with SIGSEGV on a 50,000-digit number).
#include "cases/lexical_forms.hpp"

#include <gtest/gtest.h>

#include <string>

namespace vivv {
namespace {

TEST(LexicalForms, DecimalsInTheFormReportsKeep) {
  for (const char* text : {"0", "-0.5", "2", "1.25e-3", "7E+12", "-10.000"}) EXPECT_TRUE(is_decimal_text(text)) << text;
  for (const char* text : {"", "+2", ".5", "2.", "1e", "1e+", "--1", "1.2.3", "1 ", "pi", "0x10", "1e5.5"})
    EXPECT_FALSE(is_decimal_text(text)) << text;
}

TEST(LexicalForms, NumeralsAndFractions) {
  EXPECT_TRUE(is_numeral_text("+2"));
  EXPECT_TRUE(is_numeral_text(".5e-"));
  EXPECT_FALSE(is_numeral_text(""));
  EXPECT_FALSE(is_numeral_text("pi/4"));
  for (const char* text : {"1/2", "0.25", "3", "10/30"}) EXPECT_TRUE(is_fraction_text(text)) << text;
  for (const char* text : {"1/0", "1/02", "-1/2", "/2", "1/", ".5", "1/2/3"}) EXPECT_FALSE(is_fraction_text(text)) << text;
}

TEST(LexicalForms, NamesOfFormulasAndSystems) {
  EXPECT_TRUE(is_name_text("x1_b", 32, "_"));
  EXPECT_FALSE(is_name_text("1x", 32, "_"));
  EXPECT_FALSE(is_name_text("a-b", 32, "_"));
  EXPECT_TRUE(is_name_text("my-system.v2", 64, "_.-"));
  EXPECT_TRUE(is_name_text(std::string(32, 'a'), 32, "_"));
  EXPECT_FALSE(is_name_text(std::string(33, 'a'), 32, "_"));
  EXPECT_FALSE(is_name_text("", 32, "_"));
}

// A million digits, valid or with one stray letter at the end: read in one pass, no recursion.
TEST(LexicalForms, TextOfAnyLengthIsReadInOnePass) {
  const std::string digits(1000000, '7');
  EXPECT_TRUE(is_decimal_text(digits));
  EXPECT_TRUE(is_numeral_text(digits));
  EXPECT_TRUE(is_fraction_text(digits + "/" + digits));
  EXPECT_FALSE(is_decimal_text(digits + "x"));
  EXPECT_FALSE(is_numeral_text(digits + "x"));
  EXPECT_FALSE(is_name_text("a" + digits, 64, "_"));
}

}  // namespace
}  // namespace vivv
