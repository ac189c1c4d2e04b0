// A recording analysed with its samples left in the file (streamed_measurement_channels, as
// `analyze` reads it) against the same recording read whole into memory, the second method: the
// same levels to the bit, the same slices to the rounding of a sum taken in another order; and
// a bad sample that only decoding meets refused in the reader's words.
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::TempDir;

// Both wells' stepped sines of the paper's model, 5 levels each (about 55 s).
std::vector<Recording> stepped_sines() {
  analysis::SteppedSineSchedule schedule;
  schedule.levels_n = {0.5, 1.0, 1.5, 2.0, 2.5};
  std::vector<Recording> out;
  for (const bool positive : {true, false}) {
    RigSpec spec;
    spec.positive_well = positive;
    spec.seed = positive ? 21 : 22;
    out.push_back(record_stepped_sine(analysis::paper_model(), schedule, spec).recording);
  }
  return out;
}

analysis::OfflineRetention nothing_kept() {
  analysis::OfflineRetention retention;
  retention.cycles = false;
  retention.motion = false;
  return retention;
}

void expect_same_levels(const analysis::RecordAnalysis& streamed,
                        const analysis::RecordAnalysis& whole) {
  ASSERT_EQ(streamed.levels.size(), whole.levels.size());
  for (std::size_t i = 0; i < whole.levels.size(); ++i) {
    const analysis::LevelResult& a = streamed.levels[i];
    const analysis::LevelResult& b = whole.levels[i];
    EXPECT_EQ(a.f0_n, b.f0_n) << i;
    EXPECT_EQ(a.edc_mean_j, b.edc_mean_j) << i;
    EXPECT_EQ(a.edc_std_j, b.edc_std_j) << i;
    EXPECT_EQ(a.edc_noise_floor_j, b.edc_noise_floor_j) << i;
    EXPECT_EQ(a.cycles, b.cycles) << i;
    EXPECT_EQ(a.flags(), b.flags()) << i;
  }
  EXPECT_EQ(streamed.cycle_count, whole.cycles.size());
  EXPECT_TRUE(streamed.cycles.empty());  // not kept
  EXPECT_EQ(streamed.motion.t_s.size(), 0);
  EXPECT_EQ(streamed.notes, whole.notes);
}

TEST(StreamedChannels, AnalyseAsTheRecordingReadWhole) {
  const TempDir dir;
  const std::vector<Recording> recordings = stepped_sines();
  for (const std::string extension : {".flac", ".wav"}) {
    std::vector<std::string> paths;
    for (std::size_t i = 0; i < recordings.size(); ++i) {
      paths.push_back(dir.file("well" + std::to_string(i) + extension));
      write_recording(recordings[i], paths.back());
    }
    std::vector<analysis::MeasurementChannels> whole, streamed;
    for (const std::string& path : paths) {
      whole.push_back(measurement_channels(read_recording(path)));
      streamed.push_back(streamed_measurement_channels(path));
      ASSERT_NE(streamed.back().source, nullptr) << path;
      EXPECT_EQ(streamed.back().base.size(), 0);  // the samples stay in the file
      EXPECT_EQ(streamed.back().sample_count(), whole.back().base.size());
    }
    const analysis::PipelineSettings settings;
    // The cycles, not kept, are seen as they are fitted, each record's apart (the records are
    // analysed on threads of their own).
    analysis::OfflineRetention seen = nothing_kept();
    std::vector<std::vector<analysis::CycleFit>> visited(2);
    seen.each_cycle = [&](std::size_t record, const analysis::CycleFit& cycle) {
      visited.at(record).push_back(cycle);
    };
    const analysis::CampaignAnalysis a =
        analysis::analyze_campaign(streamed, settings, {}, {}, seen);
    const analysis::CampaignAnalysis b = analysis::analyze_campaign(whole, settings);
    ASSERT_EQ(a.records.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      expect_same_levels(a.records[i], b.records[i]);
      ASSERT_EQ(visited[i].size(), b.records[i].cycles.size()) << i;
      for (std::size_t k = 0; k < visited[i].size(); ++k) {
        EXPECT_EQ(visited[i][k].start_s, b.records[i].cycles[k].start_s);
        EXPECT_EQ(visited[i][k].edc_j, b.records[i].cycles[k].edc_j);
      }
    }
    ASSERT_TRUE(a.stiffness && b.stiffness) << a.rfs_message << b.rfs_message;
    // The band and the 1–99 % range are order statistics: equal. The fit's centre is a mean
    // summed in another order (one pass per stage against Eigen's vectorised sum): its
    // coefficients agree to the rounding that carries through the normal equations (1e-13 of
    // each measured; 1e-11 leaves room for a cubic's condition of some 1e3 on the samples).
    EXPECT_EQ(a.stiffness->velocity_band_m_s, b.stiffness->velocity_band_m_s);
    EXPECT_EQ(a.stiffness->z_min_m, b.stiffness->z_min_m);
    EXPECT_EQ(a.stiffness->z_max_m, b.stiffness->z_max_m);
    EXPECT_EQ(a.stiffness->fit.samples, b.stiffness->fit.samples);
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(a.stiffness->fit.coefficients[k] / b.stiffness->fit.coefficients[k], 1.0, 1e-11)
          << extension << " c" << k;
      EXPECT_NEAR(a.stiffness->fit.std_errors[k] / b.stiffness->fit.std_errors[k], 1.0, 1e-11)
          << extension << " c" << k;
    }
    ASSERT_EQ(a.stiffness->bins.size(), b.stiffness->bins.size());
    for (std::size_t k = 0; k < a.stiffness->bins.size(); ++k) {
      EXPECT_EQ(a.stiffness->bins[k].samples, b.stiffness->bins[k].samples);
      EXPECT_EQ(a.stiffness->bins[k].force_n, b.stiffness->bins[k].force_n);
    }
    ASSERT_EQ(a.damping.size(), b.damping.size());
    ASSERT_GE(a.damping.size(), 1u);  // the stable equilibria the slice crosses
    for (std::size_t d = 0; d < a.damping.size(); ++d) {
      EXPECT_NEAR(a.damping[d].z_center_m, b.damping[d].z_center_m, 1e-12);
      EXPECT_GE(a.damping[d].bins.size(), 10u);
    }
  }
}

