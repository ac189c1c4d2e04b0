// level_response (the model side of an EDC fit): natural continuation with halved steps, and the
// arclength fallback from the last level reached when a fold lies ahead.
#include "analysis/hbm/level_response.h"

#include <cmath>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

#include "analysis/hbm/continuation.h"
#include "analysis/model/reference_models.h"

namespace oscilab::analysis {
namespace {

// Expects level_response's EDCs to be the first crossings of the levels by one continuation from
// rest (the branch a sweep up follows, folds and all).
void expect_first_crossings_from_rest(const Model& model, double freq_hz, bool positive_well,
                                      const std::vector<double>& levels,
                                      const LevelResponse& response) {
  ASSERT_EQ(response.status, JobStatus::Ok) << response.message;
  ASSERT_EQ(response.edc_j.size(), levels.size());
  ContinuationOptions options;
  options.freq_hz = freq_hz;
  options.positive_well = positive_well;
  options.start = 0.0;
  options.end = levels.back();
  options.stability = false;
  options.landing = levels;
  const Branch branch = continue_branch(model, options);
  std::size_t next = 0;
  for (const BranchPoint& p : branch.points) {
    if (next >= levels.size() || std::abs(p.f0_n - levels[next]) > 1e-12) continue;
    if (p.marker != PointMarker::Landing && p.marker != PointMarker::End) continue;
    // Two converged solutions of the same equations (‖r‖ ≤ 1e-11 N): EDCs agree to ~1e-9.
    EXPECT_NEAR(response.edc_j[next] / p.measures.edc_j, 1.0, 1e-8) << "f0 = " << levels[next];
    ++next;
  }
  EXPECT_EQ(next, levels.size());
}

// The illustrative example of eq. (14) folds at 1.3778 N and 1.3477 N (H = 7): a sweep
// up from rest jumps at the upper fold. Levels across it make the fast path stop at the fold and
// hand over to arclength continuation from the last level it reached; the result must equal the
// first crossings of one continuation from rest.
TEST(LevelResponse, LevelsAcrossAFoldEqualFirstCrossingsFromRest) {
  const Model model = illustrative_model();
  const double freq_hz = 0.8 * std::sqrt(800.0 / 1.3) / (2.0 * M_PI);  // 80 % of √(k/m), §4.2
  std::vector<double> levels;
  for (int i = 1; i <= 20; ++i) levels.push_back(0.1 * i);
  const LevelResponse response = level_response(model, freq_hz, true, levels);
  EXPECT_TRUE(response.used_arclength);  // the fold at 1.3778 N is in range
  expect_first_crossings_from_rest(model, freq_hz, true, levels, response);
  // Past the jump the response is on the upper branch: the EDC at 1.4 N is several times that at
  // 1.3 N (the jump of Fig. 11b), not a smooth continuation of the levels below.
  ASSERT_EQ(response.edc_j.size(), levels.size());
  EXPECT_GT(response.edc_j[13] / response.edc_j[12], 2.0);
}

// The paper's softer negative well at 10 Hz jumps up at a fold near 2.45 N and its branch turns
// back to a second fold near 2.20 N before it rises (oscilab-cli hbm --freq 10 --well negative).
// With the top two levels 2.4 and 2.5 N the arclength run resumes at 2.4 N and must follow the
// branch back 0.2 N, twice the 0.1 N between the levels, to reach 2.5 N on the upper branch.
TEST(LevelResponse, ResumedContinuationFollowsAJumpWhoseFoldLiesFarBelow) {
  const Model model = paper_model();
  const std::vector<double> levels = {1.0, 2.0, 2.4, 2.5};
  const LevelResponse response = level_response(model, 10.0, false, levels);
  EXPECT_TRUE(response.used_arclength);
  expect_first_crossings_from_rest(model, 10.0, false, levels, response);
  // On the upper branch: the 2.5 N EDC (about 0.09 J) is about twice that at 2.4 N (about 0.04 J).
  ASSERT_EQ(response.edc_j.size(), levels.size());
  EXPECT_GT(response.edc_j[3] / response.edc_j[2], 1.5);
}

// Between the folds of the paper's negative well at 10 Hz (about 2.20 and 2.45 N) the model has
// two stable responses. A specimen measured on the upper branch at 2.3 and 2.4 N (it jumped
// early) is compared on that branch when its |Z1| is given: the responses there equal the upper
// branch of one continuation from rest (its last crossings of those levels, a second method),
// while the levels with one response keep the sweep's. Without the measurement, or with a
// measurement on the swept branch, the sweep's responses stand.
TEST(LevelResponse, FollowsTheMeasuredBranchBetweenTheFolds) {
  const Model model = paper_model();
  const std::vector<double> levels = {1.0, 2.0, 2.3, 2.4, 2.6};
  ContinuationOptions options;
  options.freq_hz = 10.0;
  options.positive_well = false;
  options.end = levels.back();
  options.stability = false;
  options.landing = levels;
  const Branch branch = continue_branch(model, options);
  std::vector<double> last_edc(levels.size(), 0.0), last_z1(levels.size(), 0.0);
  for (const BranchPoint& p : branch.points) {
    for (std::size_t k = 0; k < levels.size(); ++k) {
      if (std::abs(p.f0_n - levels[k]) <= 1e-12 &&
          (p.marker == PointMarker::Landing || p.marker == PointMarker::End)) {
        last_edc[k] = p.measures.edc_j;
        last_z1[k] = std::abs(p.measures.z1_m);
      }
    }
  }
  const LevelResponse swept = level_response(model, 10.0, false, levels);
  ASSERT_EQ(swept.status, JobStatus::Ok) << swept.message;
  ASSERT_EQ(swept.edc_j.size(), levels.size());
  // The sweep is on the lower branch at 2.3 and 2.4 N: the upper branch dissipates about twice.
  EXPECT_GT(last_edc[2] / swept.edc_j[2], 1.5);
  EXPECT_GT(last_edc[3] / swept.edc_j[3], 1.5);

  const LevelResponse measured_upper = level_response(model, 10.0, false, levels, {}, last_z1);
  ASSERT_EQ(measured_upper.status, JobStatus::Ok);
  EXPECT_EQ(measured_upper.branch_switched, 2);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    // Converged solutions of the same equations (‖r‖ ≤ 1e-11 N) on the same branch.
    EXPECT_NEAR(measured_upper.edc_j[k] / last_edc[k], 1.0, 1e-8) << "f0 = " << levels[k];
  }

  std::vector<double> swept_z1;
  for (const Eigen::VectorXd& x : swept.coefficients) swept_z1.push_back(std::hypot(x[1], x[2]));
  const LevelResponse measured_lower = level_response(model, 10.0, false, levels, {}, swept_z1);
  EXPECT_EQ(measured_lower.branch_switched, 0);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    EXPECT_EQ(measured_lower.edc_j[k], swept.edc_j[k]);
  }
  EXPECT_THROW(level_response(model, 10.0, false, levels, {}, {1e-3}), InputError);
}

TEST(LevelResponse, RejectsDecreasingLevels) {
  EXPECT_THROW(level_response(paper_model(), 9.0, true, {0.5, 0.4}), InputError);
}

}  // namespace
}  // namespace oscilab::analysis
