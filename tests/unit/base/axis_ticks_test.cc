#include "base/axis_ticks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hull {
namespace {

TEST(AxisTicks, RoundStepsCoverTheInterval) {
  const std::vector<double> f = NiceTicks(0, 1, 5);
  ASSERT_EQ(f.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(f[i], 0.2 * i, 1e-12);
  // A deviation legend of +-0.177 m: steps of 0.1 (0.05 would give 7 ticks).
  EXPECT_EQ(NiceTicks(-0.177, 0.177, 4), (std::vector<double>{-0.1, 0.0, 0.1}));
  // 2.5 steps where 2 would give too many ticks and 5 too few.
  const std::vector<double> q = NiceTicks(0, 10, 4);
  ASSERT_EQ(q.size(), 5u);
  EXPECT_DOUBLE_EQ(q[1], 2.5);
  for (double v : NiceTicks(3.7, 1234.5, 6)) {
    EXPECT_GE(v, 3.7);
    EXPECT_LE(v, 1234.5);
  }
}

TEST(AxisTicks, ZeroIsExactlyZero) {
  // 0.1 steps from -0.3 accumulate rounding; the tick at zero is still 0.
  bool zero = false;
  for (double v : NiceTicks(-0.3, 0.3, 6)) {
    if (std::abs(v) < 1e-6) {
      EXPECT_EQ(v, 0.0);
      zero = true;
    }
  }
  EXPECT_TRUE(zero);
}

TEST(AxisTicks, EmptyOrNonFiniteIntervalsGiveNoTicks) {
  EXPECT_TRUE(NiceTicks(1, 1, 5).empty());
  EXPECT_TRUE(NiceTicks(2, 1, 5).empty());
  EXPECT_TRUE(NiceTicks(0, std::numeric_limits<double>::infinity(), 5).empty());
  EXPECT_TRUE(NiceTicks(std::nan(""), 1, 5).empty());
  EXPECT_EQ(NiceTicks(0, 1, 0), NiceTicks(0, 1, 1));  // target < 1 counts as 1
}

TEST(AxisTicks, LabelsAreAsExactAsTheStep) {
  EXPECT_EQ(TickDecimals(0.25), 2);  // 0.25, 0.50, 0.75: not 0.3, 0.5, 0.8
  EXPECT_EQ(TickDecimals(2.5), 1);   // 0.0, 2.5, 5.0, 7.5: not 0, 3, 5, 8
  EXPECT_EQ(TickDecimals(5), 0);
  EXPECT_EQ(TickDecimals(0.2), 1);
  EXPECT_EQ(TickDecimals(0.001), 3);
  EXPECT_EQ(TickDecimals(1.0 / 3.0), 6);  // never more than six
}

TEST(AxisTicks, LogTicksArePowersOfTen) {
  EXPECT_EQ(LogTicks(0.5, 2000), (std::vector<double>{1, 10, 100, 1000}));
  EXPECT_TRUE(LogTicks(0, 10).empty());
  EXPECT_TRUE(LogTicks(10, 1).empty());
}

}  // namespace
}  // namespace hull