TEST(StreamedChannels, ANanInTheFileIsRefusedByThePassThatMeetsIt) {
  const TempDir dir;
  Recording recording = stepped_sines().front();
  write_recording(recording, dir.file("nan.wav"));
  std::string bytes = testing::read_file(dir.file("nan.wav"));
  const std::size_t data = bytes.find("data", 12) + 8;  // float64 samples, interleaved
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const int mass = recording.channel_index(ChannelRole::Mass);
  const auto channels = static_cast<std::size_t>(recording.samples_si.cols());
  std::memcpy(&bytes[data + 8 * (channels * 20000 + static_cast<std::size_t>(mass))], &nan,
              sizeof nan);
  testing::write_file(dir.file("nan.wav"), bytes);
  // Opening it decodes nothing; the analysis's first pass meets the NaN.
  const analysis::MeasurementChannels streamed = streamed_measurement_channels(dir.file("nan.wav"));
  const std::string message = testing::input_error_of(
      [&] { analysis::analyze_campaign({streamed}, {}, {}, {}, nothing_kept()); });
  const std::string name = recording.sidecar.channels[static_cast<std::size_t>(mass)].name;
  EXPECT_EQ(message, dir.file("nan.wav") + ": channel \"" + name +
                         "\": sample 20000 (t = 39.0625 s) is NaN");
}

TEST(StreamedChannels, AFileShorterThanItsHeaderIsRefusedAsTruncated) {
  const TempDir dir;
  write_recording(stepped_sines().front(), dir.file("cut.flac"));
  const std::string bytes = testing::read_file(dir.file("cut.flac"));
  testing::write_file(dir.file("cut.flac"), bytes.substr(0, bytes.size() / 2));
  const analysis::MeasurementChannels streamed =
      streamed_measurement_channels(dir.file("cut.flac"));
  const std::string message = testing::input_error_of(
      [&] { analysis::analyze_campaign({streamed}, {}, {}, {}, nothing_kept()); });
  EXPECT_EQ(message.rfind(dir.file("cut.flac") + ": truncated: the header promises ", 0), 0u)
      << message;
}

TEST(StreamedChannels, OtherFormatsAreReadWhole) {
  const TempDir dir;
  write_recording(stepped_sines().front(), dir.file("run.csv"));
  const analysis::MeasurementChannels channels = streamed_measurement_channels(dir.file("run.csv"));
  EXPECT_EQ(channels.source, nullptr);
  EXPECT_GT(channels.base.size(), 20000);
}

TEST(StreamedChannels, ARecordingThatCannotBeMappedIsRefusedBeforeDecoding) {
  const TempDir dir;
  Recording recording = stepped_sines().front();
  for (ChannelInfo& channel : recording.sidecar.channels) {
    if (channel.role == ChannelRole::Base) channel.role = ChannelRole::Mass;
  }
  write_recording(recording, dir.file("nobase.flac"));
  EXPECT_EQ(
      testing::input_error_of([&] { streamed_measurement_channels(dir.file("nobase.flac")); }),
      dir.file("nobase.flac") + ": no channel with role \"base\" (the table's motion)");
}

}  // namespace
}  // namespace oscilab::daq
