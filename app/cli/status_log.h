#pragma once

#include <cstdio>
#include <string>

#include "daq/live/acquisition.h"

namespace oscilab::cli {

/// The status log of `record --status-log`: one CSV row per `every_s` seconds of wall time,
/// written and flushed as the run goes (a log to watch or plot, like the event log: not
/// all-or-nothing). What a day-long unattended run needs afterwards: did the stream stay whole,
/// the queue below its capacity, the live EDC on time, from the first hour to the last. Columns:
/// docs/contracts.md, "Status log".
class StatusLog {
 public:
  /// Opens `path` and writes the header (nothing when `path` is empty); throws InputError
  /// naming --status-log when it cannot.
  StatusLog(const std::string& path, double every_s);
  StatusLog(const StatusLog&) = delete;
  StatusLog& operator=(const StatusLog&) = delete;
  ~StatusLog();

  /// A row when `every_s` has passed since the last one (always when `last`).
  void maybe_write(double wall_s, const daq::AcquisitionStatus& status, bool last = false);
  /// Closes and removes the log (nothing was recorded).
  void discard();
  /// A write that failed during the run stopped the log there; it is said (InputError) once the
  /// recording is closed: the recording matters more than its log.
  void throw_if_failed() const;

 private:
  void check();

  std::string path_;
  double every_s_;
  double next_s_ = 0.0;
  std::FILE* file_ = nullptr;
  std::string failure_;
};

}  // namespace oscilab::cli
