#include "daq/recording/measurement_mapping.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "analysis/common/input_error.h"
#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/formats/sound_file.h"

namespace oscilab::daq {
namespace {

analysis::MotionQuantity motion_quantity(const ChannelInfo& channel, const std::string& file) {
  switch (channel.quantity) {
    case Quantity::Displacement:
      return analysis::MotionQuantity::Displacement;
    case Quantity::Velocity:
      return analysis::MotionQuantity::Velocity;
    case Quantity::Acceleration:
      return analysis::MotionQuantity::Acceleration;
    case Quantity::Force:
      break;
  }
  throw InputError(file + ": channel \"" + channel.name + "\" (role " + to_string(channel.role) +
                   ") measures a force; a motion quantity is needed there");
}

// A stepped-sine analysis fits whole cycles: the frequency must be below Nyquist and the record
// must hold at least two of its cycles (a lower frequency would ask for cycles longer than the
// record, and buffers to match).
void check_excitation_frequency(double frequency_hz, double sample_rate_hz, Eigen::Index samples,
                                const std::string& where) {
  const auto number = [](double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return std::string(buffer);
  };
  if (!(frequency_hz > 0.0) || !std::isfinite(frequency_hz)) {
    throw InputError(where + ": " + number(frequency_hz) + " Hz is not a positive frequency");
  }
  if (frequency_hz >= 0.5 * sample_rate_hz) {
    throw InputError(where + ": " + number(frequency_hz) +
                     " Hz is not below the Nyquist frequency, " + number(0.5 * sample_rate_hz) +
                     " Hz at " + number(sample_rate_hz) + " Hz sampling");
  }
  const double duration_s = static_cast<double>(samples) / sample_rate_hz;
  if (frequency_hz * duration_s < 2.0) {
    throw InputError(where + ": " + number(frequency_hz) + " Hz: the record's " +
                     number(duration_s) + " s hold fewer than two of its cycles");
  }
}

}  // namespace

namespace {

// The recording's channels without their samples, and the columns of base and mass.
struct ChannelMapping {
  analysis::MeasurementChannels channels;
  int base_column = -1;
  int mass_column = -1;
};

int channel_with_role(const Sidecar& sidecar, ChannelRole role) {
  for (std::size_t i = 0; i < sidecar.channels.size(); ++i) {
    if (sidecar.channels[i].role == role) return static_cast<int>(i);
  }
  return -1;
}

// The excitation frequency, given or the sidecar's, checked against the record's length.
void check_frequency_of(const analysis::MeasurementChannels& channels, const std::string& file,
                        Eigen::Index samples, const MappingOverrides& overrides) {
  if (!channels.excitation_freq_hz) return;
  const std::string where = overrides.excitation_freq_hz
                                ? file + ": the excitation frequency given (--freq)"
                                : sidecar_path_for(file) + ": excitation.frequency_hz";
  check_excitation_frequency(*channels.excitation_freq_hz, channels.sample_rate_hz, samples, where);
}

ChannelMapping map_channels(const Sidecar& sidecar, const std::string& file,
                            const MappingOverrides& overrides) {
  ChannelMapping mapping;
  const int base = channel_with_role(sidecar, ChannelRole::Base);
  int mass = channel_with_role(sidecar, ChannelRole::Mass);
  const bool relative = mass < 0;
  if (relative) mass = channel_with_role(sidecar, ChannelRole::Relative);
  if (base < 0) throw InputError(file + ": no channel with role \"base\" (the table's motion)");
  if (mass < 0) {
    throw InputError(file + ": no channel with role \"mass\" or \"relative\" (the mass's motion)");
  }
  mapping.base_column = base;
  mapping.mass_column = mass;
  analysis::MeasurementChannels& channels = mapping.channels;
  channels.name = std::filesystem::path(file).filename().string();
  channels.sample_rate_hz = sidecar.sample_rate_hz;
  channels.mass_kg = sidecar.mass_kg;
  channels.base_quantity = motion_quantity(sidecar.channels[static_cast<std::size_t>(base)], file);
  channels.mass_quantity = motion_quantity(sidecar.channels[static_cast<std::size_t>(mass)], file);
  channels.mass_is_relative = relative;
  if (sidecar.excitation) {
    const Excitation& e = *sidecar.excitation;
    channels.excitation_type = e.type;
    channels.excitation_freq_hz = e.frequency_hz;
    if (!overrides.ignore_sidecar_levels) {
      for (const ExcitationLevel& level : e.levels) {
        channels.level_windows.push_back({level.start_s, level.end_s, level.f0_n});
      }
    }
  }
  for (const InvalidInterval& interval : sidecar.invalid_intervals) {
    channels.excluded.push_back({interval.start_s, interval.end_s});
  }
  if (overrides.excitation_freq_hz) channels.excitation_freq_hz = overrides.excitation_freq_hz;
  channels.well_hint_positive = overrides.well_positive;
  return mapping;
}

}  // namespace

analysis::MeasurementChannels measurement_channels(const Recording& recording,
                                                   const MappingOverrides& overrides) {
  const std::string file =
      recording.source_path.empty() ? std::string("recording") : recording.source_path;
  ChannelMapping mapping = map_channels(recording.sidecar, file, overrides);
  check_frequency_of(mapping.channels, file, recording.samples_si.rows(), overrides);
  mapping.channels.base = recording.samples_si.col(mapping.base_column);
  mapping.channels.mass = recording.samples_si.col(mapping.mass_column);
  return std::move(mapping.channels);
}

analysis::MeasurementChannels measurement_rows(const Sidecar& sidecar, const std::string& file,
                                               const Eigen::MatrixXd& rows) {
  ChannelMapping mapping = map_channels(sidecar, file, {});
  mapping.channels.base = rows.col(mapping.base_column);
  mapping.channels.mass = rows.col(mapping.mass_column);
  return std::move(mapping.channels);
}

analysis::MeasurementChannels streamed_measurement_channels(const std::string& path,
                                                            const MappingOverrides& overrides) {
  const RecordingFile file = open_recording_file(path);
  if (file.format == &sound_format()) {
    ChannelMapping mapping = map_channels(file.sidecar, path, overrides);
    std::shared_ptr<const analysis::ChannelSource> source = sound_channel_source(
        path, file.sidecar, file.sidecar_path, mapping.base_column, mapping.mass_column);
    if (source) {  // else the file does not state its length: read it whole
      check_frequency_of(mapping.channels, path, source->sample_count(), overrides);
      mapping.channels.source = std::move(source);
      return std::move(mapping.channels);
    }
  }
  return measurement_channels(file.format->read(path, file.sidecar, file.sidecar_path), overrides);
}

}  // namespace oscilab::daq
