// Text from outside vivv on its way into messages, reports and the terminal (core/platform/text.hpp).
#include "core/platform/text.hpp"

#include <gtest/gtest.h>

namespace vivv {
namespace {

const std::string replacement = "\xEF\xBF\xBD";

TEST(Utf8Repair, LeavesValidTextAsItIs) {
  const std::string text = "plain, \xC3\xA9 (2 bytes), \xE2\x82\xAC (3), \xF0\x9F\x98\x80 (4), \x1B[2J";
  EXPECT_EQ(repaired_utf8(text), text);
}

TEST(Utf8Repair, ReplacesEachByteOfWhatIsNotACharacter) {
  EXPECT_EQ(repaired_utf8("a\xFF\xFE" "b"), "a" + replacement + replacement + "b");
  EXPECT_EQ(repaired_utf8("cut \xE2\x82"), "cut " + replacement + replacement);       // truncated
  EXPECT_EQ(repaired_utf8("\xC0\xAF"), replacement + replacement);                   // overlong '/'
  EXPECT_EQ(repaired_utf8("\xED\xA0\x80"), replacement + replacement + replacement);  // a surrogate
  EXPECT_EQ(repaired_utf8("\xF4\x90\x80\x80"),
            replacement + replacement + replacement + replacement);  // above U+10FFFF
  EXPECT_EQ(repaired_utf8("\x80" "a"), replacement + "a");  // a continuation byte alone
}

TEST(Utf8Cut, NeverEndsInsideACharacter) {
  const std::string text = "x\xC3\xA9\xC3\xA9";  // x é é: 5 bytes
  EXPECT_EQ(cut_at_character(text, 2), "x");
  EXPECT_EQ(cut_at_character(text, 3), "x\xC3\xA9");
  EXPECT_EQ(cut_at_character(text, 4), "x\xC3\xA9");
  EXPECT_EQ(cut_at_character(text, 9), text);
  EXPECT_EQ(quoted_text(text, 4), "x\xC3\xA9… (5 characters)");
  EXPECT_EQ(quoted_text("a\xFF", 10), "a" + replacement);
}

TEST(TerminalSafe, ShowsControlCharactersEscapedAndKeepsLines) {
  EXPECT_EQ(terminal_safe("red \x1B[31m, bell \x07, DEL \x7F, CSI \xC2\x9B, tab \t\nnext line"),
            "red \\x1b[31m, bell \\x07, DEL \\x7f, CSI \\u009b, tab \\x09\nnext line");
  EXPECT_EQ(terminal_safe("\xC3\xA9 stays, \xFF becomes"), "\xC3\xA9 stays, " + replacement + " becomes");
}

// A program's record keeps the end of its standard error — the exception's line — and cuts in
// the middle, between characters: 2000 bytes at most, whatever came first.
TEST(Utf8Cut, InTheMiddleKeepsTheBeginningAndTheEnd) {
  EXPECT_EQ(cut_in_the_middle("short", 2000), "short");
  std::string text = "the map program 'p' at request 3 failed: stderr's end: ";
  for (int i = 0; i < 400; ++i) text += "log line \xC3\xA9 ";
  text += "\nValueError: h must be positive";
  const std::string cut = cut_in_the_middle(text, 2000);
  EXPECT_LE(cut.size(), 2000u);
  EXPECT_EQ(cut.rfind("ValueError: h must be positive"), cut.size() - 30);
  EXPECT_EQ(cut.find("the map program 'p'"), 0u);
  EXPECT_NE(cut.find(" bytes left out) … "), std::string::npos);
  EXPECT_EQ(repaired_utf8(cut), cut);  // no character cut in two
}

}  // namespace
}  // namespace vivv
