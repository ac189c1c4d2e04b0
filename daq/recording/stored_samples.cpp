#include "daq/recording/stored_samples.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "analysis/common/input_error.h"
#include "analysis/signal/ac_coupling.h"

namespace oscilab::daq {
namespace fs = std::filesystem;

// Whether sample `row` lies inside one of the sidecar's invalid intervals (a live recording's gap
// or bad samples), where non-finite values are what was recorded and are allowed.
bool declared_invalid(const Sidecar& sidecar, Eigen::Index row) {
  const double t_s = static_cast<double>(row) / sidecar.sample_rate_hz;
  const double half_sample_s = 0.5 / sidecar.sample_rate_hz;
  for (const InvalidInterval& interval : sidecar.invalid_intervals) {
    if (t_s >= interval.start_s - half_sample_s && t_s <= interval.end_s + half_sample_s) {
      return true;
    }
  }
  return false;
}

std::string lower_extension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void check_data_file(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(path + ": file not found");
  if (!fs::is_regular_file(status)) throw InputError(path + ": cannot read: not a regular file");
}

// Where sample `row` sits, for messages: "sample 42 (t = 0.082 s, line 44)".
std::string sample_place(Eigen::Index row, double sample_rate_hz, const StoredSamples& stored) {
  std::string text = "sample " + std::to_string(row) +
                     " (t = " + number_text(static_cast<double>(row) / sample_rate_hz) + " s";
  if (!stored.lines.empty()) text += ", line " + std::to_string(stored.lines[row]);
  return text + ")";
}

// physical = scale × stored + offset in the channel's unit, then × unit factor → SI.
// Non-finite samples are an error unless the sidecar declares them invalid.
Eigen::MatrixXd calibrate(const StoredSamples& stored, const Sidecar& sidecar,
                          const std::string& path) {
  const auto channels = static_cast<Eigen::Index>(sidecar.channels.size());
  const Eigen::Index rows = static_cast<Eigen::Index>(stored.values.size()) / channels;
  Eigen::MatrixXd samples(rows, channels);
  for (Eigen::Index c = 0; c < channels; ++c) {
    const ChannelInfo& channel = sidecar.channels[c];
    const double factor = unit_to_si(channel.unit, channel.quantity, path);
    Eigen::Index first_bad = -1;
    Eigen::Index bad_count = 0;
    for (Eigen::Index r = 0; r < rows; ++r) {
      const double value = stored.values[r * channels + c];
      const double si = (channel.scale * value + channel.offset) * factor;
      samples(r, c) = si;
      if (!std::isfinite(si) && !declared_invalid(sidecar, r)) {
        if (first_bad < 0) first_bad = r;
        ++bad_count;
      }
    }
    if (first_bad < 0) {
      if (channel.ac_coupling_hz) {  // the input's high-pass undone, as the live chain does
        analysis::AcCouplingInverse inverse(*channel.ac_coupling_hz, sidecar.sample_rate_hz,
                                            path + ": channel " + in_quotes(channel.name));
        for (Eigen::Index r = 0; r < rows; ++r) samples(r, c) = inverse.push(samples(r, c));
      }
      continue;
    }
    const double value = stored.values[first_bad * channels + c];
    std::string problem = std::isnan(value) ? "is NaN"
                          : std::isinf(value)
                              ? "is infinite"
                              : "(" + number_text(value) + ") overflows after calibration (scale " +
                                    number_text(channel.scale) + ")";
    throw InputError(path + ": channel " + in_quotes(channel.name) + ": " +
                     sample_place(first_bad, sidecar.sample_rate_hz, stored) + " " + problem +
                     "; " + std::to_string(bad_count) + " of " + std::to_string(rows) +
                     " samples of this channel are not finite");
  }
  return samples;
}

// The interleaved stored values as a matrix: one row per sample, one column per channel.
Eigen::MatrixXd as_matrix(const StoredSamples& stored, Eigen::Index channels) {
  const Eigen::Index rows = static_cast<Eigen::Index>(stored.values.size()) / channels;
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      stored.values.data(), rows, channels);
}

std::string TimeAxisCheck::next(double t_s) {
  std::string problem;
  if (!std::isfinite(t_s)) {
    problem = "the time is not finite";
  } else {
    if (row_ == 0) t0_s_ = t_s;
    const double expected_t_s = t0_s_ + static_cast<double>(row_) / rate_hz_;
    if (row_ > 0 && !(t_s > previous_t_s_)) {
      problem = "time " + number_text(t_s) + " s does not increase (previous " +
                number_text(previous_t_s_) + " s)";
    } else if (std::abs(t_s - expected_t_s) > 0.5 / rate_hz_) {
      problem = "time " + number_text(t_s) + " s does not fit " + sidecar_name_ +
                "'s sample_rate_hz " + number_text(rate_hz_) + " (sample " + std::to_string(row_) +
                " should be at " + number_text(expected_t_s) + " s)";
    }
  }
  previous_t_s_ = t_s;
  ++row_;
  return problem;
}

}  // namespace oscilab::daq
