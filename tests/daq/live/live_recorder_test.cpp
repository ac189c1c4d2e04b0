#include "daq/live/live_recorder.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analysis/common/input_error.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::channel;
using testing::input_error_of;
using testing::TempDir;

constexpr double kRateHz = 512.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The stream's layout: base acceleration in g with an offset, mass displacement in mm, force in N.
Sidecar layout() {
  Sidecar s;
  s.sample_rate_hz = kRateHz;
  s.mass_kg = 0.26;
  s.channels = {channel("b", ChannelRole::Base, Quantity::Acceleration, "g", 0.5, 0.01),
                channel("y", ChannelRole::Mass, Quantity::Displacement, "mm", 2.0),
                channel("f", ChannelRole::Force, Quantity::Force, "N")};
  s.notes = "live recorder test";
  return s;
}

// A block of `rows` rows of stored values, row-major: values that no decimal or single-precision
// path would keep (random doubles over 40 decades, signed), and a few special ones.
RawBlock block(std::uint64_t sequence, std::uint64_t first_sample, int rows, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-20, 20);
  RawBlock b;
  b.sequence = sequence;
  b.first_sample = first_sample;
  b.rows = rows;
  b.channels = 3;
  b.values.resize(static_cast<std::size_t>(rows) * 3);
  for (double& v : b.values) v = mantissa(rng) * std::pow(10.0, exponent(rng));
  if (rows > 2) {
    b.values[0] = -0.0;
    b.values[1] = std::numeric_limits<double>::denorm_min();
    b.values[2] = std::numeric_limits<double>::max() / 1e10;  // still finite after calibration
  }
  return b;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The process's open file descriptors.
std::size_t open_descriptors() {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
    ++n;
  }
  return n;
}

// Written in blocks of uneven sizes, closed and read back with the project's reader: every stored
// value is the one written, bit for bit (float64 containers are lossless), the SI samples are the
// sidecar's calibration of them, and the sidecar keeps the layout and says where the recording
// began in the stream.
class LiveRecorderContainer : public ::testing::TestWithParam<std::string> {};

TEST_P(LiveRecorderContainer, RoundTripsEverySampleBitForBit) {
  const TempDir dir;
  const std::string path = dir.file("live" + GetParam());
  std::mt19937_64 rng(2024);
  std::vector<RawBlock> blocks;
  const std::uint64_t first = 1000;
  std::uint64_t next = first;
  for (int rows : {1, 64, 100, 7, 512, 33}) {
    blocks.push_back(block(blocks.size(), next, rows, rng));
    next += static_cast<std::uint64_t>(rows);
  }
  {
    LiveRecorder recorder(path, layout(), first);
    for (const RawBlock& b : blocks) ASSERT_TRUE(recorder.write(b)) << recorder.error();
    EXPECT_EQ(recorder.samples_written(), next - first);
    recorder.close();
    EXPECT_EQ(recorder.error(), "");
  }
  const Recording r = read_recording(path);
  ASSERT_EQ(r.sample_count(), static_cast<Eigen::Index>(next - first));
  ASSERT_EQ(r.samples_stored.cols(), 3);
  const Sidecar expected = layout();
  Eigen::Index row = 0;
  for (const RawBlock& b : blocks) {
    for (int i = 0; i < b.rows; ++i, ++row) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(same_bits(r.samples_stored(row, c), b.value(i, c)))
            << "row " << row << ", channel " << c << ": " << r.samples_stored(row, c) << " vs "
            << b.value(i, c);
        const ChannelInfo& ch = expected.channels[static_cast<std::size_t>(c)];
        const double factor = c == 0 ? 9.80665 : c == 1 ? 1e-3 : 1.0;  // g, mm, N to SI
        EXPECT_EQ(r.samples_si(row, c), (ch.scale * b.value(i, c) + ch.offset) * factor);
      }
    }
  }
  EXPECT_EQ(r.sidecar.sample_rate_hz, kRateHz);
  EXPECT_EQ(r.sidecar.mass_kg, 0.26);
  EXPECT_EQ(r.sidecar.notes, "live recorder test");
  ASSERT_EQ(r.sidecar.channels.size(), 3u);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(r.sidecar.channels[c].name, expected.channels[c].name);
    EXPECT_EQ(r.sidecar.channels[c].role, expected.channels[c].role);
    EXPECT_EQ(r.sidecar.channels[c].unit, expected.channels[c].unit);
    EXPECT_EQ(r.sidecar.channels[c].scale, expected.channels[c].scale);
    EXPECT_EQ(r.sidecar.channels[c].offset, expected.channels[c].offset);
  }
  EXPECT_TRUE(r.sidecar.invalid_intervals.empty());
  ASSERT_TRUE(r.sidecar.extra.contains("recorded_live"));
  EXPECT_EQ(r.sidecar.extra["recorded_live"]["stream_first_sample"], first);
  EXPECT_NE(r.container.find("64"), std::string::npos) << r.container;  // 64-bit float
}

