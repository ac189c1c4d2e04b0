// The analysis settings' ranges: the defaults pass; each setting out of range is refused with
// one InputError naming it and its value, by the settings, the pipeline and the offline analysis
// alike (so every front end gets the same message).
#include "analysis/pipeline/pipeline_settings.h"

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/pipeline/measurement_pipeline.h"
#include "analysis/pipeline/offline_analysis.h"
#include "tests/input_error_of.h"

namespace oscilab::analysis {
namespace {

using oscilab::testing::input_error_of;

TEST(PipelineSettings, DefaultsAreValid) { EXPECT_NO_THROW(PipelineSettings{}.validate()); }

TEST(PipelineSettings, EachSettingOutOfRangeIsNamedWithItsValue) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    std::function<void(PipelineSettings&)> set;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {[](PipelineSettings& s) { s.harmonics = 0; }, "harmonics = 0"},
      {[](PipelineSettings& s) { s.harmonics = -3; }, "harmonics = -3"},
      {[&](PipelineSettings& s) { s.well_boundary_m = nan; }, "well_boundary_m = nan"},
      {[](PipelineSettings& s) { s.min_steady_cycles = 0; }, "min_steady_cycles = 0"},
      {[](PipelineSettings& s) { s.steady_rel_tol = 0.0; }, "steady_rel_tol = 0"},
      {[](PipelineSettings& s) { s.level_change_rel = -0.1; }, "level_change_rel = -0.1"},
      {[](PipelineSettings& s) { s.integration_highpass_hz = 0.0; }, "integration_highpass_hz = 0"},
      {[&](PipelineSettings& s) { s.derivative_lowpass_hz = nan; }, "derivative_lowpass_hz = nan"},
      {[](PipelineSettings& s) { s.stiffness_velocity_band_rel = 0.0; },
       "stiffness_velocity_band_rel = 0"},
      {[](PipelineSettings& s) { s.damping_position_band_rel = -1.0; },
       "damping_position_band_rel = -1"},
      {[](PipelineSettings& s) { s.stiffness_bins = 0; }, "stiffness_bins = 0"},
      {[](PipelineSettings& s) { s.damping_bins = -2; }, "damping_bins = -2"},
      {[](PipelineSettings& s) { s.edge_trim_s = -1.0; }, "edge_trim_s = -1"},
  };
  for (const Case& c : cases) {
    PipelineSettings settings;
    c.set(settings);
    const std::string message = input_error_of([&] { settings.validate(); });
    EXPECT_NE(message.find("analysis setting " + c.expected + ":"), std::string::npos) << message;
  }
}

TEST(PipelineSettings, ThePipelineAndTheOfflineAnalysisRefuseThemToo) {
  PipelineSettings settings;
  settings.harmonics = 0;
  StreamSetup setup;
  setup.sample_rate_hz = 512.0;
  setup.excitation_freq_hz = 9.0;
  EXPECT_NE(
      input_error_of([&] { MeasurementPipeline pipeline(settings, setup); }).find("harmonics = 0"),
      std::string::npos);
  MeasurementChannels channels;
  channels.name = "r";
  channels.sample_rate_hz = 512.0;
  channels.base = Eigen::VectorXd::Zero(1024);
  channels.mass = Eigen::VectorXd::Zero(1024);
  EXPECT_NE(input_error_of([&] { analyze_campaign({channels}, settings); }).find("harmonics = 0"),
            std::string::npos);
}

}  // namespace
}  // namespace oscilab::analysis
