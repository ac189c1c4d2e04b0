// The measurement analysis against the virtual rig's truth (target: every level's mean EDC within
// 0.5 % + 5 noise-floor σ of the simulator's true dissipated energy, both wells, 0.2 to 2.7 N).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::analysis {
namespace {

SteppedSineSchedule test_schedule() {
  SteppedSineSchedule schedule;
  schedule.levels_n = {0.2, 0.3, 0.5, 0.8, 1.0, 1.3, 1.8, 2.2, 2.7};
  return schedule;
}

daq::RigRecording rig_record(bool positive, std::uint64_t seed,
                             const SteppedSineSchedule& schedule = test_schedule()) {
  daq::RigSpec spec;
  spec.positive_well = positive;
  spec.seed = seed;
  return daq::record_stepped_sine(paper_model(), schedule, spec);
}

void expect_matches_truth(const RecordAnalysis& analysis, const daq::RigRecording& rig,
                          Well expected_well) {
  ASSERT_EQ(analysis.levels.size(), rig.levels.size());
  for (std::size_t i = 0; i < rig.levels.size(); ++i) {
    const LevelResult& measured = analysis.levels[i];
    const double truth = rig.levels[i].edc_j;
    SCOPED_TRACE("level " + std::to_string(rig.levels[i].f0_n) + " N");
    EXPECT_EQ(measured.well, expected_well);
    EXPECT_TRUE(measured.usable()) << measured.flags();
    EXPECT_GE(measured.cycles, 15);
    EXPECT_NEAR(measured.f0_n, rig.levels[i].f0_n, 0.01 * rig.levels[i].f0_n);
    // The accuracy bound: 0.5 % of the value plus 5 σ of the noise floor derived from the sensors.
    EXPECT_NEAR(measured.edc_mean_j, truth, 0.005 * truth + 5.0 * measured.edc_noise_floor_j);
  }
}

class EdcAccuracy : public ::testing::TestWithParam<std::tuple<bool, int>> {};

TEST_P(EdcAccuracy, MeanEdcWithinHalfPercentPlusFiveSigmaOfTruth) {
  const auto [positive, seed] = GetParam();
  const daq::RigRecording rig = rig_record(positive, static_cast<std::uint64_t>(seed));
  const RecordAnalysis analysis =
      analyze_record(daq::measurement_channels(rig.recording), PipelineSettings{});
  EXPECT_FALSE(analysis.frequency_detected);  // the sidecar gives it
  expect_matches_truth(analysis, rig, well_of(positive));
}

INSTANTIATE_TEST_SUITE_P(BothWellsThreeSeeds, EdcAccuracy,
                         ::testing::Combine(::testing::Bool(), ::testing::Values(11, 12, 13)));

TEST(EdcAnalysis, FindsFrequencyAndLevelsWithoutSidecarExcitation) {
  const daq::RigRecording rig = rig_record(true, 21);
  MeasurementChannels channels = daq::measurement_channels(rig.recording);
  channels.excitation_type.clear();
  channels.excitation_freq_hz.reset();
  channels.level_windows.clear();
  const RecordAnalysis analysis = analyze_record(channels, PipelineSettings{});
  EXPECT_TRUE(analysis.frequency_detected);
  EXPECT_TRUE(analysis.stepped_sine);
  // 9 levels of 10 s at 9 Hz: the carrier is found to a few µHz (1e-3 of a 3.8 mHz bin).
  EXPECT_NEAR(analysis.setup.excitation_freq_hz, 9.0, 2e-5);
  expect_matches_truth(analysis, rig, Well::Positive);
}

TEST(EdcAnalysis, LiveBlocksGiveTheOfflineLevels) {
  const daq::RigRecording rig = rig_record(false, 31);
  const MeasurementChannels channels = daq::measurement_channels(rig.recording);
  const RecordAnalysis offline = analyze_record(channels, PipelineSettings{});

  MeasurementPipeline live(PipelineSettings{}, offline.setup);
  const Eigen::Index n = channels.base.size();
  std::uint64_t sequence = 0;
  for (Eigen::Index i = 0, size = 7; i < n; i += size, size = size % 211 + 37) {
    SampleBlock block;  // odd sizes: 7, 44, 81, ... as a DAQ driver might deliver
    block.sequence = sequence++;
    block.t0_s = static_cast<double>(i) / channels.sample_rate_hz;
    const Eigen::Index count = std::min(size, n - i);
    block.samples.resize(count, 2);
    block.samples.col(0) = channels.base.segment(i, count);
    block.samples.col(1) = channels.mass.segment(i, count);
    live.push(block);
  }
  live.finish();
  ASSERT_EQ(live.levels().size(), offline.levels.size());
  for (std::size_t k = 0; k < offline.levels.size(); ++k) {
    // The accuracy target allows 0.5 %; the engine is the same code on the same samples, so the
    // only difference is the block timestamps' rounding (t0 + i/fs vs i/fs): 1e-9 relative.
    EXPECT_NEAR(live.levels()[k].edc_mean_j, offline.levels[k].edc_mean_j,
                1e-9 * offline.levels[k].edc_mean_j);
    EXPECT_EQ(live.levels()[k].cycles, offline.levels[k].cycles);
  }
}

TEST(EdcAnalysis, VibrometerVelocityAndUnknownMassStillGiveTheEnergy) {
  SteppedSineSchedule schedule;
  schedule.levels_n = {0.5, 1.5};
  const daq::RigRecording rig = rig_record(true, 41, schedule);
  MeasurementChannels channels = daq::measurement_channels(rig.recording);
  // A velocity-output vibrometer: ẏ = ż + ḃ, with 1e-4 m/s white noise.
  const SteppedSineMotion motion(schedule, paper_model().mass_kg());
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 1e-4);
  for (Eigen::Index i = 0; i < channels.mass.size(); ++i) {
    channels.mass[i] = rig.truth.z_dot_m_s[i] + motion.at(rig.truth.t_s[i]).b_dot_m_s + noise(rng);
  }
  channels.mass_quantity = MotionQuantity::Velocity;
  channels.mass_kg.reset();  // the sidecar has no mass: energies per unit mass
  channels.well_hint_positive = true;
  const RecordAnalysis analysis = analyze_record(channels, PipelineSettings{});
  EXPECT_TRUE(analysis.per_unit_mass);
  ASSERT_EQ(analysis.levels.size(), 2u);
  const double m = paper_model().mass_kg();
  for (std::size_t i = 0; i < 2; ++i) {
    const double truth_per_kg = rig.levels[i].edc_j / m;
    EXPECT_EQ(analysis.levels[i].well,
              Well::Positive);  // from the hint: a velocity has no position
    EXPECT_NEAR(analysis.levels[i].edc_mean_j, truth_per_kg,
                0.005 * truth_per_kg + 5.0 * analysis.levels[i].edc_noise_floor_j);
  }
}