INSTANTIATE_TEST_SUITE_P(Float64Containers, LiveRecorderContainer,
                         ::testing::Values(".wav", ".w64", ".rf64", ".WAV"), [](const auto& info) {
                           std::string name = info.param.substr(1);
                           return name == "WAV" ? std::string("upper_case_wav") : name;
                         });

// Crash safety: the header follows every write, so before close the file on disk (with the
// sidecar written at open) is already a complete recording of every row written so far.
TEST(LiveRecorder, FileIsReadableBeforeClose) {
  const TempDir dir;
  const std::string path = dir.file("open.wav");
  std::mt19937_64 rng(5);
  LiveRecorder recorder(path, layout(), 0);
  const RawBlock a = block(0, 0, 300, rng);
  ASSERT_TRUE(recorder.write(a));
  const Recording r = read_recording(path);
  ASSERT_EQ(r.sample_count(), 300);
  EXPECT_TRUE(same_bits(r.samples_stored(299, 2), a.value(299, 2)));
}

// A gap keeps the stream's clock: its samples are NaN rows at their place, declared invalid
// ("gap") over [first missing, last missing] in recording time, so the reader accepts them.
// Consecutive gaps extend one interval; a later one starts another.
TEST(LiveRecorder, GapsAreNaNRowsDeclaredInvalid) {
  const TempDir dir;
  const std::string path = dir.file("gaps.wav");
  std::mt19937_64 rng(9);
  const std::uint64_t first = 5120;  // stream time 10 s
  {
    LiveRecorder recorder(path, layout(), first);
    ASSERT_TRUE(recorder.write(block(0, first, 100, rng)));
    ASSERT_TRUE(recorder.write_gap(5000));  // more than one chunk of NaN rows (4096)
    ASSERT_TRUE(recorder.write_gap(20));    // the same gap, reported in two parts
    ASSERT_TRUE(recorder.write(block(3, first + 5120, 50, rng)));
    ASSERT_TRUE(recorder.write_gap(1));
    ASSERT_TRUE(recorder.write(block(5, first + 5171, 10, rng)));
    EXPECT_TRUE(recorder.write_gap(0));  // nothing to do
    EXPECT_EQ(recorder.samples_written(), 100u + 5020u + 50u + 1u + 10u);
  }  // the destructor closes
  const Recording r = read_recording(path);
  ASSERT_EQ(r.sample_count(), 5181);
  ASSERT_EQ(r.sidecar.invalid_intervals.size(), 2u);
  const InvalidInterval& g1 = r.sidecar.invalid_intervals[0];
  EXPECT_EQ(g1.reason, "gap");
  EXPECT_DOUBLE_EQ(g1.start_s, 100 / kRateHz);
  EXPECT_DOUBLE_EQ(g1.end_s, 5119 / kRateHz);
  const InvalidInterval& g2 = r.sidecar.invalid_intervals[1];
  EXPECT_DOUBLE_EQ(g2.start_s, 5170 / kRateHz);
  EXPECT_DOUBLE_EQ(g2.end_s, 5170 / kRateHz);
  for (Eigen::Index row = 0; row < r.sample_count(); ++row) {
    const bool missing = (row >= 100 && row < 5120) || row == 5170;
    for (int c = 0; c < 3; ++c) {
      ASSERT_EQ(std::isnan(r.samples_stored(row, c)), missing) << "row " << row;
    }
  }
}

