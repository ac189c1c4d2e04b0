#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <sndfile.h>

#include "daq/recording/sidecar.h"
#include "daq/sources/raw_block.h"
#include "daq/sources/stream_event.h"

namespace oscilab::daq {

/// Records a live stream losslessly and crash-safely, as it arrives:
/// - the samples exactly as delivered (stored values, float64) into a WAV, W64 or RF64 file
///   whose header libsndfile rewrites after every write (SFC_SET_UPDATE_HEADER_AUTO), so that at
///   any instant the file on disk is a complete, readable recording of everything written;
///   missing samples (gaps) are written as NaN rows and declared in the sidecar's
///   invalid_intervals, so the file keeps the stream's clock;
/// - the sidecar (`<stem>.json`, calibration, excitation as operated, invalid intervals),
///   replaced atomically (write + rename) when it changes, at most once a second, and at close;
/// - the event log (`<stem>.events.jsonl`), one JSON object per line, each appended with one
///   write(2) as it happens.
/// A SIGKILL loses at most the block being written and the last second of sidecar changes:
/// the test kills a recording process and reads what it left.
///
/// Durability (a power cut, not just a crash): the samples and the event log are handed to the
/// disk (fdatasync) at most every `sync_interval` on the writer's thread, once a second by
/// default, and at close; the sidecar is rewritten at most once a second. A power cut loses at
/// most the last interval; a file cut anywhere in its samples is repaired by
/// recover_live_recording, which keeps every whole sample before the cut.
///
/// Times are recording time: stream time − the stream time of the first sample recorded.
/// Not thread-safe: the acquisition thread owns it.
class LiveRecorder {
 public:
  /// Opens the files (throws InputError naming the path: unknown container, cannot write).
  /// `layout` says what the samples mean; `first_sample` is the stream sample recorded first.
  /// `sync_interval`: how often at most the data goes to the disk (fdatasync); 0: every write.
  LiveRecorder(const std::string& path, const Sidecar& layout, std::uint64_t first_sample,
               std::chrono::milliseconds sync_interval = kDefaultSyncInterval);
  static constexpr std::chrono::milliseconds kDefaultSyncInterval{1000};
  ~LiveRecorder();
  /// Throws InputError unless `path` names a container a live recording can be (see above).
  static void check_path(const std::string& path);
  LiveRecorder(const LiveRecorder&) = delete;
  LiveRecorder& operator=(const LiveRecorder&) = delete;

  /// Appends a block's rows (stored values). False when the disk refused (the error is kept);
  /// from then on nothing is appended, and close() cuts the file to the samples written whole,
  /// so that it opens with them.
  bool write(const RawBlock& block);
  /// Appends `samples` NaN rows for samples that never arrived, declared invalid ("gap").
  bool write_gap(std::uint64_t samples);
  /// Declares [from, to] (stream samples, inclusive; given either way round) invalid for `reason`.
  void mark_invalid(std::uint64_t from_sample, std::uint64_t to_sample, const std::string& reason);
  /// A level of the excitation as operated, in stream time: the excitation changed at change_s
  /// (which ends a previous level still open), and the level is steady over [steady_from_s,
  /// steady_to_s) (steady_to_s +∞: open until the next change).
  void add_level(double f0_n, double frequency_hz, double change_s, double steady_from_s,
                 double steady_to_s);
  /// Appends an event to the log (its t_s converted to recording time).
  void log(const StreamEvent& event);
  /// Rewrites the sidecar when it changed and a second has passed since the last rewrite.
  void maybe_write_sidecar();
  /// Final sidecar and close. Idempotent.
  void close();

  const std::string& path() const { return path_; }
  std::uint64_t samples_written() const { return samples_written_; }
  const std::string& error() const { return error_; }
  /// fdatasync calls so far (samples and event log each count once).
  std::uint64_t syncs() const { return syncs_; }

 private:
  /// Hands what was written to the disk when sync_interval has passed (or `force`).
  void maybe_sync(bool force);
  double recording_time_s(std::uint64_t stream_sample) const;
  double first_time_s() const { return static_cast<double>(first_sample_) / rate_hz_; }
  /// Rewrites the sidecar; a failure is kept in error() (thrown only when `throw_errors`: the
  /// constructor's first write, which validates the layout).
  void write_sidecar_now(bool throw_errors = false);
  /// Keeps the first write error and stops appending.
  void fail_write();
  /// Cuts the file to the samples written whole, its header to match (after a failed write).
  void truncate_to_written();

  std::string path_, sidecar_path_, events_path_;
  Sidecar sidecar_;
  std::uint64_t first_sample_;
  double rate_hz_;
  int channels_;
  SNDFILE* file_ = nullptr;
  int file_fd_ = -1;  // the samples' descriptor, owned by libsndfile (sf_open_fd, closed by it)
  int events_fd_ = -1;
  std::chrono::milliseconds sync_interval_;
  std::chrono::steady_clock::time_point last_sync_;
  std::uint64_t syncs_ = 0;
  std::uint64_t samples_written_ = 0;
  std::vector<double> nan_rows_;  // one block of NaN rows for gaps
  bool sidecar_dirty_ = false;
  std::chrono::steady_clock::time_point last_sidecar_write_;
  bool level_open_ = false;  // the last level in sidecar_ has no end yet
  std::string error_;
  bool write_failed_ = false;  // a write was refused (a full disk): nothing more is appended
};

/// Repairs a live recording cut anywhere (a power cut before the header was rewritten, a disk
/// that filled, a copy stopped short): every whole sample the file holds is kept, the header
/// made to match, and the sidecar's levels and invalid intervals clipped to what is left. The
/// file is replaced atomically (write beside it and rename). Returns the samples kept per
/// channel. Throws InputError naming the file when not even its header can be read.
std::int64_t recover_live_recording(const std::string& path);

}  // namespace oscilab::daq
