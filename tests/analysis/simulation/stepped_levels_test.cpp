// The stepped sine's level list (analysis/simulation/stepped_levels), shared by the simulation,
// the CLI's --levels A:STEP:B and the app's rig schedule.
#include "analysis/simulation/stepped_levels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

TEST(SteppedLevels, IncludesTheEndWhenTheSpanIsAWholeNumberOfSteps) {
  // (2.7 − 0.2)/0.1 evaluates to 24.999999999999996 in doubles: still 26 levels, the last 2.7.
  const std::vector<double> levels = stepped_levels(0.2, 0.1, 2.7, "--levels");
  ASSERT_EQ(levels.size(), 26u);
  EXPECT_DOUBLE_EQ(levels.front(), 0.2);
  EXPECT_NEAR(levels.back(), 2.7, 1e-12);
  EXPECT_NEAR(levels[10], 1.2, 1e-12);
  EXPECT_EQ(stepped_levels(0.5, 0.1, 0.5, "x"), std::vector<double>{0.5});  // one level
}

TEST(SteppedLevels, NeverGoesBeyondTheEnd) {
  // 0.8/0.3 = 2.67 steps: three levels (0.2, 0.5, 0.8); rounding would have added 1.1 > 1.0.
  const std::vector<double> levels = stepped_levels(0.2, 0.3, 1.0, "x");
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_NEAR(levels.back(), 0.8, 1e-12);
}

TEST(SteppedLevels, RefusesWhatIsNoScheduleNamingTheInput) {
  const auto message = [](double from, double step, double to) {
    try {
      stepped_levels(from, step, to, "--levels: \"A:S:B\"");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(1.0, 0.1, 0.5),
            "--levels: \"A:S:B\": from 1, step 0.1, to 0.5: needs 0 <= from <= to and step > 0");
  EXPECT_NE(message(0.2, 0.0, 1.0).find("step 0"), std::string::npos);
  EXPECT_NE(message(-0.1, 0.1, 1.0).find("from -0.1"), std::string::npos);
  EXPECT_NE(message(0.2, std::nan(""), 1.0), "");
  EXPECT_EQ(message(0.0, 1e-6, 1.0),
            "--levels: \"A:S:B\": more than 10000 levels; use a larger step");
}

}  // namespace
}  // namespace oscilab::analysis
