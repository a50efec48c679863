// The progress line's rate: the last minute's, not the stage's average, so a machine
// that gets loaded mid-stage lengthens the time left at once.
#include <gtest/gtest.h>

#include "sim/recent_rate.hpp"

namespace regodem {
namespace {

TEST(RecentRate, FollowsTheLastMinuteNotTheAverage) {
  RecentRate rate(60.0);
  EXPECT_EQ(rate.steps_per_s(), 0.0);
  // 100 steps/s for 10 minutes, then the machine gets loaded: 10 steps/s for 2 more.
  for (int t = 0; t <= 600; t += 5) rate.add(t, static_cast<std::uint64_t>(100 * t));
  EXPECT_DOUBLE_EQ(rate.steps_per_s(), 100.0);
  for (int t = 605; t <= 720; t += 5) rate.add(t, static_cast<std::uint64_t>(60000 + 10 * (t - 600)));
  // The last minute, 660 to 720 s, at 10 steps/s; the stage's average would say
  // 61200 / 720 = 85 steps/s, and a time left 8.5x too short.
  EXPECT_DOUBLE_EQ(rate.steps_per_s(), 10.0);
}

TEST(RecentRate, SpansTheWholeRunWhileItIsShorterThanTheWindow) {
  RecentRate rate(60.0);
  rate.add(0.0, 0);
  rate.add(2.0, 30);
  rate.add(4.0, 50);
  EXPECT_DOUBLE_EQ(rate.steps_per_s(), 12.5);
}

}  // namespace
}  // namespace regodem
