// The digit count of protocol vivv-map/1's numbers (harness/process/program.hpp): what decides
// whether a map program's answer carries the precision it was asked for. And a program that
// cannot be started leaves no descriptor of vivv's open.
#include "harness/process/program.hpp"

#include <dirent.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <set>
#include <string>
#include <vector>

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

// The descriptors open in this process (without the one that lists them).
std::set<int> open_descriptors() {
  std::set<int> open;
  DIR* listing = opendir("/proc/self/fd");
  if (!listing) return open;
  while (const dirent* entry = readdir(listing))
    if (entry->d_name[0] != '.') open.insert(std::atoi(entry->d_name));
  open.erase(dirfd(listing));
  closedir(listing);
  return open;
}

// With room for two pipes and half of a third, starting a program fails at its third pipe, says
// so, and closes the two it made.
TEST(MapProcessStart, APipeThatCannotBeMadeClosesTheOnesMadeBeforeIt) {
  const std::set<int> before = open_descriptors();
  std::vector<int> free;
  for (int fd = 0; free.size() < 5; ++fd)
    if (!before.count(fd)) free.push_back(fd);
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_NOFILE, &saved), 0);
  rlimit lowered = saved;
  lowered.rlim_cur = static_cast<rlim_t>(free.back() + 1);
  ASSERT_EQ(setrlimit(RLIMIT_NOFILE, &lowered), 0);
  std::string message;
  try {
    MapProcess process({{"/bin/true"}, "/", 5}, {{"protocol", map_protocol}});
  } catch (const MapProcessError& error) {
    message = error.what();
  }
  ASSERT_EQ(setrlimit(RLIMIT_NOFILE, &saved), 0);
  EXPECT_NE(message.find("cannot create the pipes to start"), std::string::npos) << message;
  EXPECT_EQ(open_descriptors(), before);
}

}  // namespace
}  // namespace vivv