// Without a position the slices are against z − z̄: they exist, say so, and their slope at
// z − z̄ = 0 is the well's stiffness per unit mass, U''(z₊*)/m = (2π f₊)² (eq. (4)), to within what
// the levels' offset of z̄ from z₊* and the cubic's curvature over their travel move it (measured
// on this seed: 2679 against 2919 N/(kg m), 8 % low; allowed 15 %).
TEST(EdcAnalysis, AVelocityOnlyCampaignStillGivesTheStiffnessAboutTheMeanOfZ) {
  SteppedSineSchedule schedule;
  schedule.levels_n = {0.5, 1.5};
  const daq::RigRecording rig = rig_record(true, 41, schedule);
  MeasurementChannels channels = daq::measurement_channels(rig.recording);
  const SteppedSineMotion motion(schedule, paper_model().mass_kg());
  for (Eigen::Index i = 0; i < channels.mass.size(); ++i) {
    channels.mass[i] = rig.truth.z_dot_m_s[i] + motion.at(rig.truth.t_s[i]).b_dot_m_s;
  }
  channels.mass_quantity = MotionQuantity::Velocity;
  channels.mass_kg.reset();
  channels.well_hint_positive = true;
  const CampaignAnalysis campaign = analyze_campaign({channels}, PipelineSettings{});
  ASSERT_TRUE(campaign.stiffness.has_value()) << campaign.rfs_message;
  EXPECT_TRUE(campaign.z_about_mean);
  double omega2 = 0.0;
  for (const Equilibrium& e : paper_model().equilibria()) {
    if (e.stable && e.z_m > 0) omega2 = std::pow(2 * std::numbers::pi * e.linear_frequency_hz, 2);
  }
  ASSERT_GT(omega2, 0.0);
  const double slope = campaign.stiffness->fit.coefficients[1];  // dK/dz at z − z̄ = 0, per kg
  EXPECT_NEAR(slope, omega2, 0.15 * omega2);
}

