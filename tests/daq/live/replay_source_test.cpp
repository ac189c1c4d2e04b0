#include "daq/live/replay_source.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

const std::string kSample = std::string(OSCILAB_SOURCE_DIR) + "/samples/stepped_positive.flac";

// Takes every block the source delivers, checking the stream clock is continuous, and keeps the
// stored values of channel 1 with the file sample each came from (via the position).
struct Drain {
  std::uint64_t next_sample = 0, next_sequence = 0;
  std::vector<double> y;
  bool continuous = true;
  void take(BlockQueue& queue) {
    while (RawBlock* b = queue.front()) {
      continuous &= b->first_sample == next_sample && b->sequence == next_sequence;
      next_sample = b->first_sample + static_cast<std::uint64_t>(b->rows);
      next_sequence = b->sequence + 1;
      for (int r = 0; r < b->rows; ++r) y.push_back(b->value(r, 1));
      queue.pop();
    }
  }
};

TEST(ReplaySource, PlaysEveryStoredValueAsFastAsTakenAndPostsTheLevels) {
  const Recording recording = read_recording(kSample);
  ReplaySource::Options options;
  options.speed = 0;
  ReplaySource source(kSample, options);
  BlockQueue queue(4, source.max_block_rows(), source.max_channels());
  source.start(queue);
  Drain drain;
  while (!source.finished() || queue.size() > 0) {
    drain.take(queue);
    std::this_thread::yield();
  }
  source.stop();
  EXPECT_TRUE(drain.continuous);
  ASSERT_EQ(drain.y.size(), static_cast<std::size_t>(recording.sample_count()));
  for (Eigen::Index k = 0; k < recording.sample_count(); k += 997) {
    EXPECT_EQ(drain.y[static_cast<std::size_t>(k)], recording.samples_stored(k, 1));  // bit-exact
  }
  std::size_t levels = 0;
  for (const StreamEvent& e : source.take_events()) {
    if (e.kind != EventKind::Level) continue;
    const ExcitationLevel& original = recording.sidecar.excitation->levels[levels++];
    EXPECT_EQ(e.data["steady_from_s"].get<double>(), original.start_s);  // no seek: same times
    EXPECT_EQ(e.data["steady_to_s"].get<double>(), original.end_s);
  }
  EXPECT_EQ(levels, recording.sidecar.excitation->levels.size());
  EXPECT_TRUE(source.layout()->excitation->extra.value("levels_live", false));
}

TEST(ReplaySource, PausesAndSeeksWhileTheStreamClockRunsOn) {
  ReplaySource::Options options;
  options.speed = 20;  // 20× real time: 10 240 samples per second
  ReplaySource source(kSample, options);
  BlockQueue queue(64, source.max_block_rows(), source.max_channels());
  source.start(queue);
  Drain drain;
  const auto drain_for = [&](int ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    while (std::chrono::steady_clock::now() < end) {
      drain.take(queue);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  };
  drain_for(200);
  source.set_paused(true);
  drain_for(50);
  const std::size_t paused_at = drain.y.size();
  drain_for(200);
  EXPECT_EQ(drain.y.size(), paused_at);  // nothing while paused
  EXPECT_GT(paused_at, 1000u);           // ~2000 samples in 200 ms at 20×

  source.seek(200.0);  // file time 200 s
  source.set_paused(false);
  drain_for(100);
  source.stop();
  EXPECT_TRUE(drain.continuous);  // the stream's clock did not jump
  const Recording recording = read_recording(kSample);
  const auto target = static_cast<Eigen::Index>(200.0 * 512);
  EXPECT_EQ(drain.y[paused_at], recording.samples_stored(target, 1));
  bool discontinuity = false;
  for (const StreamEvent& e : source.take_events())
    discontinuity |= e.kind == EventKind::Discontinuity;
  EXPECT_TRUE(discontinuity);
  EXPECT_THROW(source.set_speed(-1), InputError);
  EXPECT_THROW(ReplaySource(kSample + ".missing.wav", options), InputError);
}

}  // namespace
}  // namespace oscilab::daq
