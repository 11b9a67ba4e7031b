// vivv's verdicts as a GoogleTest assertion, for a user's own test suite:
//   EXPECT_TRUE(vivv::check(vivv::run({"my-case.json"})));
// fails with one line per claim that does not hold.
#pragma once

#include <gtest/gtest.h>

#include "harness/library/vivv.hpp"

namespace vivv {

inline ::testing::AssertionResult check(const Run& run) {
  if (holds(run)) return ::testing::AssertionSuccess() << "every claim holds";
  return ::testing::AssertionFailure() << failures(run);
}

}  // namespace vivv
