#pragma once

#include <functional>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/pipeline/measurement_channels.h"
#include "analysis/pipeline/pipeline_settings.h"
#include "analysis/rfs/motion_signals.h"

namespace oscilab::analysis {

/// How a record's motion signals (motion_signals.h) are made a span at a time, so that a record
/// of any length is transformed in bounded memory.
struct MotionSpanning {
  /// A record of up to this many samples is transformed whole, exactly as motion_signals does:
  /// 2^20 samples, 34 min at 512 Hz.
  Eigen::Index whole_record_samples = Eigen::Index{1} << 20;
  /// A longer one in consecutive spans of this many samples (512 s at 512 Hz), each transformed
  /// together with a margin of the record on either side, which is dropped afterwards.
  Eigen::Index span_samples = Eigen::Index{1} << 18;
  /// The zero-phase filters of the transform ring near its ends as they do near a record's
  /// (where the slices leave out edge_trim_s): this margin is 16 periods of the integration
  /// high-pass, the slowest of them (16 s at the default 1 Hz); the spans then agree with the
  /// whole-record transform to 6e-6 of z's range and 1e-9 of R's, far below the sensors' noise
  /// (tests/analysis/rfs/motion_spans_test.cpp measures it; the error falls about 5x for each
  /// doubling of the margin up to there).
  double margin_highpass_periods = 16.0;
};

/// One span of a record's motion signals (t_s on the record's clock), and the record's last
/// sample time, for the slices' trim at the record's ends.
using MotionSpanVisit = std::function<void(const MotionSignals& span, double record_end_s)>;

/// Calls visit() with the record's z, ż and R span after span, in time order, computed as
/// motion_signals() does after the non-finite samples of the sidecar's invalid intervals are
/// filled (gap_fill.h), and with R non-finite within one high-pass period of such an interval
/// (the filters spread a bad stretch over about that). Reads the record through
/// MeasurementChannels::open(), so a record streamed from its file is read once per call.
/// Stops between spans when `cancel` is set.
void for_each_motion_span(const MeasurementChannels& channels, const PipelineSettings& settings,
                          const MotionSpanVisit& visit, const CancelToken& cancel = CancelToken(),
                          const MotionSpanning& spanning = MotionSpanning());

/// The samples a window of a record is transformed from: [first, end) with the spans' margin on
/// either side, as far as the record reaches.
struct SampleRange {
  Eigen::Index first = 0, end = 0;
};
SampleRange motion_window_range(Eigen::Index first, Eigen::Index end, Eigen::Index record_samples,
                                double sample_rate_hz, const PipelineSettings& settings,
                                const MotionSpanning& spanning = MotionSpanning());

/// z, ż, R and the excitation force f = −m b̈ (eq. 1) of a window of a record, for what is looked
/// at a stretch at a time (a level's loop in a record of any length).
struct WindowMotion {
  MotionSignals motion;
  Eigen::VectorXd force_n;
};
/// Of samples [first, end) of a record, from `window`: the record's channels (its metadata and
/// invalid intervals) over the samples from `window_first` on, which should be
/// motion_window_range(first, end, ...). The same as what for_each_motion_span gives there, to
/// the spans' accuracy (the margin is the spans'); t_s on the record's clock; R left out near
/// the record's invalid intervals. Throws InputError when [first, end) is not inside the window.
WindowMotion window_motion(const MeasurementChannels& window, Eigen::Index window_first,
                           Eigen::Index first, Eigen::Index end, const PipelineSettings& settings);

}  // namespace oscilab::analysis
