#include "daq/recording/measurement_mapping.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "analysis/common/input_error.h"

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

analysis::MeasurementChannels measurement_channels(const Recording& recording,
                                                   const MappingOverrides& overrides) {
  const std::string file =
      recording.source_path.empty() ? std::string("recording") : recording.source_path;
  const Sidecar& sidecar = recording.sidecar;
  const int base = recording.channel_index(ChannelRole::Base);
  int mass = recording.channel_index(ChannelRole::Mass);
  const bool relative = mass < 0;
  if (relative) mass = recording.channel_index(ChannelRole::Relative);
  if (base < 0) throw InputError(file + ": no channel with role \"base\" (the table's motion)");
  if (mass < 0) {
    throw InputError(file + ": no channel with role \"mass\" or \"relative\" (the mass's motion)");
  }
  analysis::MeasurementChannels channels;
  channels.name = std::filesystem::path(file).filename().string();
  channels.sample_rate_hz = sidecar.sample_rate_hz;
  channels.mass_kg = sidecar.mass_kg;
  channels.base = recording.samples_si.col(base);
  channels.base_quantity = motion_quantity(sidecar.channels[static_cast<std::size_t>(base)], file);
  channels.mass = recording.samples_si.col(mass);
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
  if (channels.excitation_freq_hz) {
    const std::string where = overrides.excitation_freq_hz
                                  ? file + ": the excitation frequency given (--freq)"
                                  : sidecar_path_for(file) + ": excitation.frequency_hz";
    check_excitation_frequency(*channels.excitation_freq_hz, sidecar.sample_rate_hz,
                               recording.samples_si.rows(), where);
  }
  channels.well_hint_positive = overrides.well_positive;
  return channels;
}

}  // namespace oscilab::daq