TEST(EdcAnalysis, FlagsPeriodDoublingBeyondThreePointFiveNewton) {
  // The paper's model doubles its period on the z₊* branch near 3.4 N (docs/hbm.md); at 3.7 N the
  // response is not period-1 and must be kept out of fits.
  SteppedSineSchedule schedule;
  schedule.levels_n = {2.7, 3.7};
  const daq::RigRecording rig = rig_record(true, 51, schedule);
  const RecordAnalysis analysis =
      analyze_record(daq::measurement_channels(rig.recording), PipelineSettings{});
  ASSERT_EQ(analysis.levels.size(), 2u);
  EXPECT_TRUE(analysis.levels[0].usable());
  EXPECT_FALSE(analysis.levels[1].period1);
  EXPECT_FALSE(analysis.levels[1].usable());
}

// Degenerate recordings of the rig are said, not scored: a base channel held at a constant (an
// unplugged accelerometer's offset), base and mass swapped, or levels whose windows lie past the
// record's end give flagged levels that are not usable, a note saying why, and a record that
// the analysis refuses; the intact record gives none of that.
TEST(EdcAnalysis, DegenerateRecordsAreFlaggedNotedAndRefused) {
  SteppedSineSchedule schedule;
  schedule.levels_n = {0.5, 1.5};
  const daq::RigRecording rig = rig_record(true, 61, schedule);
  const MeasurementChannels intact = daq::measurement_channels(rig.recording);
  const auto analyse = [](const MeasurementChannels& channels) {
    CampaignAnalysis campaign;
    campaign.records.push_back(analyze_record(channels, PipelineSettings{}));
    return campaign;
  };
  const CampaignAnalysis good = analyse(intact);
  EXPECT_EQ(no_measured_level_reason(good.records[0]), "");
  EXPECT_NO_THROW(require_measured_levels(good));

  const auto expect_refused = [&](const MeasurementChannels& channels, const char* flag) {
    SCOPED_TRACE(flag);
    const CampaignAnalysis campaign = analyse(channels);
    const RecordAnalysis& record = campaign.records[0];
    ASSERT_EQ(record.levels.size(), 2u);
    for (const LevelResult& level : record.levels) {
      EXPECT_NE(level.flags().find(flag), std::string::npos) << level.flags();
      EXPECT_FALSE(level.usable());
    }
    const std::string note = std::string("2 of 2 levels flagged ") + flag + ": ";
    EXPECT_TRUE(std::any_of(record.notes.begin(), record.notes.end(),
                            [&](const std::string& n) { return n.rfind(note, 0) == 0; }));
    const std::string reason = no_measured_level_reason(record);
    EXPECT_EQ(reason.rfind(intact.name + ": no usable level: " + note, 0), 0u) << reason;
    EXPECT_THROW(require_measured_levels(campaign), InputError);
  };
  MeasurementChannels constant_base = intact;
  constant_base.base.setConstant(0.004);  // m/s²: the accelerometer's bias alone
  expect_refused(constant_base, "base-constant");
  MeasurementChannels swapped = intact;
  std::swap(swapped.base, swapped.mass);
  std::swap(swapped.base_quantity, swapped.mass_quantity);
  expect_refused(swapped, "negative-edc");
  MeasurementChannels beyond = intact;
  const double duration_s = static_cast<double>(intact.base.size()) / intact.sample_rate_hz;
  for (LevelWindow& window : beyond.level_windows) {
    window.start_s += duration_s;
    window.end_s += duration_s;
  }
  expect_refused(beyond, "beyond-record");
}

}  // namespace
}  // namespace oscilab::analysis
