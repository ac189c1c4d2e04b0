#pragma once

#include <optional>
#include <string>

#include "analysis/pipeline/measurement_channels.h"
#include "daq/recording/recording.h"

namespace oscilab::daq {

/// Choices a person can make on the command line where the sidecar is silent or wrong.
struct MappingOverrides {
  std::optional<double> excitation_freq_hz;
  std::optional<bool> well_positive;
  bool ignore_sidecar_levels = false;  // detect levels from the signals instead
};

/// The analysis's view of a recording: the base channel (role "base"), the mass channel (role
/// "mass", or "relative" for z measured directly), their quantities, and the excitation
/// metadata. Throws InputError naming the file when a needed channel is missing or has a
/// quantity the analysis cannot use.
analysis::MeasurementChannels measurement_channels(const Recording& recording,
                                                   const MappingOverrides& overrides = {});

/// Rows of a recording (its samples from some first on, in SI, every channel) mapped as
/// measurement_channels maps the whole: the base and mass columns with the record's metadata, for
/// a window of a record of any length (analysis::window_motion). Throws InputError as
/// measurement_channels does for the sidecar; the record's length is not checked here.
analysis::MeasurementChannels measurement_rows(const Sidecar& sidecar, const std::string& file,
                                               const Eigen::MatrixXd& rows);

/// The analysis's view of the recording at `path` (with its sidecar), its samples left in the
/// file where the format allows it (sound containers: MeasurementChannels::source, decoded a
/// pass at a time, so that a record of any length is analysed in bounded memory), read whole
/// otherwise. Refuses what read_recording refuses, in its words; a problem with a sample that
/// only decoding shows (a non-finite value, a file shorter than its header) is thrown by the
/// pass that meets it.
analysis::MeasurementChannels streamed_measurement_channels(const std::string& path,
                                                            const MappingOverrides& overrides = {});

}  // namespace oscilab::daq
