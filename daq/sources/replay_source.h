#pragma once

#include <atomic>
#include <string>

#include "daq/recording/recording.h"
#include "daq/sources/sample_source.h"

namespace oscilab::daq {

/// Plays a recording as a live stream: its stored values, block by block, at 1× (the sample
/// clock of the file), faster, or as fast as the consumer takes them (speed 0: waits for room in
/// the queue, never drops). Pause and seek act while it plays. The stream's sample clock runs on
/// through a seek (the stream did not stop); the jump is posted as a `discontinuity` event. The
/// recording's stepped-sine levels are posted as `level` events when the stream reaches them,
/// with their steady windows mapped to stream time, so a replay analyses like the original.
class ReplaySource final : public SampleSource {
 public:
  struct Options {
    double speed = 1.0;   // × real time; 0: as fast as possible
    int block_rows = 64;  // samples per block
    bool loop = false;    // start again at the end (a discontinuity event each time)
  };

  /// Reads the recording (throws InputError naming the file) and checks the options.
  ReplaySource(const std::string& path, Options options);
  /// Plays a recording already in memory; it must hold samples_stored (the readers fill it).
  ReplaySource(Recording recording, Options options);
  ~ReplaySource() override;

  void set_paused(bool paused) { paused_.store(paused, std::memory_order_release); }
  bool paused() const { return paused_.load(std::memory_order_acquire); }
  /// Continue from file time t_s (clamped to the recording). Thread-safe.
  void seek(double t_s);
  /// Changes the speed while playing (0: as fast as possible). Thread-safe.
  void set_speed(double speed);
  /// File time of the next sample to play.
  double position_s() const;
  double duration_s() const { return recording_.duration_s(); }

  int max_block_rows() const override { return options_.block_rows; }
  std::string describe() const override;

 private:
  void run() override;

  Recording recording_;
  Options options_;
  std::atomic<bool> paused_{false};
  std::atomic<double> speed_;
  std::atomic<long long> seek_to_{-1};  // file sample to continue from, or −1
  std::atomic<long long> position_{0};  // file sample played next
};

}  // namespace oscilab::daq
