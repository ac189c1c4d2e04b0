#pragma once

#include <string>

#include <Eigen/Core>

#include "daq/recording/sidecar.h"

namespace oscilab::daq {

/// A recording in memory: its sidecar and its samples in physical SI units (calibration and unit
/// conversion applied), one column per sidecar channel, one row per sample.
struct Recording {
  Sidecar sidecar;
  Eigen::MatrixXd samples_si;  // rows: samples at sidecar.sample_rate_hz; cols: channels
  /// The values exactly as the file stores them (before calibration), same shape; filled by the
  /// readers (replay and streaming send these, so a re-recording is bit-exact), empty otherwise.
  Eigen::MatrixXd samples_stored;
  std::string source_path;  // where it was read from (empty when made in memory)
  std::string container;    // e.g. "WAV (Microsoft), 64 bit float" or "CSV"; set by the reader

  Eigen::Index sample_count() const { return samples_si.rows(); }
  double duration_s() const;
  /// Index of the first channel with `role`, or -1.
  int channel_index(ChannelRole role) const;
  /// Index of the channel named `name`, or -1.
  int channel_index(const std::string& name) const;
};

/// Reads a recording: a libsndfile container (WAV, FLAC, W64, RF64, AIFF, CAF, ...) or a CSV, with
/// its JSON sidecar of the same stem. Every problem (missing or malformed sidecar, unknown unit or
/// role, channel count or rate mismatch, truncated or empty data, NaN/Inf, non-monotonic CSV
/// time, ...) throws one oscilab::InputError naming the file and the problem.
///
/// Sound containers store an integer sample rate: the sidecar's rate (which may be fractional, a
/// measured clock) must round to it. CSV files may carry a time column (`t_s` in the header, or
/// the sidecar's csv.time_column): it must increase strictly and stay within half a sample of
/// t0 + i / sample_rate_hz.
Recording read_recording(const std::string& path);

class FormatReader;
/// A recording's file before its samples are read: what read_recording checks first (a regular
/// file, not a .json, a format Oscilab reads, a sidecar beside it) and the sidecar, parsed.
struct RecordingFile {
  const FormatReader* format = nullptr;
  std::string sidecar_path;
  Sidecar sidecar;
};
RecordingFile open_recording_file(const std::string& path);

/// Reads the samples of `path` with a sidecar given in memory instead of the file beside it (for
/// a CSV whose channels the command line describes). The sidecar is validated first.
Recording read_recording(const std::string& path, const Sidecar& sidecar);

/// Writes samples and sidecar; the container follows the extension (.wav, .flac, .w64, .rf64,
/// .aiff, .caf, .csv). Stored value = (SI value / unit factor − offset) / scale, so a round trip
/// returns the same SI samples (to floating-point rounding of that calibration for float64
/// containers and CSV at full precision; to half the channel's scale for integer containers such
/// as FLAC, 24-bit). Throws InputError when the file cannot be written or the data cannot be
/// represented. Both files are written beside their targets under temporary names and renamed
/// into place, so a failure leaves no half-written recording.
void write_recording(const Recording& recording, const std::string& path);

}  // namespace oscilab::daq