// mark_invalid takes stream samples, inclusive: converted to recording time, clipped at the
// recording's start, dropped when wholly before it; intervals of different reasons stay apart and
// in time order; a NaN inside a declared interval reads back, one outside is refused.
TEST(LiveRecorder, InvalidIntervalsAreInRecordingTime) {
  const TempDir dir;
  const std::string path = dir.file("invalid.w64");
  std::mt19937_64 rng(13);
  const std::uint64_t first = 1024;
  RawBlock b = block(0, first, 512, rng);
  b.values[200 * 3 + 1] = kNaN;  // row 200, channel y
  {
    LiveRecorder recorder(path, layout(), first);
    ASSERT_TRUE(recorder.write(b));
    recorder.mark_invalid(0, 1000, "saturated");                   // before the recording: dropped
    recorder.mark_invalid(first + 310, first + 300, "saturated");  // ends either way round
    recorder.mark_invalid(1000, first + 9, "discontinuity");       // clipped to the first sample
    recorder.mark_invalid(first + 200, first + 200, "non-finite");
    recorder.close();
  }
  const Recording r = read_recording(path);
  ASSERT_EQ(r.sidecar.invalid_intervals.size(), 3u);
  const auto& iv = r.sidecar.invalid_intervals;
  EXPECT_EQ(iv[0].reason, "discontinuity");
  EXPECT_DOUBLE_EQ(iv[0].start_s, 0.0);
  EXPECT_DOUBLE_EQ(iv[0].end_s, 9 / kRateHz);
  EXPECT_EQ(iv[1].reason, "non-finite");
  EXPECT_DOUBLE_EQ(iv[1].start_s, 200 / kRateHz);
  EXPECT_EQ(iv[2].reason, "saturated");
  EXPECT_DOUBLE_EQ(iv[2].start_s, 300 / kRateHz);
  EXPECT_DOUBLE_EQ(iv[2].end_s, 310 / kRateHz);
  EXPECT_TRUE(std::isnan(r.samples_stored(200, 1)));

  // The same NaN undeclared: the reader refuses the file, naming the channel.
  const std::string bad = dir.file("undeclared.w64");
  {
    LiveRecorder recorder(bad, layout(), first);
    ASSERT_TRUE(recorder.write(b));
  }
  const std::string message = input_error_of([&] { read_recording(bad); });
  EXPECT_NE(message.find("\"y\""), std::string::npos) << message;
}

