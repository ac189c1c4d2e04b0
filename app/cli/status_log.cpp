#include "app/cli/status_log.h"

#include <cerrno>
#include <cstring>

#include "analysis/common/input_error.h"

namespace oscilab::cli {

StatusLog::StatusLog(const std::string& path, double every_s) : path_(path), every_s_(every_s) {
  if (path.empty()) return;
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) {
    throw InputError("--status-log: " + path + ": cannot write: " + std::strerror(errno));
  }
  std::fprintf(file_,
               "wall_s,stream_s,samples,gaps,gap_samples,duplicates,reordered,late,nan_samples,"
               "saturated_samples,overflowed_blocks,queue_fill,queue_capacity,cycles,"
               "excluded_cycles,levels,edc_latency_s,edc_latency_median_s,edc_latency_max_s\n");
  check();
  throw_if_failed();
}

StatusLog::~StatusLog() {
  if (file_) std::fclose(file_);
}

void StatusLog::maybe_write(double wall_s, const daq::AcquisitionStatus& s, bool last) {
  if (!file_ || (!last && wall_s < next_s_)) return;
  next_s_ = wall_s + every_s_;
  using Count = unsigned long long;
  std::fprintf(file_, "%.3f,%.6f,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%zu,%zu,%ld,%ld,%zu,",
               wall_s, s.stream_time_s, Count{s.samples}, Count{s.gaps}, Count{s.gap_samples},
               Count{s.duplicates}, Count{s.reordered}, Count{s.late}, Count{s.non_finite_samples},
               Count{s.saturated_samples}, Count{s.overflowed_blocks}, s.queue_fill,
               s.queue_capacity, s.cycles, s.excluded_cycles, s.levels);
  std::fprintf(file_, "%.6f,%.6f,%.6f\n", s.edc_latency_s, s.edc_latency_median_s,
               s.edc_latency_max_s);
  std::fflush(file_);
  check();
}

void StatusLog::discard() {
  if (!file_) return;
  std::fclose(file_);
  file_ = nullptr;
  std::remove(path_.c_str());
}

void StatusLog::throw_if_failed() const {
  if (!failure_.empty()) throw InputError(failure_);
}

void StatusLog::check() {
  if (std::ferror(file_)) {
    failure_ = "--status-log: " + path_ + ": write failed: " + std::strerror(errno);
    std::fclose(file_);
    file_ = nullptr;
  }
}

}  // namespace oscilab::cli
