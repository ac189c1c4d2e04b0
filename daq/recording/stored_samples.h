#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "daq/recording/message_text.h"
#include "daq/recording/sidecar.h"

// What every file-format reader shares: samples as a file stores them, their calibration into SI
// with the sidecar, the check of a time axis against the sidecar's rate, and the wording of the
// readers' messages (message_text.h).
namespace oscilab::daq {

/// The file's extension in lower case, with its dot (".tdms"), or "".
std::string lower_extension(const std::string& path);
/// Throws InputError unless `path` is an existing regular file.
void check_data_file(const std::string& path);

/// Samples as stored in a file, interleaved: row r, channel c at values[r * channels + c].
struct StoredSamples {
  std::vector<double> values;
  std::vector<long> lines;  // text formats only: the file line of each row, for messages
};

/// Where sample `row` sits, for messages: "sample 42 (t = 0.082 s, line 44)".
std::string sample_place(Eigen::Index row, double sample_rate_hz, const StoredSamples& stored);

/// Whether sample `row` lies inside one of the sidecar's invalid intervals (a live recording's gap
/// or bad samples), where non-finite values are what was recorded and are allowed.
bool declared_invalid(const Sidecar& sidecar, Eigen::Index row);

/// physical = scale × stored + offset in each channel's unit, then × unit factor → SI. Non-finite
/// samples are an error (naming `path`, the channel and the first bad sample) unless the sidecar
/// declares them invalid.
Eigen::MatrixXd calibrate(const StoredSamples& stored, const Sidecar& sidecar,
                          const std::string& path);

/// The interleaved stored values as a matrix: one row per sample, one column per channel.
Eigen::MatrixXd as_matrix(const StoredSamples& stored, Eigen::Index channels);

/// Checks a file's time axis, one sample after the other, against the sidecar's rate: strictly
/// increasing and within half a sample of t0 + i / rate. Half a sample: a skipped or repeated
/// sample, or a rate that differs from the sidecar's by more than 1/(2 n) after n samples, shows;
/// timestamp rounding below that does not.
class TimeAxisCheck {
 public:
  TimeAxisCheck(double sample_rate_hz, std::string sidecar_name)
      : rate_hz_(sample_rate_hz), sidecar_name_(std::move(sidecar_name)) {}
  /// The problem with the time of the next sample, or "" when it fits.
  std::string next(double t_s);

 private:
  double rate_hz_;
  std::string sidecar_name_;
  long row_ = 0;
  double t0_s_ = 0.0;
  double previous_t_s_ = 0.0;
};

}  // namespace oscilab::daq
