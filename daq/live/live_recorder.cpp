#include "daq/live/live_recorder.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "analysis/common/input_error.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::daq {
namespace {

int live_format_for(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".wav") return SF_FORMAT_WAV | SF_FORMAT_DOUBLE;
  if (extension == ".w64") return SF_FORMAT_W64 | SF_FORMAT_DOUBLE;
  if (extension == ".rf64") return SF_FORMAT_RF64 | SF_FORMAT_DOUBLE;
  throw InputError(path +
                   ": a live recording is written as .wav, .w64 or .rf64 (float64, its "
                   "header kept current, so a crash leaves a readable file); got \"" +
                   extension + "\"");
}

constexpr std::size_t kGapChunkRows = 4096;

}  // namespace

LiveRecorder::LiveRecorder(const std::string& path, const Sidecar& layout,
                           std::uint64_t first_sample, std::chrono::milliseconds sync_interval)
    : path_(path),
      sidecar_path_(sidecar_path_for(path)),
      sidecar_(layout),
      first_sample_(first_sample),
      rate_hz_(layout.sample_rate_hz),
      channels_(static_cast<int>(layout.channels.size())),
      sync_interval_(sync_interval) {
  const int format = live_format_for(path);
  events_path_ =
      (std::filesystem::path(path).parent_path() / std::filesystem::path(path).stem()).string() +
      ".events.jsonl";
  sidecar_.csv.reset();
  for (ChannelInfo& channel : sidecar_.channels) channel.column = -1;
  sidecar_.invalid_intervals.clear();
  if (sidecar_.excitation) sidecar_.excitation->levels.clear();
  sidecar_.extra["recorded_live"] = {{"started", utc_now_iso8601()},
                                     {"stream_first_sample", first_sample}};

  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(rate_hz_));
  info.channels = channels_;
  info.format = format;
  if (info.samplerate < 1 || sf_format_check(&info) == SF_FALSE) {
    throw InputError(path + ": cannot record " + std::to_string(channels_) + " channels at " +
                     std::to_string(rate_hz_) + " Hz in this container");
  }
  // Opened here, so that its descriptor can be synced; libsndfile closes it.
  file_fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (file_fd_ < 0) throw InputError(path + ": cannot write: " + std::strerror(errno));
  file_ = sf_open_fd(file_fd_, SFM_WRITE, &info, SF_TRUE);
  if (file_ == nullptr) {
    // Its header could not be written (a full disk): no empty file is left behind.
    const std::string why = sf_strerror(nullptr);
    ::close(file_fd_);
    ::unlink(path.c_str());
    throw InputError(path + ": cannot write: " + why);
  }
  last_sync_ = std::chrono::steady_clock::now();
  sf_command(file_, SFC_SET_UPDATE_HEADER_AUTO, nullptr, SF_TRUE);
  // No destructor runs when a constructor throws: what is open is closed before rethrowing.
  bool sidecar_written = false;
  try {
    write_sidecar_now(true);  // validates it too (InputError on a bad layout)
    sidecar_written = true;
    events_fd_ =
        ::open(events_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC, 0644);
    if (events_fd_ < 0) throw InputError(events_path_ + ": cannot write: " + std::strerror(errno));
    // Levels the stream's sidecar gave up front (stream time) move to recording time.
    if (layout.excitation) {
      const double freq = layout.excitation->frequency_hz.value_or(0.0);
      for (const ExcitationLevel& level : layout.excitation->levels) {
        add_level(level.f0_n, freq, level.start_s, level.start_s, level.end_s);
      }
      if (sidecar_dirty_) write_sidecar_now();
    }
  } catch (...) {
    // A refused recording leaves none of its files behind.
    if (events_fd_ >= 0) {
      ::close(events_fd_);
      ::unlink(events_path_.c_str());
    }
    sf_close(file_);
    file_ = nullptr;
    ::unlink(path_.c_str());
    if (sidecar_written) ::unlink(sidecar_path_.c_str());
    throw;
  }
  nan_rows_.assign(kGapChunkRows * static_cast<std::size_t>(channels_),
                   std::numeric_limits<double>::quiet_NaN());
}

void LiveRecorder::check_path(const std::string& path) { live_format_for(path); }

LiveRecorder::~LiveRecorder() {
  try {
    close();
  } catch (...) {  // a destructor must not throw; close() already kept the error
  }
}

double LiveRecorder::recording_time_s(std::uint64_t stream_sample) const {
  return (static_cast<double>(stream_sample) - static_cast<double>(first_sample_)) / rate_hz_;
}

bool LiveRecorder::write(const RawBlock& block) {
  // After a failed write nothing more is appended: the file ends at the last whole sample.
  if (file_ == nullptr || write_failed_) return false;
  const auto rows = static_cast<sf_count_t>(block.rows);
  if (sf_writef_double(file_, block.values.data(), rows) != rows) {
    fail_write();
    return false;
  }
  samples_written_ += static_cast<std::uint64_t>(block.rows);
  maybe_sync(false);
  return true;
}

