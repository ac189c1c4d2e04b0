#include "daq/recording/measurement_mapping.h"

#include <filesystem>

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
  channels.well_hint_positive = overrides.well_positive;
  return channels;
}

}  // namespace oscilab::daq
