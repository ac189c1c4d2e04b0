#pragma once

#include <exception>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/pipeline/measurement_channels.h"
#include "daq/recording/opening_control.h"
#include "daq/recording/recording.h"
#include "daq/recording/sample_overview.h"
#include "daq/recording/sidecar.h"

namespace oscilab::daq {

/// Where a recording's samples live, read a window at a time: in memory, or in their file (a
/// sound container read by seeking), so that a record of any length is looked at in memory
/// bounded by its overview, not its length. Reads may come from any thread.
class RecordingSamples {
 public:
  virtual ~RecordingSamples() = default;
  virtual Eigen::Index sample_count() const = 0;
  virtual Eigen::Index channel_count() const = 0;
  /// Samples [first, first + count) of every channel in SI, calibrated as read_recording
  /// calibrates them (AC-coupling inverse included): one row per sample. The window is clipped to
  /// the record. Throws InputError naming the file when it can no longer be read.
  virtual Eigen::MatrixXd read(Eigen::Index first, Eigen::Index count) const = 0;
  /// The base and mass channels for the analysis (measurement_mapping.h), streamed from the
  /// file when the samples live there. Throws InputError as measurement_channels does.
  virtual analysis::MeasurementChannels measurement_channels() const = 0;
  /// The whole recording in memory (for the exports, which write every sample): read from its
  /// file again when the samples live there.
  virtual Recording whole() const = 0;
};

/// A recording opened to be looked at: its sidecar and container, where its samples live and
/// their min/max overview (sample_overview.h).
struct OpenedRecording {
  Sidecar sidecar;
  std::string source_path;  // where it was read from (empty when made in memory)
  std::string container;    // as Recording::container
  std::shared_ptr<const RecordingSamples> samples;
  std::shared_ptr<const SampleOverview> overview;

  Eigen::Index sample_count() const { return samples ? samples->sample_count() : 0; }
  double duration_s() const;
};

/// Opens `path` to be looked at. A sound container's samples stay in the file: one pass decodes
/// it, checks every sample as read_recording does (the same refusals, in the same words) and
/// builds the overview; `control` gets the share of the samples gone through and is polled
/// between the pass's windows of 2^16 samples. Other formats are read whole (read_recording),
/// their samples in SI only: the read reports [0, kReadShare] as it goes (FormatReader::
/// read_controlled: a CSV by its bytes, a file of named signals by its signals), the overview's
/// pass the rest. Throws InputError as read_recording does, and OpeningCancelled when `control`
/// was cancelled.
OpenedRecording open_recording_for_review(const std::string& path,
                                          const OpeningControl& control = {});

/// The share of a whole-read format's opening its read is reported as (the overview's pass, of
/// samples in memory, is the rest).
inline constexpr double kReadShare = 0.8;

/// A recording in memory (made by a program, or read by a caller), held as it is; `control` as
/// for open_recording_for_review (its overview's pass).
OpenedRecording hold_recording(Recording recording, const OpeningControl& control = {});

/// The overview of samples given as a pass over windows (the one builder both holders use), with
/// its progress and cancellation (OpeningControl).
SampleOverview build_overview(const RecordingSamples& samples, const OpeningControl& control = {});

}  // namespace oscilab::daq
