// The stiffness slice and K(z) fit against the model's true K(z) (target: within 2 % of the force
// span over the travelled range; k3 and k1 within 5 %), on noisy virtual-rig records.
#include <cmath>

#include <gtest/gtest.h>

#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::analysis {
namespace {

void expect_stiffness_recovered(const CampaignAnalysis& campaign) {
  ASSERT_TRUE(campaign.stiffness.has_value()) << campaign.rfs_message;
  const StiffnessSlice& slice = *campaign.stiffness;
  const Model model = paper_model();
  double k_min = 1e300, k_max = -1e300, worst = 0.0;
  for (int i = 0; i <= 200; ++i) {
    const double z = slice.z_min_m + (slice.z_max_m - slice.z_min_m) * i / 200.0;
    const double k_true = model.elastic_force(z);
    k_min = std::min(k_min, k_true);
    k_max = std::max(k_max, k_true);
    worst = std::max(worst, std::abs(slice.fit.value(z) - k_true));
  }
  EXPECT_LT(worst / (k_max - k_min), 0.02) << "worst " << worst << " N";
  // Table 1 via eq. (2): k3 = c3, k1 = −c1.
  EXPECT_NEAR(slice.fit.coefficients[3] / 7.35e5, 1.0, 0.05);
  EXPECT_NEAR(-slice.fit.coefficients[1] / 550.0, 1.0, 0.05);
}

TEST(StiffnessSlice, RecoversKOfZFromACrossWellRandomRecord) {
  daq::RigSpec spec;
  spec.seed = 7;
  RandomMotionSpec random;
  random.duration_s = 60.0;
  random.force_rms_n = 2.0;  // crosses the barrier about half the time (seed 7)
  const daq::RigRecording rig = daq::record_random(paper_model(), random, spec);
  // Cross-well: the record visits both wells.
  ASSERT_LT(rig.truth.z_m.minCoeff(), -0.02);
  ASSERT_GT(rig.truth.z_m.maxCoeff(), 0.015);
  const CampaignAnalysis campaign =
      analyze_campaign({daq::measurement_channels(rig.recording)}, PipelineSettings{});
  EXPECT_FALSE(campaign.records[0].stepped_sine);
  expect_stiffness_recovered(campaign);
}

TEST(StiffnessSlice, RecoversKOfZFromBothSteppedSineTests) {
  // §3.2: the two stepped-sine tests stacked.
  SteppedSineSchedule schedule;
  schedule.levels_n = {0.5, 1.0, 1.5, 2.0, 2.7};
  std::vector<MeasurementChannels> records;
  for (bool positive : {true, false}) {
    daq::RigSpec spec;
    spec.positive_well = positive;
    spec.seed = positive ? 8 : 9;
    records.push_back(daq::measurement_channels(
        daq::record_stepped_sine(paper_model(), schedule, spec).recording));
  }
  expect_stiffness_recovered(analyze_campaign(records, PipelineSettings{}));
}

}  // namespace
}  // namespace oscilab::analysis