void LiveRecorder::maybe_sync(bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_sync_ < sync_interval_) return;
  last_sync_ = now;
  // The header is current (SFC_SET_UPDATE_HEADER_AUTO); fdatasync makes samples and header
  // durable together with what the file's size needs.
  if (file_fd_ >= 0 && ::fdatasync(file_fd_) != 0 && error_.empty()) {
    error_ = path_ + ": cannot sync to disk: " + std::strerror(errno);
  }
  if (events_fd_ >= 0) ::fdatasync(events_fd_);
  syncs_ += 1;
}

bool LiveRecorder::write_gap(std::uint64_t samples) {
  if (file_ == nullptr || write_failed_) return false;
  if (samples == 0) return true;
  const std::uint64_t from = first_sample_ + samples_written_;
  mark_invalid(from, from + samples - 1, "gap");
  std::uint64_t left = samples;
  while (left > 0) {
    const auto rows = static_cast<sf_count_t>(std::min<std::uint64_t>(left, kGapChunkRows));
    if (sf_writef_double(file_, nan_rows_.data(), rows) != rows) {
      fail_write();
      return false;
    }
    left -= static_cast<std::uint64_t>(rows);
    samples_written_ += static_cast<std::uint64_t>(rows);
  }
  maybe_sync(false);
  return true;
}

void LiveRecorder::mark_invalid(std::uint64_t from_sample, std::uint64_t to_sample,
                                const std::string& reason) {
  if (to_sample < from_sample) std::swap(from_sample, to_sample);  // an interval either way round
  if (to_sample < first_sample_) return;
  from_sample = std::max(from_sample, first_sample_);
  InvalidInterval interval{recording_time_s(from_sample), recording_time_s(to_sample), reason};
  auto& intervals = sidecar_.invalid_intervals;
  // Consecutive samples of one kind extend the last interval rather than add one per block.
  if (!intervals.empty() && intervals.back().reason == reason &&
      interval.start_s <= intervals.back().end_s + 1.5 / rate_hz_) {
    intervals.back().end_s = std::max(intervals.back().end_s, interval.end_s);
  } else {
    intervals.push_back(interval);
    std::sort(
        intervals.begin(), intervals.end(),
        [](const InvalidInterval& a, const InvalidInterval& b) { return a.start_s < b.start_s; });
  }
  sidecar_dirty_ = true;
}

void LiveRecorder::add_level(double f0_n, double frequency_hz, double change_s,
                             double steady_from_s, double steady_to_s) {
  auto& excitation = sidecar_.excitation;
  if (!excitation) excitation = Excitation{"stepped-sine", frequency_hz, {}, {}};
  if (!excitation->frequency_hz) excitation->frequency_hz = frequency_hz;
  auto& levels = excitation->levels;
  const double t0_s = first_time_s();
  if (level_open_ && !levels.empty()) {
    levels.back().end_s = std::max(change_s - t0_s, levels.back().start_s);
    if (!(levels.back().end_s > levels.back().start_s)) levels.pop_back();  // never steady
  }
  level_open_ = false;
  if (!(f0_n > 0)) return;  // the table at rest: no level
  ExcitationLevel level;
  level.f0_n = f0_n;
  level.start_s = std::max(steady_from_s - t0_s, 0.0);
  level.end_s = steady_to_s - t0_s;  // +∞ while open: written as "so far"
  level.extra["frequency_hz"] = frequency_hz;
  if (!(level.end_s > level.start_s)) return;  // ended before the recording began
  levels.push_back(level);
  level_open_ = !std::isfinite(level.end_s);
  sidecar_dirty_ = true;
}

