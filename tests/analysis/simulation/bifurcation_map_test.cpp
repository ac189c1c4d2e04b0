#include "analysis/simulation/bifurcation_map.h"

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/hbm/continuation.h"
#include "analysis/model/reference_models.h"

namespace oscilab::analysis {
namespace {

TEST(BifurcationMap, PaperModelSplitsIntoTwoPointsBeyondTheHbmPeriodDoubling) {
  const Model model = paper_model();
  // The oracle: the HBM branch of the positive well and its period-doubling point (H = 7).
  ContinuationOptions continuation;
  continuation.freq_hz = 9.0;
  continuation.start = 0.1;
  continuation.end = 3.7;
  const Branch branch = continue_branch(model, continuation);
  ASSERT_EQ(branch.status, JobStatus::Ok) << branch.message;
  const auto flips = branch.events_of(PointMarker::PeriodDoubling);
  ASSERT_EQ(flips.size(), 1u);
  const double flip_n = flips[0].f0_n;  // 3.4314 N

  // A coarse grid across the flip keeps the run short (4 levels × 200 periods ≈ 90 s simulated).
  BifurcationMapOptions options;
  options.levels_n = {3.2, 3.35, 3.5, 3.6};
  options.negative_well = false;
  int reports = 0;
  const BifurcationMap map = bifurcation_map(
      model, options, [&reports](double) { ++reports; }, CancelToken{});
  ASSERT_EQ(map.status, JobStatus::Ok) << map.message;
  const auto levels = map.levels_of(true);
  ASSERT_EQ(levels.size(), options.levels_n.size());
  ASSERT_EQ(map.rows.size(), options.levels_n.size() * options.sampled_periods);
  EXPECT_GT(reports, 10);  // about once per simulated second

  // Below the HBM flip the response is period T: the 32 sections are one point (measured spread
  // 7e-14 and 2e-13 m at 3.2 and 3.35 N, rounding of a converged orbit; bound 1 µm, 1e-4 of the
  // ≈ 15 mm section). Beyond it, period 2T: two points alternating (measured 4.6 mm apart at
  // 3.5 N, 7.1 mm at 3.6 N; the split grows like √(f0 − f0_flip) from the flip, so ≥ 1 mm).
  for (const BifurcationMapLevel& level : levels) {
    if (level.f0_n < flip_n) {
      EXPECT_EQ(level.distinct_points, 1) << level.f0_n;
      EXPECT_LT(level.spread_m, 1e-6) << level.f0_n;
    } else {
      EXPECT_EQ(level.distinct_points, 2) << level.f0_n;
      EXPECT_GT(level.spread_m, 1e-3) << level.f0_n;
    }
  }
  // Period 2T exactly: each section repeats two periods later and differs from the next one.
  for (std::size_t i = 2; i < map.rows.size(); ++i) {
    const BifurcationMapRow& row = map.rows[i];
    if (row.f0_n < flip_n || map.rows[i - 2].f0_n != row.f0_n) continue;
    EXPECT_NEAR(row.z_m, map.rows[i - 2].z_m, 1e-6) << row.f0_n;
    EXPECT_GT(std::abs(row.z_m - map.rows[i - 1].z_m), 1e-3) << row.f0_n;
  }

  // The period-T sections lie on the HBM orbit's z(t = 0) = a0 + Σ a_h at the same level, within
  // 0.1 mm (H = 7 truncation; 0.7 % of the ≈ 15 mm).
  for (const BifurcationMapLevel& level : levels) {
    if (level.f0_n > flip_n) continue;
    for (std::size_t i = 1; i < branch.points.size(); ++i) {
      const BranchPoint& a = branch.points[i - 1];
      const BranchPoint& b = branch.points[i];
      if ((a.f0_n - level.f0_n) * (b.f0_n - level.f0_n) > 0.0) continue;
      auto z0 = [](const BranchPoint& p) {
        double z = p.coefficients[0];
        for (Eigen::Index k = 1; k < p.coefficients.size(); k += 2) z += p.coefficients[k];
        return z;
      };
      const double s = (level.f0_n - a.f0_n) / (b.f0_n - a.f0_n);
      EXPECT_NEAR(level.z_min_m, z0(a) + s * (z0(b) - z0(a)), 1e-4) << level.f0_n;
      break;
    }
  }
}

TEST(BifurcationMap, CancelledBeforeTheStartReturnsNoLevels) {
  BifurcationMapOptions options;
  options.levels_n = {1.0, 2.0};
  const CancelToken cancel;
  cancel.cancel();
  const BifurcationMap map = bifurcation_map(paper_model(), options, {}, cancel);
  EXPECT_EQ(map.status, JobStatus::Cancelled);
  EXPECT_TRUE(map.levels.empty());
}

TEST(BifurcationMap, CsvHasOneRowPerSection) {
  BifurcationMap map;
  map.rows = {{3.5, true, 0.0125, 398}, {3.5, false, -0.02, 399}};
  std::ostringstream out;
  write_bifurcation_map_csv(map, out);
  EXPECT_EQ(out.str(), "f0_n,well,z_m,period\n3.5,positive,0.0125,398\n3.5,negative,-0.02,399\n");
}

TEST(BifurcationMap, ThrowsInputErrorForBadOptions) {
  BifurcationMapOptions options;
  options.positive_well = options.negative_well = false;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.sampled_periods = options.hold_periods;
  EXPECT_THROW(options.validate(), InputError);
  options = {};
  options.step_n = 0.0;
  EXPECT_THROW(options.validate(), InputError);
  options = {};  // 73 levels of 10^6 periods: 7.3e7 samples a well, over the simulation's limit
  options.hold_periods = 1000000;
  EXPECT_THROW(options.validate(), InputError);
  options.hold_periods = 100000;
  EXPECT_NO_THROW(options.validate());
}

TEST(BifurcationMap, ResolvedLevelsIncludeTheEnd) {
  BifurcationMapOptions options;  // 0.1 → 3.7 N by 0.05 N
  const std::vector<double> levels = options.resolved_levels();
  ASSERT_EQ(levels.size(), 73u);
  EXPECT_DOUBLE_EQ(levels.front(), 0.1);
  EXPECT_NEAR(levels.back(), 3.7, 1e-12);
}

}  // namespace
}  // namespace oscilab::analysis