// Levels of the excitation as operated, given in stream time, are written in recording time: a
// level open at close ends where the recording ends; the next change ends an open level; a level
// whose steady part ends before the recording began is left out; f0 = 0 (rest) ends one and adds
// none.
TEST(LiveRecorder, OperatedLevelsAreWrittenInRecordingTime) {
  const TempDir dir;
  const std::string path = dir.file("levels.wav");
  std::mt19937_64 rng(17);
  const std::uint64_t first = 2048;  // stream time 4 s
  const double inf = std::numeric_limits<double>::infinity();
  {
    LiveRecorder recorder(path, layout(), first);
    recorder.add_level(0.3, 9.0, 1.0, 2.0, 3.5);  // steady 2–3.5 s: before the recording
    recorder.add_level(0.5, 9.0, 3.5, 4.5, inf);  // open
    ASSERT_TRUE(recorder.write(block(0, first, 2048, rng)));  // up to 8 s
    recorder.add_level(1.0, 9.0, 7.0, 7.5, inf);  // ends the 0.5 N level at 7 s (3 s rec.)
    ASSERT_TRUE(recorder.write(block(1, first + 2048, 1024, rng)));  // up to 10 s
    recorder.add_level(0.0, 9.0, 9.0, 9.0, inf);                     // back to rest at 9 s
    recorder.add_level(1.5, 9.0, 9.5, 9.75, inf);                    // open at close
    ASSERT_TRUE(recorder.write(block(2, first + 3072, 512, rng)));   // up to 11 s
    recorder.close();
    recorder.close();  // idempotent
  }
  const Sidecar s = read_sidecar(sidecar_path_for(path));
  ASSERT_TRUE(s.excitation.has_value());
  EXPECT_EQ(s.excitation->type, "stepped-sine");
  EXPECT_EQ(s.excitation->frequency_hz, 9.0);
  const auto& levels = s.excitation->levels;
  ASSERT_EQ(levels.size(), 3u);
  EXPECT_EQ(levels[0].f0_n, 0.5);
  EXPECT_DOUBLE_EQ(levels[0].start_s, 0.5);
  EXPECT_DOUBLE_EQ(levels[0].end_s, 3.0);
  EXPECT_EQ(levels[1].f0_n, 1.0);
  EXPECT_DOUBLE_EQ(levels[1].start_s, 3.5);
  EXPECT_DOUBLE_EQ(levels[1].end_s, 5.0);
  EXPECT_EQ(levels[2].f0_n, 1.5);
  EXPECT_DOUBLE_EQ(levels[2].start_s, 5.75);
  EXPECT_DOUBLE_EQ(levels[2].end_s, 7.0);  // 3584 samples written
  EXPECT_EQ(levels[2].extra["frequency_hz"], 9.0);
}

// Levels the stream's own sidecar gives up front (stream time) move to recording time too.
TEST(LiveRecorder, LevelsOfTheStreamLayoutMoveToRecordingTime) {
  const TempDir dir;
  const std::string path = dir.file("given.wav");
  Sidecar given = layout();
  given.excitation = Excitation{"stepped-sine", 9.0, {}, {}};
  given.excitation->levels.push_back({0.5, 1.0, 3.0, {}});
  given.excitation->levels.push_back({1.0, 4.0, 7.0, {}});
  given.invalid_intervals.push_back({0.0, 1.0, "gap"});  // the stream's, not this recording's
  { LiveRecorder recorder(path, given, 1024); }          // stream time 2 s
  const Sidecar s = read_sidecar(sidecar_path_for(path));
  ASSERT_TRUE(s.excitation.has_value());
  ASSERT_EQ(s.excitation->levels.size(), 2u);
  EXPECT_DOUBLE_EQ(s.excitation->levels[0].start_s, 0.0);  // clipped at the recording's start
  EXPECT_DOUBLE_EQ(s.excitation->levels[0].end_s, 1.0);
  EXPECT_DOUBLE_EQ(s.excitation->levels[1].start_s, 2.0);
  EXPECT_DOUBLE_EQ(s.excitation->levels[1].end_s, 5.0);
  EXPECT_TRUE(s.invalid_intervals.empty());
}

// The event log: one JSON object per line, its time moved to recording time (NaN: null).
TEST(LiveRecorder, EventsAreLoggedOnePerLineInRecordingTime) {
  const TempDir dir;
  const std::string path = dir.file("events.wav");
  {
    LiveRecorder recorder(path, layout(), 1024);  // stream time 2 s
    recorder.log(StreamEvent(2.5, EventKind::Mark, "operator's mark", {{"n", 1}}));
    recorder.log(StreamEvent(kNaN, EventKind::Connected));
  }
  std::ifstream in(dir.file("events.events.jsonl"));
  std::string line;
  std::vector<nlohmann::json> events;
  while (std::getline(in, line)) events.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0]["kind"], "mark");
  EXPECT_DOUBLE_EQ(events[0]["t_s"].get<double>(), 0.5);
  EXPECT_EQ(events[0]["text"], "operator's mark");
  EXPECT_EQ(events[0]["data"]["n"], 1);
  EXPECT_TRUE(events[1]["t_s"].is_null());
  EXPECT_EQ(events[1]["kind"], "connected");
}

