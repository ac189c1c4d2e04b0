#include "daq/sources/replay_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

void check(const ReplaySource::Options& options, const Recording& recording) {
  if (!(options.speed >= 0) || !std::isfinite(options.speed)) {
    throw InputError("replay: speed " + std::to_string(options.speed) +
                     " must be >= 0 (0: as fast as possible)");
  }
  if (options.block_rows < 1 || options.block_rows > 65536) {
    throw InputError("replay: block size " + std::to_string(options.block_rows) +
                     " samples must be within 1..65536");
  }
  if (recording.samples_stored.rows() != recording.samples_si.rows() ||
      recording.samples_stored.rows() == 0) {
    throw InputError("replay: " + recording.source_path + ": no stored samples to play");
  }
}

}  // namespace

ReplaySource::ReplaySource(const std::string& path, Options options)
    : ReplaySource(read_recording(path), options) {}

ReplaySource::ReplaySource(Recording recording, Options options)
    : recording_(std::move(recording)), options_(options), speed_(options.speed) {
  check(options_, recording_);
  Sidecar sidecar = recording_.sidecar;
  // Levels and invalid intervals are in file time: they come again as events in stream time.
  if (sidecar.excitation && !sidecar.excitation->levels.empty()) {
    sidecar.excitation->levels.clear();
    sidecar.excitation->extra["levels_live"] = true;  // they come as `level` events
  }
  sidecar.invalid_intervals.clear();
  sidecar.extra["replayed_from"] =
      std::filesystem::path(recording_.source_path).filename().string();
  set_layout(sidecar);
}

ReplaySource::~ReplaySource() { stop(); }

void ReplaySource::seek(double t_s) {
  const double rate = recording_.sidecar.sample_rate_hz;
  const auto last = static_cast<long long>(recording_.sample_count()) - 1;
  const auto sample = static_cast<long long>(std::llround(std::max(0.0, t_s) * rate));
  seek_to_.store(std::min(sample, last), std::memory_order_release);
}

void ReplaySource::set_speed(double speed) {
  if (!(speed >= 0) || !std::isfinite(speed)) {
    throw InputError("replay: speed " + std::to_string(speed) + " must be >= 0");
  }
  speed_.store(speed, std::memory_order_release);
}

double ReplaySource::position_s() const {
  return static_cast<double>(position_.load(std::memory_order_acquire)) /
         recording_.sidecar.sample_rate_hz;
}

std::string ReplaySource::describe() const {
  return "replay " + std::filesystem::path(recording_.source_path).filename().string();
}

void ReplaySource::run() {
  const double rate_hz = recording_.sidecar.sample_rate_hz;
  const Eigen::Index n = recording_.sample_count();
  const auto channels = static_cast<int>(recording_.samples_stored.cols());
  const std::vector<ExcitationLevel> levels = recording_.sidecar.excitation
                                                  ? recording_.sidecar.excitation->levels
                                                  : std::vector<ExcitationLevel>{};
  // 0: the recording does not say (the acquisition keeps its own frequency then).
  const double frequency_hz = recording_.sidecar.excitation
                                  ? recording_.sidecar.excitation->frequency_hz.value_or(0.0)
                                  : 0.0;

  Eigen::Index file_sample = 0;
  std::uint64_t stream_sample = 0, sequence = 0;
  std::size_t next_level = 0, next_invalid = 0;
  // Stream time = file time + offset; the offset changes at every seek or loop.
  double offset_s = 0.0;
  auto pace_start = std::chrono::steady_clock::now();
  std::uint64_t pace_first = 0;
  double pace_speed = speed_.load();

  const auto jump_to = [&](Eigen::Index target, const char* why) {
    const double t_s = static_cast<double>(stream_sample) / rate_hz;
    post_event({t_s, EventKind::Discontinuity,
                std::string(why) + ": file time " +
                    std::to_string(static_cast<double>(file_sample) / rate_hz) + " s -> " +
                    std::to_string(static_cast<double>(target) / rate_hz) + " s"});
    file_sample = target;
    offset_s = t_s - static_cast<double>(target) / rate_hz;
    next_level = 0;
    while (next_level < levels.size() &&
           levels[next_level].start_s < static_cast<double>(target) / rate_hz) {
      ++next_level;
    }
    next_invalid = 0;
  };

  while (!stop_requested()) {
    if (const long long target = seek_to_.exchange(-1); target >= 0) jump_to(target, "seek");
    if (paused()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      pace_start = std::chrono::steady_clock::now();
      pace_first = stream_sample;
      continue;
    }
    if (file_sample >= n) {
      if (!options_.loop) break;
      jump_to(0, "loop");
    }
    // Events for what the stream reaches in this block, in stream time.
    const int rows = static_cast<int>(std::min<Eigen::Index>(options_.block_rows, n - file_sample));
    const double block_end_file_s = static_cast<double>(file_sample + rows) / rate_hz;
    while (next_level < levels.size() && levels[next_level].start_s < block_end_file_s) {
      const ExcitationLevel& level = levels[next_level++];
      nlohmann::json data = {{"f0_n", level.f0_n},
                             {"steady_from_s", level.start_s + offset_s},
                             {"steady_to_s", level.end_s + offset_s}};
      if (frequency_hz > 0) data["frequency_hz"] = frequency_hz;
      post_event({level.start_s + offset_s, EventKind::Level,
                  "f0 " + std::to_string(level.f0_n) + " N (from the recording)", data});
    }
    const auto& invalid = recording_.sidecar.invalid_intervals;
    while (next_invalid < invalid.size() && invalid[next_invalid].start_s < block_end_file_s) {
      const InvalidInterval& interval = invalid[next_invalid++];
      post_event({interval.start_s + offset_s,
                  EventKind::Invalid,
                  "the recording marks this stretch invalid (" + interval.reason + ")",
                  {{"from_s", interval.start_s + offset_s}, {"to_s", interval.end_s + offset_s}}});
    }

    const double speed = speed_.load(std::memory_order_acquire);
    if (speed != pace_speed) {  // a new speed paces from here
      pace_speed = speed;
      pace_start = std::chrono::steady_clock::now();
      pace_first = stream_sample;
    }
    if (speed > 0) {
      const double due_s =
          static_cast<double>(stream_sample + static_cast<std::uint64_t>(rows) - pace_first) /
          (rate_hz * speed);
      std::this_thread::sleep_until(pace_start +
                                    std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>(due_s)));
    }
    if (RawBlock* block = begin_block(speed == 0)) {
      for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < channels; ++c) {
          block->values[static_cast<std::size_t>(r) * static_cast<std::size_t>(channels) +
                        static_cast<std::size_t>(c)] =
              recording_.samples_stored(file_sample + r, c);
        }
      }
      block->sequence = sequence;
      block->first_sample = stream_sample;
      block->rows = rows;
      block->channels = channels;
      end_block(*block);
    } else if (!stop_requested()) {
      count_overflow(stream_sample);
    }
    ++sequence;
    stream_sample += static_cast<std::uint64_t>(rows);
    file_sample += rows;
    position_.store(file_sample, std::memory_order_release);
  }
  if (file_sample >= n) {
    post_event({static_cast<double>(stream_sample) / rate_hz, EventKind::SourceEnded,
                "the end of the recording"});
  }
}

}  // namespace oscilab::daq