void LiveRecorder::log(const StreamEvent& event) {
  if (events_fd_ < 0) return;
  StreamEvent local = event;
  if (std::isfinite(local.t_s)) {
    local.t_s -= first_time_s();
  }
  const std::string line =
      local.to_json().dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  // One write(2) per line: a crash leaves whole lines (O_APPEND, a few hundred bytes).
  if (::write(events_fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
    error_ = events_path_ + ": write failed: " + std::strerror(errno);
  }
}

void LiveRecorder::maybe_write_sidecar() {
  if (!sidecar_dirty_ && !level_open_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_sidecar_write_ < std::chrono::seconds(1)) return;
  write_sidecar_now();
}

void LiveRecorder::write_sidecar_now(bool throw_errors) {
  Sidecar out = sidecar_;
  const double recorded_s = static_cast<double>(samples_written_) / rate_hz_;
  if (out.excitation) {
    auto& levels = out.excitation->levels;
    // The open level ends where the recording ends so far; one not yet steady is left out.
    if (!levels.empty() && !std::isfinite(levels.back().end_s)) {
      levels.back().end_s = recorded_s;
      if (!(levels.back().end_s > levels.back().start_s)) levels.pop_back();
    }
  }
  // A full disk refuses the sidecar too: the previous one stays (it is replaced atomically), the
  // error is kept, and nothing is thrown on the acquisition's thread.
  try {
    write_sidecar(out, sidecar_path_);
  } catch (const InputError& error) {
    if (throw_errors) throw;
    if (error_.empty()) error_ = error.what();
  }
  sidecar_dirty_ = false;
  last_sidecar_write_ = std::chrono::steady_clock::now();
}

void LiveRecorder::fail_write() {
  if (error_.empty()) error_ = path_ + ": write failed: " + sf_strerror(file_);
  write_failed_ = true;
}

void LiveRecorder::truncate_to_written() {
  // libsndfile may have put part of the failed block on the disk and updated the header for it:
  // the file is cut in place to the samples written whole and its header rewritten to match
  // (SFC_FILE_TRUNCATE needs no free space), so that it opens with exactly those.
  SF_INFO info{};
  SNDFILE* file = sf_open(path_.c_str(), SFM_RDWR, &info);
  if (file == nullptr) return;  // the error already says the recording failed
  sf_count_t frames = static_cast<sf_count_t>(samples_written_);
  sf_command(file, SFC_FILE_TRUNCATE, &frames, sizeof frames);
  sf_close(file);
}

void LiveRecorder::close() {
  if (file_ == nullptr) return;
  maybe_sync(true);
  const int closed = sf_close(file_);
  file_fd_ = -1;
  file_ = nullptr;
  if (closed != 0 && error_.empty()) error_ = path_ + ": close failed: " + sf_error_number(closed);
  if (write_failed_ || closed != 0) truncate_to_written();
  if (events_fd_ >= 0) ::close(events_fd_);
  events_fd_ = -1;
  write_sidecar_now();
}

std::int64_t recover_live_recording(const std::string& path) {
  SF_INFO info{};
  SNDFILE* in = sf_open(path.c_str(), SFM_READ, &info);
  if (in == nullptr) {
    throw InputError(path + ": cannot recover: not even its header can be read (" +
                     sf_strerror(nullptr) + ")");
  }
  // Every whole frame the file holds (libsndfile stops at the end of the data it finds).
  std::vector<double> samples;
  std::vector<double> chunk(static_cast<std::size_t>(4096 * info.channels));
  sf_count_t frames = 0;
  for (;;) {
    const sf_count_t got = sf_readf_double(in, chunk.data(), 4096);
    if (got <= 0) break;
    samples.insert(samples.end(), chunk.begin(), chunk.begin() + got * info.channels);
    frames += got;
  }
  sf_close(in);
  if (frames == 0) throw InputError(path + ": cannot recover: no whole sample before the cut");
  TemporaryFile out_file(path);
  SF_INFO out_info{};
  out_info.samplerate = info.samplerate;
  out_info.channels = info.channels;
  out_info.format = info.format;
  SNDFILE* out = sf_open(out_file.path().c_str(), SFM_WRITE, &out_info);
  if (out == nullptr) throw InputError(path + ": cannot recover: " + sf_strerror(nullptr));
  const bool written = sf_writef_double(out, samples.data(), frames) == frames;
  if (sf_close(out) != 0 || !written) throw InputError(path + ": cannot recover: write failed");
  out_file.commit();
  // The sidecar: levels and invalid intervals no later than what is left.
  const std::string sidecar_path = sidecar_path_for(path);
  if (std::filesystem::exists(sidecar_path)) {
    Sidecar sidecar = read_sidecar(sidecar_path);
    const double end_s = static_cast<double>(frames) / sidecar.sample_rate_hz;
    if (sidecar.excitation) {
      auto& levels = sidecar.excitation->levels;
      levels.erase(std::remove_if(levels.begin(), levels.end(),
                                  [&](const ExcitationLevel& l) { return l.start_s >= end_s; }),
                   levels.end());
      for (ExcitationLevel& level : levels) level.end_s = std::min(level.end_s, end_s);
    }
    auto& intervals = sidecar.invalid_intervals;
    intervals.erase(std::remove_if(intervals.begin(), intervals.end(),
                                   [&](const InvalidInterval& i) { return i.start_s > end_s; }),
                    intervals.end());
    for (InvalidInterval& interval : intervals) interval.end_s = std::min(interval.end_s, end_s);
    sidecar.extra["recovered"] = {{"samples", frames}, {"at", utc_now_iso8601()}};
    write_sidecar(sidecar, sidecar_path);
  }
  return frames;
}

}  // namespace oscilab::daq
