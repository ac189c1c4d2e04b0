#include "daq/recording/format_reader.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

// "group/a", "group/b", ... (at most 12), for a message about a name that is not there.
std::string signal_list(const FileContents& contents) {
  std::string list;
  for (std::size_t i = 0; i < contents.file_signals.size() && i < 12; ++i) {
    list += (i == 0 ? "" : ", ") + in_quotes(contents.file_signals[i].name);
  }
  if (contents.file_signals.size() > 12) list += ", ...";
  return list.empty() ? "none" : list;
}

const FileSignal& find_signal(const FileContents& contents, const std::string& name, int column,
                              const std::string& path, const std::string& what) {
  const auto it = std::find_if(contents.file_signals.begin(), contents.file_signals.end(),
                               [&](const FileSignal& signal) { return signal.name == name; });
  if (it == contents.file_signals.end()) {
    // A name the format lists as skipped (not numeric, not a vector or matrix, ...): say why.
    if (const auto skipped = contents.properties.find("skipped");
        skipped != contents.properties.end() && skipped->is_array()) {
      for (const nlohmann::json& item : *skipped) {
        if (item.is_object() && item.value("name", "") == name) {
          throw InputError(path + ": " + what + " reads " + in_quotes(name) +
                           ", which is not a signal: " + item.value("reason", ""));
        }
      }
    }
    throw InputError(path + ": " + what + " reads " + in_quotes(name) +
                     ", which the file does not hold (it holds " + signal_list(contents) +
                     "; `oscilab-cli info` lists them)");
  }
  if (it->columns > 1 && column < 0) {
    throw InputError(path + ": " + what + ": " + in_quotes(name) + " has " +
                     std::to_string(it->columns) +
                     " columns; the sidecar must pick one (\"column\")");
  }
  if (column >= 0 && column >= it->columns) {
    throw InputError(path + ": " + what + " reads column " + std::to_string(column) + " of " +
                     in_quotes(name) + ", which has " + std::to_string(it->columns) +
                     (it->columns == 1 ? " column" : " columns") + " (0-based)");
  }
  if (it->sample_count <= 0) {
    throw InputError(path + ": " + what + ": " + in_quotes(name) + " holds no samples");
  }
  return *it;
}

}  // namespace

Recording FormatReader::read_controlled(const std::string& path, const Sidecar& sidecar,
                                        const std::string& sidecar_name,
                                        const OpeningControl& control) const {
  if (control.cancel.cancelled()) throw OpeningCancelled();
  Recording recording = read(path, sidecar, sidecar_name);
  if (control.cancel.cancelled()) throw OpeningCancelled();
  if (control.progress) control.progress(1.0);
  return recording;
}

Recording SignalFileReader::read(const std::string& path, const Sidecar& sidecar,
                                 const std::string& sidecar_name) const {
  return read_controlled(path, sidecar, sidecar_name, {});
}