TEST(LiveRecorder, WriteAfterCloseIsRefused) {
  const TempDir dir;
  std::mt19937_64 rng(23);
  LiveRecorder recorder(dir.file("closed.wav"), layout(), 0);
  recorder.close();
  EXPECT_FALSE(recorder.write(block(0, 0, 10, rng)));
  EXPECT_FALSE(recorder.write_gap(10));
  EXPECT_EQ(recorder.samples_written(), 0u);
}

// Bad paths and layouts throw InputError naming the path (and the offending extension).
TEST(LiveRecorder, ThrowsInputErrorNamingAnUnusablePath) {
  const TempDir dir;
  // A container that is not float64 with a live header.
  const std::string flac = dir.file("live.flac");
  std::string message = input_error_of([&] { LiveRecorder(flac, layout(), 0); });
  EXPECT_NE(message.find(flac), std::string::npos) << message;
  EXPECT_NE(message.find("\".flac\""), std::string::npos) << message;
  message = input_error_of([] { LiveRecorder::check_path("run.csv"); });
  EXPECT_NE(message.find("\".csv\""), std::string::npos) << message;
  EXPECT_EQ(input_error_of([] { LiveRecorder::check_path("run.rf64"); }), "");

  // A directory that does not exist.
  const std::string missing = dir.file("no/such/dir/live.wav");
  message = input_error_of([&] { LiveRecorder(missing, layout(), 0); });
  EXPECT_NE(message.find(missing), std::string::npos) << message;
  EXPECT_NE(message.find("cannot write"), std::string::npos) << message;

  // A sample rate no container can hold.
  Sidecar zero_rate = layout();
  zero_rate.sample_rate_hz = 0.2;
  message = input_error_of([&] { LiveRecorder(dir.file("slow.wav"), zero_rate, 0); });
  EXPECT_NE(message.find("cannot record"), std::string::npos) << message;

  // A layout the sidecar format refuses (a zero scale): named by its field. The sound file is
  // open by then; the failed constructor closes it again (no descriptor left behind).
  Sidecar zero_scale = layout();
  zero_scale.channels[1].scale = 0.0;
  const std::size_t open_before = open_descriptors();
  message = input_error_of([&] { LiveRecorder(dir.file("bad.wav"), zero_scale, 0); });
  EXPECT_NE(message.find("channels[1].scale"), std::string::npos) << message;
  EXPECT_EQ(open_descriptors(), open_before);
}

}  // namespace
}  // namespace oscilab::daq

