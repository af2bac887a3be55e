// The app's human-readable numbers: grouping, plurals, clock times.
#include <gtest/gtest.h>

#include "text_format.h"

namespace softsub::app {
namespace {

TEST(TextFormat, CountsAreGroupedAndPluralised) {
  EXPECT_EQ(countOf(0, "frame"), "0 frames");
  EXPECT_EQ(countOf(1, "frame"), "1 frame");
  EXPECT_EQ(countOf(2, "frame"), "2 frames");
  EXPECT_EQ(countOf(1, "particle"), "1 particle");
  EXPECT_EQ(countOf(10000, "particle"), "10,000 particles");
  EXPECT_EQ(groupThousands(1234567), "1,234,567");
}

TEST(TextFormat, ClockTimes) {
  EXPECT_EQ(clockTime(0), "0:00");
  EXPECT_EQ(clockTime(65.4), "1:05");
  EXPECT_EQ(clockTime(3725), "1:02:05");
  EXPECT_EQ(clockTime(-3), "0:00");
}

}  // namespace
}  // namespace softsub::app
