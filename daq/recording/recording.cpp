#include "daq/recording/recording.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <system_error>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/stored_samples.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::daq {

namespace fs = std::filesystem;

double Recording::duration_s() const {
  if (!(sidecar.sample_rate_hz > 0.0)) return 0.0;
  return static_cast<double>(sample_count()) / sidecar.sample_rate_hz;
}

int Recording::channel_index(ChannelRole role) const {
  for (std::size_t i = 0; i < sidecar.channels.size(); ++i) {
    if (sidecar.channels[i].role == role) return static_cast<int>(i);
  }
  return -1;
}

int Recording::channel_index(const std::string& name) const {
  for (std::size_t i = 0; i < sidecar.channels.size(); ++i) {
    if (sidecar.channels[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

RecordingFile open_recording_file(const std::string& path) {
  check_data_file(path);
  if (lower_extension(path) == ".json") {
    throw InputError(path + ": a recording is a data file; .json is its sidecar");
  }
  const FormatReader& format = format_for_file(path);
  const std::string sidecar_path = sidecar_path_for(path);
  std::error_code error;
  if (!fs::exists(sidecar_path, error)) {
    throw InputError(path + ": sidecar " + sidecar_path +
                     " not found (it says what the channels are and the sample rate; "
                     "`oscilab-cli info " +
                     path + "` lists what the file holds and drafts one)");
  }
  return {&format, sidecar_path, read_sidecar(sidecar_path)};
}

Recording read_recording(const std::string& path) {
  const RecordingFile file = open_recording_file(path);
  return file.format->read(path, file.sidecar, file.sidecar_path);
}

Recording read_recording(const std::string& path, const Sidecar& sidecar) {
  const FormatReader& format = format_for_file(path);
  const std::string name = "the sidecar given";
  const Sidecar checked = parse_sidecar(sidecar_to_json(sidecar), path + ": " + name);
  return format.read(path, checked, name);
}

void write_recording(const Recording& recording, const std::string& path) {
  const std::string extension = lower_extension(path);
  const bool csv = extension == ".csv";
  const int sound_format = sound_format_for(extension);
  const bool integer_container = stores_24_bit_integers(sound_format);
  if (!csv && sound_format == 0) {
    throw InputError(path + ": unknown container " + in_quotes(extension) +
                     " (expected .wav, .flac, .w64, .rf64, .aiff, .caf or .csv)");
  }
  const std::string sidecar_path = sidecar_path_for(path);

  // What the sidecar says about where the source file kept each signal does not apply to the
  // file written.
  Sidecar sidecar = recording.sidecar;
  sidecar.csv.reset();
  sidecar.time.reset();
  for (ChannelInfo& channel : sidecar.channels) {
    channel.column = -1;
    channel.source.clear();
  }
  parse_sidecar(sidecar_to_json(sidecar), sidecar_path);

  const Eigen::MatrixXd& samples = recording.samples_si;
  const auto channels = static_cast<Eigen::Index>(sidecar.channels.size());
  if (samples.cols() != channels) {
    throw InputError(path + ": the recording holds " + std::to_string(samples.cols()) +
                     " sample columns, its sidecar lists " + std::to_string(channels) +
                     " channels");
  }
  if (samples.rows() == 0) throw InputError(path + ": no samples to write");

  // Stored value = (SI / unit factor − offset) / scale, the inverse of the reader's calibration.
  std::vector<double> stored(static_cast<std::size_t>(samples.rows() * channels));
  const StoredSamples no_lines;
  for (Eigen::Index c = 0; c < channels; ++c) {
    const ChannelInfo& channel = sidecar.channels[c];
    const double factor = unit_to_si(channel.unit, channel.quantity, sidecar_path);
    for (Eigen::Index r = 0; r < samples.rows(); ++r) {
      const double si = samples(r, c);
      double value = (si / factor - channel.offset) / channel.scale;
      const std::string place = path + ": channel " + in_quotes(channel.name) + ": " +
                                sample_place(r, sidecar.sample_rate_hz, no_lines);
      if (!std::isfinite(si)) {
        if (integer_container || !declared_invalid(sidecar, r)) {
          throw InputError(place + " is not finite" +
                           (integer_container ? " (an integer container cannot hold it)" : ""));
        }
        stored[static_cast<std::size_t>(r * channels + c)] = si;  // what was recorded
        continue;
      }
      if (!std::isfinite(value)) {
        throw InputError(place + ": " + number_text(si) + " overflows with scale " +
                         number_text(channel.scale));
      }
      // Samples that were integer counts times the scale come back as counts to a few ulps;
      // store the count itself (a change of at most 4 ulps) so that files read as counts.
      const double count = std::nearbyint(value);
      if (std::abs(value - count) <=
          4.0 * std::numeric_limits<double>::epsilon() * std::abs(count)) {
        value = count;
      }
      if (integer_container) {
        value = std::nearbyint(value);
        if (value < kInt24Min || value > kInt24Max) {
          throw InputError(place + ": " + number_text(si) + " " + si_unit(channel.quantity) +
                           " is " + number_text(value) + " counts at scale " +
                           number_text(channel.scale) + " " + channel.unit +
                           ", beyond 24-bit FLAC's ±8388607; use a coarser scale or a float64 "
                           "container (.wav, .w64, .caf)");
        }
      }
      stored[static_cast<std::size_t>(r * channels + c)] = value;
    }
  }

  TemporaryFile data_file(path);
  if (csv) {
    write_csv(stored, sidecar, data_file.path(), path);
  } else {
    write_sound(stored, sidecar, sound_format, data_file.path(), path);
  }
  TemporaryFile sidecar_file(sidecar_path);
  write_sidecar(sidecar, sidecar_file.path());
  data_file.commit();
  sidecar_file.commit();
}

}  // namespace oscilab::daq
