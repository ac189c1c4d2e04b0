#include "daq/recording/recording_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace oscilab::daq {
namespace {

// Six significant digits: enough to recognise a value, short enough to read.
std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

std::string line(const std::string& label, const std::string& value) {
  std::string text = "  " + label + ":";
  text.resize(std::max<std::size_t>(text.size() + 1, 16), ' ');
  return text + value + "\n";
}

std::string describe_excitation(const Sidecar& sidecar) {
  if (!sidecar.excitation) return "Excitation: none (the analysis will detect it)\n";
  const Excitation& excitation = *sidecar.excitation;
  std::string text = "Excitation:\n";
  text += line("type", excitation.type.empty() ? "not given" : excitation.type);
  text += line("frequency", excitation.frequency_hz
                                ? number(*excitation.frequency_hz) + " Hz"
                                : std::string("not given (the analysis will detect it)"));
  const auto& levels = excitation.levels;
  if (levels.empty()) {
    text += line("levels", "not given (the analysis will detect them)");
    return text;
  }
  const auto [low, high] = std::minmax_element(
      levels.begin(), levels.end(),
      [](const ExcitationLevel& a, const ExcitationLevel& b) { return a.f0_n < b.f0_n; });
  text += line("levels", std::to_string(levels.size()) + ", f0 from " + number(low->f0_n) +
                             " N to " + number(high->f0_n) + " N");
  for (std::size_t i = 0; i < levels.size(); ++i) {
    text += "    level " + std::to_string(i + 1) + ": f0 = " + number(levels[i].f0_n) + " N, " +
            number(levels[i].start_s) + " s to " + number(levels[i].end_s) + " s\n";
  }
  return text;
}

// Properties as `key: value` lines, long values cut, at most `limit` of them.
std::string property_lines(const nlohmann::json& properties, const std::string& indent,
                           std::size_t limit) {
  std::string text;
  std::size_t count = 0;
  for (const auto& [key, value] : properties.items()) {
    if (count++ == limit) {
      text += indent + "... (" + std::to_string(properties.size() - limit) + " more)\n";
      break;
    }
    std::string shown = value.is_string() ? value.get<std::string>() : value.dump();
    if (shown.size() > 100) shown = shown.substr(0, 97) + "...";
    text += indent + key + ": " + shown + "\n";
  }
  return text;
}

}  // namespace

std::string describe_file_contents(const std::string& path, const FileContents& contents) {
  std::string text = "File: " + path + "\n";
  text += line("container", contents.container);
  if (!contents.properties.empty()) {
    text += "  properties:\n" + property_lines(contents.properties, "    ", 40);
  }
  text += "Signals (" + std::to_string(contents.file_signals.size()) +
          (contents.picked_by_source ? "; a sidecar's channels[].source names them):\n"
                                     : "; a sidecar's channels map them in order or by name):\n");
  for (const FileSignal& signal : contents.file_signals) {
    text += "  " + signal.name + ": " + std::to_string(signal.sample_count) + " samples";
    if (signal.columns > 1) text += " x " + std::to_string(signal.columns) + " columns";
    if (!signal.stored_type.empty()) text += ", " + signal.stored_type;
    text += ", unit " + (signal.unit.empty() ? std::string("not stated") : signal.unit);
    if (signal.sample_rate_hz) text += ", " + number(*signal.sample_rate_hz) + " Hz";
    text += "\n" + property_lines(signal.properties, "      ", 12);
  }
  return text;
}

std::string describe_recording(const Recording& recording) {
  const Sidecar& sidecar = recording.sidecar;
  std::string text =
      "Recording: " +
      (recording.source_path.empty() ? std::string("(in memory)") : recording.source_path) + "\n";
  text +=
      line("container", recording.container.empty() ? "not read from a file" : recording.container);
  text += line("sample rate", number(sidecar.sample_rate_hz) + " Hz");
  text += line("samples", std::to_string(recording.sample_count()));
  text += line("duration", number(recording.duration_s()) + " s");
  text += line("mass", sidecar.mass_kg ? number(*sidecar.mass_kg) + " kg" : "not given");
  if (!sidecar.notes.empty()) text += line("notes", sidecar.notes);

  text += "Channels (" + std::to_string(sidecar.channels.size()) + "):\n";
  const auto& samples = recording.samples_si;
  for (std::size_t c = 0; c < sidecar.channels.size(); ++c) {
    const ChannelInfo& channel = sidecar.channels[c];
    text += "  " + std::to_string(c + 1) + ". " + channel.name + ": role " +
            to_string(channel.role) + ", " + to_string(channel.quantity) + ", unit in file " +
            channel.unit + " (scale " + number(channel.scale) + ", offset " +
            number(channel.offset) + ")" +
            (channel.sensor.empty() ? "" : ", sensor " + channel.sensor) + "\n";
    const auto column = static_cast<Eigen::Index>(c);
    if (samples.rows() == 0 || column >= samples.cols()) {
      text += "     no samples\n";
      continue;
    }
    const std::string unit = si_unit(channel.quantity);
    const double rms =
        std::sqrt(samples.col(column).squaredNorm() / static_cast<double>(samples.rows()));
    text += "     min " + number(samples.col(column).minCoeff()) + ' ' + unit;
    text += ", max " + number(samples.col(column).maxCoeff()) + ' ' + unit;
    text += ", rms " + number(rms) + ' ' + unit + '\n';
  }
  text += describe_excitation(sidecar);
  return text;
}

}  // namespace oscilab::daq
