#include "daq/sources/replay_source.h"

#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "tests/daq/eventually.h"

namespace oscilab::daq {
namespace {

using testing::eventually;

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
  // As fast as taken, into a queue of 4 blocks: the source delivers 4 and waits for room. Paused,
  // it finishes at most the block it was on. Two seeks while paused are each taken (a
  // `discontinuity` event each) and deliver nothing: a source that played on while paused
  // would have played a block of the first target before taking the second (the test keeps the
  // queue empty). Resumed, the stream goes on from the last seek's file sample, its clock
  // continuous.
  ReplaySource::Options options;
  options.speed = 0;
  ReplaySource source(kSample, options);
  BlockQueue queue(4, source.max_block_rows(), source.max_channels());
  source.start(queue);
  ASSERT_TRUE(eventually([&] { return source.counters().blocks_delivered == 4; },
                         "the source filled the queue of 4 blocks"));
  source.set_paused(true);
  Drain drain;
  std::size_t discontinuities = 0;
  const auto seek_while_paused = [&](double t_s) {
    source.seek(t_s);
    return eventually(
        [&] {
          drain.take(queue);
          for (const StreamEvent& e : source.take_events())
            discontinuities += e.kind == EventKind::Discontinuity;
          return discontinuities > 0 && source.counters().blocks_delivered == drain.next_sequence;
        },
        "the paused source took the seek to " + std::to_string(t_s) + " s");
  };
  ASSERT_TRUE(seek_while_paused(200.0));
  const std::uint64_t paused_at = source.counters().blocks_delivered;
  EXPECT_LE(paused_at, 5u);  // the 4 in the queue and at most the one it was on
  discontinuities = 0;
  ASSERT_TRUE(seek_while_paused(100.0));  // file time 100 s
  EXPECT_EQ(source.counters().blocks_delivered, paused_at) << "nothing while paused";
  EXPECT_EQ(drain.y.size(), paused_at * 64);

  const std::size_t resumed_at = drain.y.size();
  source.set_paused(false);
  ASSERT_TRUE(eventually(
      [&] {
        drain.take(queue);
        return drain.y.size() >= resumed_at + 1024;
      },
      "1024 samples after the source was resumed"));
  source.stop();
  EXPECT_TRUE(drain.continuous);  // the stream's clock did not jump
  const Recording recording = read_recording(kSample);
  // Before the resume, the file from its start: nothing from either seek's target.
  for (std::size_t k = 0; k < resumed_at; ++k) {
    ASSERT_EQ(drain.y[k], recording.samples_stored(static_cast<Eigen::Index>(k), 1))
        << "sample " << k << " before the resume";
  }
  const auto target = static_cast<Eigen::Index>(100.0 * 512);
  for (Eigen::Index k = 0; k < 1024; ++k) {
    ASSERT_EQ(drain.y[resumed_at + static_cast<std::size_t>(k)],
              recording.samples_stored(target + k, 1))
        << "sample " << k << " after the seek";
  }
  EXPECT_THROW(source.set_speed(-1), InputError);
  EXPECT_THROW(ReplaySource(kSample + ".missing.wav", options), InputError);
}

}  // namespace
}  // namespace oscilab::daq
