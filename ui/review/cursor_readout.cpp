#include "ui/review/cursor_readout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "analysis/common/input_error.h"

namespace oscilab::ui {

CursorReadout read_cursor(const daq::OpenedRecording& recording, double t_s) {
  CursorReadout readout;
  const double rate_hz = recording.sidecar.sample_rate_hz;
  const Eigen::Index count = recording.sample_count();
  if (count == 0 || !(rate_hz > 0.0) || !std::isfinite(t_s)) return readout;
  const double nearest = std::round(t_s * rate_hz);
  const auto sample = static_cast<Eigen::Index>(std::clamp(nearest, 0.0, double(count - 1)));
  Eigen::MatrixXd row;
  try {
    row = recording.samples->read(sample, 1);
  } catch (const InputError&) {  // the file went away or changed since it was opened
    return readout;
  }
  if (row.rows() != 1) return readout;
  readout.sample = sample;
  readout.t_s = double(sample) / rate_hz;
  readout.values_si.reserve(std::size_t(row.cols()));
  for (Eigen::Index c = 0; c < row.cols(); ++c) readout.values_si.push_back(row(0, c));
  return readout;
}

std::string format_readout(const CursorReadout& readout, const daq::OpenedRecording& recording,
                           const std::vector<DisplayUnit>& units) {
  if (readout.sample < 0) return "";
  // Decimals of t: enough to tell neighbouring samples apart (3 at 512 Hz, 4 at 10 kHz).
  const double rate_hz = recording.sidecar.sample_rate_hz;
  const int decimals = std::clamp(int(std::ceil(std::log10(rate_hz))), 0, 9);
  std::array<char, 64> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "t = %.*f s", decimals, readout.t_s);
  std::string text = buffer.data();
  const auto& channels = recording.sidecar.channels;
  for (std::size_t c = 0; c < readout.values_si.size() && c < channels.size(); ++c) {
    const DisplayUnit unit = c < units.size() ? units[c] : DisplayUnit{};
    // Right-aligned to the width of the channel's largest value (4 significant digits and a
    // sign), so that the line does not jitter while the cursor moves.
    const int width =
        1 + std::max(1, 4 - unit.decimals) + (unit.decimals > 0 ? 1 + unit.decimals : 0);
    const std::string value = format_value(readout.values_si[c], unit);
    const std::size_t number =
        value.find(' ') == std::string::npos ? value.size() : value.find(' ');
    const std::string pad(std::size_t(std::max(0, width - int(number))), ' ');
    text += "   " + channels[c].name + " = " + pad + value;
  }
  return text;
}

}  // namespace oscilab::ui
