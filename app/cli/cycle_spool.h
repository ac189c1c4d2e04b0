#pragma once

#include <cstddef>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "analysis/edc/cycle_fit.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::cli {

/// The cycle table of `analyze --cycles` (analysis::cycle_table_columns) written while the
/// analysis fits the cycles, so that none is kept: a day-long record fits about 800 000 of them,
/// some 220 MB held as fits. Each record's rows go to a spool file of their own beside the
/// target (records are analysed in parallel), without the record column; write() puts the table
/// together in record then time order, each row led by its record's name, as the table of kept
/// cycles reads. Spools are removed when the object goes, whatever happened.
class CycleSpool {
 public:
  /// `target`: the --cycles path (spools are `target.recordN.tmp.PID.K`).
  explicit CycleSpool(std::string target);
  CycleSpool(const CycleSpool&) = delete;
  CycleSpool& operator=(const CycleSpool&) = delete;
  ~CycleSpool();

  /// For analysis::OfflineRetention::each_cycle: appends the cycle's row to record `record`'s
  /// spool. Calls for one record come from one thread at a time; different records' from any.
  /// Never throws: a failed write is kept and thrown by write().
  void add(std::size_t record, const analysis::CycleFit& cycle) noexcept;

  /// Writes the table to `path`, the records named by `record_names` (by index; a record without
  /// a cycle gives no row). Throws InputError naming the target when a spool could not be written
  /// or read, or `path` cannot be written.
  void write(const std::vector<std::string>& record_names, const std::string& path) const;

 private:
  struct Spool {
    std::unique_ptr<daq::TemporaryFile> file;
    std::FILE* stream = nullptr;
  };
  Spool* spool_of(std::size_t record);

  std::string target_;
  mutable std::mutex mutex_;  // guards spools_ and failure_
  std::map<std::size_t, Spool> spools_;
  std::string failure_;  // the first failed write, as an error message
};

}  // namespace oscilab::cli
