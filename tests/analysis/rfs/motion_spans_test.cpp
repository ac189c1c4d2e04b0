// A record's motion signals made span by span (analysis/rfs/motion_spans.h) against the same
// signals from one transform of the whole record (motion_signals), the second method: equal for a
// record that fits in one span, and for a longer one equal to within an error that falls as the
// margin around each span grows.
#include "analysis/rfs/motion_spans.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "analysis/model/reference_models.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::analysis {
namespace {

// A 60 s cross-well random record of the paper's model: the broadband motion the slices use.
const MeasurementChannels& random_record() {
  static const MeasurementChannels channels = [] {
    daq::RigSpec spec;
    spec.seed = 7;
    RandomMotionSpec random;
    random.duration_s = 60.0;
    random.force_rms_n = 2.0;
    return daq::measurement_channels(daq::record_random(paper_model(), random, spec).recording);
  }();
  return channels;
}

MotionSignals concatenated_spans(const MeasurementChannels& channels,
                                 const MotionSpanning& spanning, int* spans = nullptr) {
  MotionSignals all;
  std::vector<double> t, z, v, r;
  int count = 0;
  for_each_motion_span(
      channels, PipelineSettings{},
      [&](const MotionSignals& span, double record_end_s) {
        EXPECT_DOUBLE_EQ(record_end_s,
                         static_cast<double>(channels.base.size() - 1) / channels.sample_rate_hz);
        for (Eigen::Index i = 0; i < span.t_s.size(); ++i) {
          t.push_back(span.t_s[i]);
          z.push_back(span.z_m[i]);
          v.push_back(span.z_dot_m_s[i]);
          r.push_back(span.restoring_force_n[i]);
        }
        ++count;
      },
      CancelToken(), spanning);
  const auto vector = [](const std::vector<double>& x) {
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(x.data(), Eigen::Index(x.size())));
  };
  all.t_s = vector(t);
  all.z_m = vector(z);
  all.z_dot_m_s = vector(v);
  all.restoring_force_n = vector(r);
  if (spans) *spans = count;
  return all;
}

// The largest difference of a signal from the whole-record one away from the record's ends,
// relative to the signal's range. Near its ends the whole-record transform itself is off by up
// to 1e-3 of the range within 5 s of them (a record that stops mid-motion leaks through the
// high-pass, docs/analysis.md), and a span there meets the same end with another length: the
// two are compared beyond those 5 s, where the margin is what decides.
double relative_difference(const Eigen::VectorXd& spans, const Eigen::VectorXd& whole,
                           const Eigen::VectorXd& t_s, double trim_s) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < whole.size(); ++i) {
    if (t_s[i] < trim_s || t_s[i] > t_s[t_s.size() - 1] - trim_s) continue;
    worst = std::max(worst, std::abs(spans[i] - whole[i]));
  }
  return worst / (whole.maxCoeff() - whole.minCoeff());
}

TEST(MotionSpans, ARecordWithinOneSpanIsTheWholeRecordTransform) {
  const MeasurementChannels& channels = random_record();
  const MotionSignals whole =
      motion_signals(channels, PipelineSettings{}, channels.mass_kg.value_or(1.0));
  int spans = 0;
  const MotionSignals spanned = concatenated_spans(channels, MotionSpanning(), &spans);
  EXPECT_EQ(spans, 1);
  EXPECT_EQ(spanned.t_s, whole.t_s);
  EXPECT_EQ(spanned.z_m, whole.z_m);
  EXPECT_EQ(spanned.z_dot_m_s, whole.z_dot_m_s);
  EXPECT_EQ(spanned.restoring_force_n, whole.restoring_force_n);
}

TEST(MotionSpans, SpansAgreeWithTheWholeRecordBetterAsTheirMarginGrows) {
  const MeasurementChannels& channels = random_record();
  const MotionSignals whole =
      motion_signals(channels, PipelineSettings{}, channels.mass_kg.value_or(1.0));
  const double trim_s = 5.0;
  const auto expected_spans = static_cast<int>((channels.base.size() + 2047) / 2048);
  double previous = std::numeric_limits<double>::infinity();
  // Measured: z 8.8e-4, 1.7e-4, 3.4e-5, 5.6e-6 of its range for 2, 4, 8, 16 periods (R 4.6e-7
  // down to 8.8e-10); 32 periods give 4.5e-6, where the whole-record transform's own end error
  // is what is left of the difference.
  for (const double periods : {2.0, 4.0, 8.0, 16.0}) {
    MotionSpanning spanning;
    spanning.whole_record_samples = 4096;  // 8 s: the 60 s record in spans of 4 s
    spanning.span_samples = 2048;
    spanning.margin_highpass_periods = periods;
    int spans = 0;
    const MotionSignals spanned = concatenated_spans(channels, spanning, &spans);
    EXPECT_EQ(spans, expected_spans);
    ASSERT_EQ(spanned.t_s.size(), whole.t_s.size());
    for (Eigen::Index i = 0; i < whole.t_s.size(); ++i) {
      ASSERT_NEAR(spanned.t_s[i], whole.t_s[i], 1e-12) << i;  // one clock, no sample twice
    }
    const double z = relative_difference(spanned.z_m, whole.z_m, whole.t_s, trim_s);
    const double v = relative_difference(spanned.z_dot_m_s, whole.z_dot_m_s, whole.t_s, trim_s);
    const double r =
        relative_difference(spanned.restoring_force_n, whole.restoring_force_n, whole.t_s, trim_s);
    const double worst = std::max({z, v, r});
    std::printf("margin %2.0f high-pass periods: z %.2e, z_dot %.2e, R %.2e of their range\n",
                periods, z, v, r);
    EXPECT_LT(worst, previous);  // convergence under refinement of the margin
    previous = worst;
    // The default margin of 16 periods: the figure MotionSpanning documents (5.6e-6 measured).
    if (periods == 16.0) {
      EXPECT_LT(worst, 1e-5);
    }
  }
}

TEST(MotionSpans, RestoringForceNearAnInvalidIntervalIsLeftOutInEverySpan) {
  MeasurementChannels channels = random_record();
  channels.excluded.push_back({20.0, 20.5});  // a gap inside the third span of 8 s
  for (Eigen::Index i = 20 * 512; i <= Eigen::Index(20.5 * 512); ++i) {
    channels.mass[i] = std::numeric_limits<double>::quiet_NaN();
  }
  MotionSpanning spanning;
  spanning.whole_record_samples = 4096;
  spanning.span_samples = 4096;
  const MotionSignals spanned = concatenated_spans(channels, spanning);
  const double margin_s = 1.0 / PipelineSettings{}.integration_highpass_hz;
  for (Eigen::Index i = 0; i < spanned.t_s.size(); ++i) {
    const double t = spanned.t_s[i];
    const bool near = t >= 20.0 - margin_s && t <= 20.5 + margin_s;  // overlaps() is inclusive
    EXPECT_EQ(std::isfinite(spanned.restoring_force_n[i]), !near) << "t = " << t;
    EXPECT_TRUE(std::isfinite(spanned.z_m[i])) << "t = " << t;  // the gap filled
  }
}

}  // namespace
}  // namespace oscilab::analysis