Recording SignalFileReader::read_controlled(const std::string& path, const Sidecar& sidecar,
                                            const std::string& sidecar_name,
                                            const OpeningControl& control) const {
  // One step per signal read: the time's (when the sidecar maps one), then each channel's.
  const double steps = static_cast<double>(sidecar.channels.size() + (sidecar.time ? 1 : 0));
  double done = 0.0;
  const auto step_done = [&] {
    if (control.cancel.cancelled()) throw OpeningCancelled();
    done += 1.0;
    if (control.progress) control.progress(done / steps);
  };
  if (control.cancel.cancelled()) throw OpeningCancelled();
  const FileContents contents = describe(path);
  const auto channels = static_cast<Eigen::Index>(sidecar.channels.size());
  std::vector<const FileSignal*> mapped;
  for (const ChannelInfo& channel : sidecar.channels) {
    const std::string& name = channel.source.empty() ? channel.name : channel.source;
    const std::string what = "channel " + in_quotes(channel.name) + " of " + sidecar_name;
    const FileSignal& signal = find_signal(contents, name, channel.column, path, what);
    if (!mapped.empty() && signal.sample_count != mapped.front()->sample_count) {
      throw InputError(path + ": " + in_quotes(signal.name) + " holds " +
                       std::to_string(signal.sample_count) + " samples, " +
                       in_quotes(mapped.front()->name) + " " +
                       std::to_string(mapped.front()->sample_count) +
                       "; a recording's channels have one length");
    }
    // A rate the file states must agree with the sidecar's to within half a sample over the
    // whole signal (the criterion of a time axis, TimeAxisCheck).
    const double rate_hz = sidecar.sample_rate_hz;
    if (signal.sample_rate_hz) {
      const double drift_s = std::abs(static_cast<double>(signal.sample_count) *
                                      (1.0 / *signal.sample_rate_hz - 1.0 / rate_hz));
      if (!(drift_s <= 0.5 / rate_hz)) {
        throw InputError(path + ": " + in_quotes(signal.name) + " is sampled at " +
                         number_text(*signal.sample_rate_hz) + " Hz, " + sidecar_name +
                         " says sample_rate_hz " + number_text(rate_hz));
      }
    }
    mapped.push_back(&signal);
  }
  const auto rows = static_cast<Eigen::Index>(mapped.front()->sample_count);

  if (sidecar.time) {
    const std::string what = "the time of " + sidecar_name;
    const FileSignal& signal =
        find_signal(contents, sidecar.time->source, sidecar.time->column, path, what);
    if (signal.sample_count != rows) {
      throw InputError(path + ": " + what + " (" + in_quotes(signal.name) + ") holds " +
                       std::to_string(signal.sample_count) + " samples, the channels " +
                       std::to_string(rows));
    }
    const std::vector<double> time_s = read_signal(path, signal, sidecar.time->column);
    TimeAxisCheck check(sidecar.sample_rate_hz, sidecar_name);
    for (std::size_t i = 0; i < time_s.size(); ++i) {
      if (const std::string problem = check.next(time_s[i]); !problem.empty()) {
        throw InputError(path + ": " + in_quotes(signal.name) + ", sample " + std::to_string(i) +
                         ": " + problem);
      }
    }
    step_done();
  }

  StoredSamples stored;
  stored.values.resize(static_cast<std::size_t>(rows * channels));
  for (Eigen::Index c = 0; c < channels; ++c) {
    const std::vector<double> values = read_signal(path, *mapped[c], sidecar.channels[c].column);
    if (static_cast<Eigen::Index>(values.size()) != rows) {
      throw InputError(path + ": " + in_quotes(mapped[c]->name) + ": read " +
                       std::to_string(values.size()) + " samples, the file announced " +
                       std::to_string(rows));
    }
    for (Eigen::Index r = 0; r < rows; ++r) stored.values[r * channels + c] = values[r];
    step_done();
  }

  Recording recording;
  recording.sidecar = sidecar;
  recording.samples_si = calibrate(stored, sidecar, path);
  recording.samples_stored = as_matrix(stored, channels);
  recording.source_path = path;
  recording.container = contents.container;
  return recording;
}

const std::vector<const FormatReader*>& known_formats() {
  // MAT before HDF5: a MAT v7.3 file is an HDF5 file behind a "MATLAB 7.3 MAT-file" header.
  static const std::vector<const FormatReader*> formats = {
      &sound_format(), &tdms_format(), &uff_format(), &mat_format(), &hdf5_format(), &csv_format()};
  return formats;
}

const FormatReader& format_for_file(const std::string& path) {
  check_data_file(path);
  std::string head(512, '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  for (const FormatReader* format : known_formats()) {
    if (format->matches_signature(head)) return *format;
  }
  const std::string extension = lower_extension(path);
  for (const FormatReader* format : known_formats()) {
    if (format->matches_extension(extension)) return *format;
  }
  std::string names;
  for (const FormatReader* format : known_formats()) {
    names += (names.empty() ? "" : ", ") + std::string(format->format_name());
  }
  throw InputError(path + ": not a format Oscilab reads (it reads " + names + ")");
}

}  // namespace oscilab::daq
