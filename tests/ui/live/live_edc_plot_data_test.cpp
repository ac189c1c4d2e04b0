// The EDC points per well, the prediction levels and the level warning.
#include "ui/live/live_edc_plot_data.h"

#include <optional>
#include <vector>

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

analysis::LevelResult level(analysis::Well well, double f0, double edc, double std, int cycles) {
  analysis::LevelResult r;
  r.well = well;
  r.f0_n = f0;
  r.edc_mean_j = edc;
  r.edc_std_j = std;
  r.cycles = cycles;
  return r;
}

TEST(EdcPlotData, SplitsLevelsByWellWithThreeSigmaBars) {
  std::vector<analysis::LevelResult> levels = {
      level(analysis::Well::Positive, 0.2, 1e-5, 1e-7, 80),
      level(analysis::Well::Negative, 0.2, 2e-5, 2e-7, 80),
      level(analysis::Well::Positive, 0.3, 3e-5, 1e-7, 80),
      level(analysis::Well::CrossWell, 2.9, 1e-2, 1e-3, 80)};
  levels[3].cross_well = true;
  const EdcPlotData data =
      edc_plot_data(levels, level(analysis::Well::Positive, 0.4, 4e-5, 1e-7, 12));
  ASSERT_EQ(data.positive.size(), 2u);
  ASSERT_EQ(data.negative.size(), 1u);
  ASSERT_EQ(data.other.size(), 1u);
  EXPECT_EQ(data.positive[1].f0_n, 0.3);
  EXPECT_EQ(data.positive[1].edc_j, 3e-5);
  EXPECT_DOUBLE_EQ(data.negative[0].error_j, 6e-7);  // Fig. 10: ±3σ
  EXPECT_EQ(data.other[0].flags, "cross-well");
  ASSERT_TRUE(data.current.has_value());
  EXPECT_EQ(data.current->f0_n, 0.4);
  EXPECT_EQ(data.current_well, analysis::Well::Positive);
  EXPECT_EQ(data.max_f0_n, 2.9);
  // A level with no steady cycle yet is not drawn.
  EXPECT_FALSE(
      edc_plot_data({}, level(analysis::Well::Positive, 0.5, 0, 0, 0)).current.has_value());
}

TEST(PredictionLevels, CoverThePapersRangeOrThatMeasured) {
  const auto levels = prediction_levels(1.0);
  EXPECT_DOUBLE_EQ(levels.front(), 0.1);
  EXPECT_NEAR(levels.back(), 2.7, 1e-9);
  EXPECT_EQ(levels.size(), 53u);  // 0.1 … 2.7 in 0.05 N
  for (std::size_t i = 1; i < levels.size(); ++i) EXPECT_GT(levels[i], levels[i - 1]);
  EXPECT_GE(prediction_levels(3.0).back(), 3.1 - 1e-9);
}

TEST(LevelWarning, NamesTheFlagsOfTheLevelBeingFilled) {
  EXPECT_EQ(level_warning(std::nullopt), "");
  analysis::LevelResult r = level(analysis::Well::Positive, 2.8, 1e-2, 1e-4, 40);
  EXPECT_EQ(level_warning(r), "");
  r.period1 = false;
  r.cross_well = true;
  EXPECT_NE(level_warning(r).find("not period-1"), std::string::npos);
  EXPECT_NE(level_warning(r).find("crosses wells"), std::string::npos);
}

}  // namespace
}  // namespace oscilab::ui