namespace oscilab::daq {
namespace {

TEST(LiveRecorder, HandsTheDataToTheDiskAtMostOncePerIntervalAndAtClose) {
  // The policy: fdatasync at most every sync_interval on the writer's thread, and at close.
  const TempDir dir;
  std::mt19937_64 rng(11);
  {
    LiveRecorder recorder(dir.file("slow.wav"), layout(), 0, std::chrono::hours(1));
    for (int i = 0; i < 20; ++i) ASSERT_TRUE(recorder.write(block(i, 16 * i, 16, rng)));
    EXPECT_EQ(recorder.syncs(), 0u) << "an hour has not passed";
    recorder.close();
    EXPECT_EQ(recorder.syncs(), 1u) << "the close syncs";
  }
  LiveRecorder every(dir.file("every.wav"), layout(), 0, std::chrono::milliseconds(0));
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(every.write(block(i, 16 * i, 16, rng)));
  EXPECT_EQ(every.syncs(), 20u) << "interval 0: every block";
  EXPECT_EQ(LiveRecorder::kDefaultSyncInterval, std::chrono::milliseconds(1000));
}

TEST(LiveRecorder, ARecordingCutAnywhereInItsLastSecondKeepsEverythingBeforeTheCut) {
  // 10 s of 3 float64 channels (24 bytes per sample time), a level and an invalid interval
  // reaching into the last second. A copy cut at every 29th byte of the last second (29 is prime
  // to 24 and 8: every position within a sample and within a value is hit) is repaired by
  // recover_live_recording and then opens with read_recording, holding exactly the whole
  // samples before the cut, bit for bit.
  const TempDir dir;
  const std::string path = dir.file("whole.wav");
  std::mt19937_64 rng(12);
  {
    LiveRecorder recorder(path, layout(), 0);
    recorder.add_level(0.5, 9.0, 1.0, 1.5, 9.8);
    recorder.mark_invalid(4900, 5000, "gap");
    for (int i = 0; i < 320; ++i) ASSERT_TRUE(recorder.write(block(i, 16 * i, 16, rng)));
    recorder.close();
  }
  const Recording whole = read_recording(path);
  ASSERT_EQ(whole.sample_count(), 5120);
  const auto size = static_cast<std::int64_t>(std::filesystem::file_size(path));
  const std::int64_t frame_bytes = 24, data_begin = size - 5120 * frame_bytes;
  const std::string cut = dir.file("cut.wav");
  int cuts = 0;
  for (std::int64_t at = size - 512 * frame_bytes; at < size; at += 29) {
    std::filesystem::copy_file(path, cut, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(sidecar_path_for(path), sidecar_path_for(cut),
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::resize_file(cut, static_cast<std::uintmax_t>(at));
    const std::int64_t expected = (at - data_begin) / frame_bytes;
    ASSERT_EQ(recover_live_recording(cut), expected) << "cut at byte " << at;
    const Recording kept = read_recording(cut);
    ASSERT_EQ(kept.sample_count(), expected);
    for (Eigen::Index c = 0; c < 3; ++c) {
      ASSERT_TRUE(
          same_bits(kept.samples_stored(expected - 1, c), whole.samples_stored(expected - 1, c)))
          << "cut at byte " << at;
    }
    ASSERT_TRUE(kept.samples_stored == whole.samples_stored.topRows(expected));
    const double end_s = static_cast<double>(expected) / kRateHz;
    ASSERT_TRUE(kept.sidecar.excitation && !kept.sidecar.excitation->levels.empty());
    ASSERT_LE(kept.sidecar.excitation->levels.back().end_s, end_s);
    // The interval from sample 4900 on is kept, clipped to the cut, once the cut passes it.
    ASSERT_EQ(kept.sidecar.invalid_intervals.size(), expected >= 4900 ? 1u : 0u);
    if (expected >= 4900) {
      ASSERT_LE(kept.sidecar.invalid_intervals.back().end_s, end_s);
    }
    ++cuts;
  }
  EXPECT_EQ(cuts, 424);
  std::filesystem::resize_file(cut, 10);
  EXPECT_EQ(input_error_of([&] { recover_live_recording(cut); }).rfind(cut, 0), 0u);
}

// The durability policy (docs/live.md) tested where it matters, at every block boundary:
// - a crash: the file on disk after each block, copied while the recorder still has it open,
//   opens with read_recording as it is, holding exactly the blocks written so far;
// - a power cut: the finished file cut at every block boundary, at offsets inside blocks and
//   inside its header. read_recording never crashes on it: it opens with exactly the samples
//   before the cut or refuses it with an InputError naming the file; recover_live_recording
//   then makes it open with exactly those samples, bit for bit (or names the file when not one
//   whole sample is left).
TEST(LiveRecorder, ACutAtEveryBlockBoundaryOpensWithTheSamplesBeforeIt) {
  constexpr int kBlocks = 96, kRows = 16;
  constexpr std::int64_t kFrameBytes = 24;  // 3 float64 channels
  const TempDir dir;
  const std::string path = dir.file("blocks.wav");
  const std::string copy = dir.file("copy.wav");
  const auto copy_as = [&](const std::string& to) {
    std::filesystem::copy_file(path, to, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(sidecar_path_for(path), sidecar_path_for(to),
                               std::filesystem::copy_options::overwrite_existing);
  };
  std::mt19937_64 rng(31);
  std::vector<RawBlock> blocks;
  {
    LiveRecorder recorder(path, layout(), 0);
    recorder.add_level(0.5, 9.0, 0.0, 0.5, 2.5);
    for (int i = 0; i < kBlocks; ++i) {
      blocks.push_back(block(i, kRows * i, kRows, rng));
      ASSERT_TRUE(recorder.write(blocks.back()));
      copy_as(copy);
      const Recording open = read_recording(copy);
      ASSERT_EQ(open.sample_count(), kRows * (i + 1)) << "after block " << i;
      ASSERT_TRUE(same_bits(open.samples_stored(kRows * i, 1), blocks.back().value(0, 1)));
    }
    recorder.close();
  }
  const Recording whole = read_recording(path);
  ASSERT_EQ(whole.sample_count(), kBlocks * kRows);
  const auto size = static_cast<std::int64_t>(std::filesystem::file_size(path));
  const std::int64_t data_begin = size - kBlocks * kRows * kFrameBytes;
  std::vector<std::int64_t> cuts = {0, 4, 12, 36, data_begin - 1};  // inside the header
  for (int b = 0; b <= kBlocks; ++b) {
    const std::int64_t boundary = data_begin + b * kRows * kFrameBytes;
    cuts.push_back(boundary);
    if (b % 17 == 3) {  // a few inside blocks: within a value, between values, a row past
      for (const std::int64_t inside :
           {std::int64_t{1}, std::int64_t{8}, std::int64_t{23}, kFrameBytes * 5 + 13}) {
        cuts.push_back(boundary + inside);
      }
    }
  }
  int opened_as_cut = 0, recovered = 0;
  for (const std::int64_t at : cuts) {
    copy_as(copy);
    std::filesystem::resize_file(copy, static_cast<std::uintmax_t>(at));
    const std::int64_t expected = std::max<std::int64_t>(0, (at - data_begin) / kFrameBytes);
    try {
      const Recording as_cut = read_recording(copy);
      ASSERT_EQ(as_cut.sample_count(), expected) << "cut at byte " << at;
      ++opened_as_cut;
    } catch (const InputError& error) {
      ASSERT_EQ(std::string(error.what()).rfind(copy, 0), 0u) << error.what();
    }
    if (expected == 0) {
      EXPECT_EQ(input_error_of([&] { recover_live_recording(copy); }).rfind(copy, 0), 0u)
          << "cut at byte " << at;
      continue;
    }
    ASSERT_EQ(recover_live_recording(copy), expected) << "cut at byte " << at;
    const Recording kept = read_recording(copy);
    ASSERT_TRUE(kept.samples_stored == whole.samples_stored.topRows(expected))
        << "cut at byte " << at;
    // The level's steady window (0.5 to 2.5 s) is kept once the cut passes its start, clipped.
    const double end_s = static_cast<double>(expected) / kRateHz;
    const auto& levels = kept.sidecar.excitation->levels;
    ASSERT_EQ(levels.size(), end_s > 0.5 ? 1u : 0u) << "cut at byte " << at;
    if (!levels.empty()) {
      ASSERT_EQ(levels[0].end_s, std::min(end_s, 2.5));
    }
    ++recovered;
  }
  EXPECT_EQ(cuts.size(), 5u + (kBlocks + 1) + 6u * 4u);
  EXPECT_EQ(opened_as_cut, 1) << "only the uncut length has a header that matches";
  EXPECT_EQ(recovered, kBlocks + 6 * 4);  // every cut but those before the first sample
}

}  // namespace
}  // namespace oscilab::daq
