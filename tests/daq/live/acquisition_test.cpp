#include "daq/live/acquisition.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/reference_models.h"
#include "daq/live/stream_monitor.h"
#include "daq/network/net_source.h"
#include "daq/network/stream_protocol.h"
#include "daq/network/tcp_socket.h"
#include "daq/recording/campaign_reader.h"
#include "daq/rig/virtual_rig.h"
#include "daq/sources/rig_source.h"
#include "tests/daq/eventually.h"
#include "tests/daq/live/scripted_source.h"

namespace oscilab::daq {
namespace {

namespace fs = std::filesystem;
using testing::ScriptedSource;

fs::path temp_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("oscilab_live_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs until the source has ended and everything it sent was processed (60 s at most).
void run_to_end(Acquisition& acquisition) {
  acquisition.start();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!acquisition.finished() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  acquisition.stop();
  ASSERT_TRUE(acquisition.finished()) << "the source never ended within 60 s";
}

std::size_t count_events(const Acquisition& acquisition, const std::string& kind) {
  std::size_t n = 0;
  for (const StreamEvent& e : acquisition.events_since(0)) n += e.kind_name() == kind;
  return n;
}

RigSource::Options stepped_rig(double speed) {
  RigSource::Options o;
  o.speed = speed;
  o.duration_s = 20.0;
  o.schedule = {{1.0, 0.5, 9.0}, {7.0, 1.0, 9.0}, {13.0, 1.5, 9.0}, {19.0, 0.0, 9.0}};
  return o;
}

TEST(Acquisition, LiveRecordingAnalysesOfflineToTheSameEdcs) {
  // A recording made live analyses to the same EDCs as the same data offline. The
  // live chain and the offline analysis run the same pipeline on the same stored values, with
  // the levels the recorder wrote as they were operated: the EDCs agree to the last bit.
  const fs::path dir = temp_dir("same_edc");
  const std::string path = (dir / "live.wav").string();
  Acquisition acquisition(std::make_unique<RigSource>(analysis::paper_model(), stepped_rig(0.0)),
                          {});
  acquisition.start_recording(path);
  run_to_end(acquisition);
  const std::vector<analysis::LevelResult> live = acquisition.levels();
  ASSERT_EQ(live.size(), 3u);

  const analysis::CampaignAnalysis offline =
      analyze_recordings({path}, {}, analysis::PipelineSettings{});
  const auto& levels = offline.records.at(0).levels;
  ASSERT_EQ(levels.size(), live.size());
  for (std::size_t i = 0; i < live.size(); ++i) {
    EXPECT_EQ(levels[i].edc_mean_j, live[i].edc_mean_j) << "level " << i;
    EXPECT_EQ(levels[i].edc_std_j, live[i].edc_std_j);
    EXPECT_EQ(levels[i].cycles, live[i].cycles);
    EXPECT_EQ(levels[i].f0_n, live[i].f0_n);
    EXPECT_NEAR(live[i].f0_n, 0.5 * static_cast<double>(i + 1), 2e-3);  // ±0.4 %: sensor noise
  }
  const Recording recording = read_recording(path);
  EXPECT_EQ(recording.sample_count(), 20 * 512);
  EXPECT_EQ(recording.sidecar.excitation->levels.size(), 3u);
  EXPECT_TRUE(fs::exists(dir / "live.events.jsonl"));
  fs::remove_all(dir);
}

TEST(Acquisition, OperatorStepsTheRigWhileItRuns) {
  RigSource::Options o;
  o.speed = 0.0;
  o.duration_s = 8.0;
  auto source = std::make_unique<RigSource>(analysis::paper_model(), o);
  RigSource& rig = *source;
  rig.set_excitation(1.0, 9.0);  // applied from the first block
  Acquisition acquisition(std::move(source), {});
  run_to_end(acquisition);
  EXPECT_EQ(rig.excitation().f0_n, 1.0);
  ASSERT_EQ(acquisition.levels().size(), 1u);
  EXPECT_NEAR(acquisition.levels()[0].f0_n, 1.0, 2e-3);
  EXPECT_EQ(count_events(acquisition, "level"), 1u);
  EXPECT_THROW(rig.set_excitation(-1.0, 9.0), InputError);
}

// A clean stepped-sine recording to cut into scripted blocks.
Recording clean_recording(const fs::path& dir) {
  analysis::SteppedSineSchedule schedule;
  schedule.levels_n = {0.6, 1.2};
  schedule.hold_s = 8.0;
  schedule.lead_in_s = 1.0;
  RigSpec spec;
  const RigRecording rig = record_stepped_sine(analysis::paper_model(), schedule, spec);
  const std::string path = (dir / "clean.wav").string();
  write_recording(rig.recording, path);
  Recording recording = read_recording(path);
  recording.sidecar.channels[0].range = std::make_pair(-250.0, 250.0);
  recording.sidecar.channels[1].range = std::make_pair(-0.05, 0.05);
  return recording;
}

// A layout made in code may leave the excitation's `extra` null, not an empty object: the
// acquisition reads it as "no extra keys" (it used to throw on its thread and end the process).
TEST(Acquisition, AnExcitationWithoutExtraKeysIsAnalysedLikeOneWithThem) {
  const fs::path dir = temp_dir("null_extra");
  const Recording clean = clean_recording(dir);
  Sidecar layout = clean.sidecar;
  ASSERT_TRUE(layout.excitation.has_value());
  layout.excitation->extra = nlohmann::json();  // null
  Acquisition reference(
      std::make_unique<ScriptedSource>(clean.sidecar, ScriptedSource::cut(clean, 32)), {});
  run_to_end(reference);
  Acquisition null_extra(std::make_unique<ScriptedSource>(layout, ScriptedSource::cut(clean, 32)),
                         {});
  run_to_end(null_extra);
  ASSERT_EQ(null_extra.levels().size(), reference.levels().size());
  ASSERT_EQ(reference.levels().size(), 2u);
  for (std::size_t i = 0; i < reference.levels().size(); ++i) {
    EXPECT_EQ(null_extra.levels()[i].edc_mean_j, reference.levels()[i].edc_mean_j);
  }
  fs::remove_all(dir);
}

TEST(Acquisition, FaultsAreCountedLoggedRecordedAndLeftOutOfTheEdc) {
  const fs::path dir = temp_dir("faults");
  const Recording clean = clean_recording(dir);
  const std::vector<ScriptedSource::Block> blocks = ScriptedSource::cut(clean, 32);

  Acquisition reference(std::make_unique<ScriptedSource>(clean.sidecar, blocks), {});
  run_to_end(reference);
  const std::vector<analysis::LevelResult> clean_levels = reference.levels();
  ASSERT_EQ(clean_levels.size(), 2u);
  EXPECT_EQ(reference.status().excluded_cycles, 0);

  // Block 60 lost (a gap), 90 sent twice, 120 and 121 swapped, a NaN in 150, the vibrometer at
  // full scale in 200: all inside the levels' steady holds.
  std::vector<ScriptedSource::Block> faulty;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (i == 60) continue;
    if (i == 120) {
      faulty.push_back(blocks[121]);
      faulty.push_back(blocks[120]);
      ++i;
      continue;
    }
    faulty.push_back(blocks[i]);
    if (i == 90) faulty.push_back(blocks[i]);
    if (i == 150) faulty.back().values[2 * 3 + 1] = std::numeric_limits<double>::quiet_NaN();
    if (i == 200) faulty.back().values[2 * 5 + 1] = 0.05 / 1e-7;  // counts of 0.05 m
  }
  const std::string path = (dir / "faulty.wav").string();
  Acquisition acquisition(std::make_unique<ScriptedSource>(clean.sidecar, faulty), {});
  acquisition.start_recording(path);
  run_to_end(acquisition);
  const AcquisitionStatus s = acquisition.status();
  EXPECT_EQ(s.gaps, 1u);
  EXPECT_EQ(s.gap_samples, 32u);
  EXPECT_EQ(s.duplicates, 1u);
  EXPECT_EQ(s.reordered, 1u);
  EXPECT_EQ(s.non_finite_samples, 1u);
  EXPECT_EQ(s.saturated_samples, 1u);
  EXPECT_EQ(s.recorded_samples, static_cast<std::uint64_t>(clean.sample_count()));
  for (const char* kind : {"gap", "duplicate", "non-finite", "saturated"}) {
    EXPECT_EQ(count_events(acquisition, kind), 1u) << kind;
  }
  // A fault spoils the cycle it falls in (and at most the one beside it, at a boundary); the
  // gap of 62.5 ms spans one or two of the 111 ms cycles.
  EXPECT_GE(s.excluded_cycles, 4);
  EXPECT_LE(s.excluded_cycles, 8);

  // The levels lose a few cycles but not their energy: within 3 standard errors of the clean.
  const std::vector<analysis::LevelResult> levels = acquisition.levels();
  ASSERT_EQ(levels.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_LT(levels[i].cycles, clean_levels[i].cycles);
    const double standard_error = clean_levels[i].edc_std_j / std::sqrt(levels[i].cycles);
    EXPECT_NEAR(levels[i].edc_mean_j, clean_levels[i].edc_mean_j, 3 * standard_error + 1e-15);
  }
  // The recording holds the faults as such (NaN where samples are missing or were NaN,
  // declared invalid) and analyses offline to the same EDCs.
  const Recording recorded = read_recording(path);
  EXPECT_EQ(recorded.sidecar.invalid_intervals.size(), 3u);
  EXPECT_TRUE(std::isnan(recorded.samples_stored(60 * 32, 0)));
  const analysis::CampaignAnalysis offline =
      analyze_recordings({path}, {}, analysis::PipelineSettings{});
  ASSERT_EQ(offline.records[0].levels.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(offline.records[0].levels[i].edc_mean_j, levels[i].edc_mean_j);
    EXPECT_EQ(offline.records[0].levels[i].cycles, levels[i].cycles);
  }
  fs::remove_all(dir);
}

TEST(Acquisition, ASlowConsumerShowsAsOverflowAndGapsNotAsCorruption) {
  const fs::path dir = temp_dir("slow");
  const Recording clean = clean_recording(dir);
  const std::vector<ScriptedSource::Block> blocks = ScriptedSource::cut(clean, 32);
  AcquisitionOptions options;
  options.queue_blocks = 2;  // the source does not wait: most blocks find the queue full
  Acquisition acquisition(std::make_unique<ScriptedSource>(clean.sidecar, blocks,
                                                           std::vector<StreamEvent>{}, false, 50),
                          options);
  run_to_end(acquisition);
  const AcquisitionStatus s = acquisition.status();
  EXPECT_GT(s.overflowed_blocks, 0u);
  EXPECT_EQ(s.blocks + s.overflowed_blocks, blocks.size());
  // Dropped blocks before a delivered one show as gaps of exactly their samples (all blocks
  // but the last hold 32); none is delivered twice or corrupted. (How many are dropped depends
  // on the scheduler; the test below makes it exact.)
  EXPECT_EQ(s.gap_samples % 32, 0u);
  EXPECT_LE(s.gap_samples, 32 * s.overflowed_blocks);
  EXPECT_EQ(s.duplicates + s.late + s.non_finite_samples, 0u);
  EXPECT_GE(count_events(acquisition, "overflow"), 1u);
  fs::remove_all(dir);
}

TEST(Acquisition, BlocksAQueueCouldNotTakeBecomeOneGapOfExactlyTheirSamples) {
  // Deterministic: 10 blocks arrive at once into a queue of 4 that nobody reads yet, so 4 are
  // taken and 6 overflow; after them the source waits for room. The consumer then sees blocks
  // 0-3, a gap of the 6 × 32 samples lost, and the rest, each once.
  const fs::path dir = temp_dir("burst");
  const Recording clean = clean_recording(dir);
  const std::vector<ScriptedSource::Block> blocks = ScriptedSource::cut(clean, 32);
  ScriptedSource source(clean.sidecar, blocks, {}, true, 0, 10);
  BlockQueue queue(4, 32, 2);
  source.start(queue);
  ASSERT_TRUE(testing::eventually([&] { return source.counters().blocks_overflowed >= 6; },
                                  "6 of the 10 blocks overflowed the queue of 4"));
  ASSERT_EQ(source.counters().blocks_overflowed, 6u);
  ASSERT_EQ(source.counters().blocks_delivered, 4u);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> gaps;
  std::uint64_t delivered = 0;
  StreamMonitor monitor(8, 32, 2,
                        {[&](const RawBlock&, std::uint64_t) { ++delivered; },
                         [&](std::uint64_t first, std::uint64_t n) { gaps.emplace_back(first, n); },
                         [](EventKind, std::uint64_t, std::uint64_t) {}});
  while (!source.finished() || queue.size() > 0) {
    while (RawBlock* block = queue.front()) {
      monitor.push(*block);
      queue.pop();
    }
    std::this_thread::yield();
  }
  source.stop();
  monitor.flush();
  EXPECT_EQ(delivered, blocks.size() - 6);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_EQ(gaps[0], std::make_pair(std::uint64_t{4 * 32}, std::uint64_t{6 * 32}));
  fs::remove_all(dir);
}

TEST(Acquisition, ARecordingKilledMidRunOpensAndHoldsEverySampleWrittenBeforeTheKill) {
  // SIGKILL the recording process; the files it leaves open and hold every sample it had
  // written, each exactly as the rig delivered it. The child records the rig in real time and
  // reports through a pipe each new count of samples its recorder has written; the parent kills
  // it once 3 s of stream are written. The file then holds at least the last count reported
  // (the recorder loses at most the block it was writing, and that one was not counted yet).
  const fs::path dir = temp_dir("kill");
  const std::string path = (dir / "killed.wav").string();
  RigSource::Options o;
  o.speed = 1.0;
  o.schedule = {{0.5, 1.0, 9.0}};
  int report[2];
  ASSERT_EQ(::pipe(report), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(report[0]);
    Acquisition acquisition(std::make_unique<RigSource>(analysis::paper_model(), o), {});
    acquisition.start_recording(path);
    acquisition.start();
    std::uint64_t reported = 0;
    for (;;) {
      const std::uint64_t recorded = acquisition.status().recorded_samples;
      if (recorded != reported) {
        if (::write(report[1], &recorded, sizeof recorded) != sizeof recorded) ::_exit(2);
        reported = recorded;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  ::close(report[1]);
  constexpr std::uint64_t kKillAfter = 3 * 512;  // samples: 3 s of stream at 512 Hz
  std::uint64_t recorded = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (recorded < kKillAfter) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    pollfd readable{report[0], POLLIN, 0};
    if (left.count() <= 0 || ::poll(&readable, 1, static_cast<int>(left.count())) != 1 ||
        ::read(report[0], &recorded, sizeof recorded) != sizeof recorded) {
      break;  // no report within the guard, or the child died
    }
  }
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  ::close(report[0]);
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_GE(recorded, kKillAfter) << "the child never reported 3 s of stream recorded";

  const Recording recording = read_recording(path);  // opens: header and sidecar are whole
  const auto held = static_cast<std::uint64_t>(recording.sample_count());
  std::printf("killed once %llu samples were written: the file holds %llu\n",
              static_cast<unsigned long long>(recorded), static_cast<unsigned long long>(held));
  EXPECT_GE(held, recorded) << "a sample written before the kill is missing";
  // Every sample is the rig's reading (no torn, zero or foreign block at the end): the same rig
  // again, as fast as taken, delivers the same stream (its noise comes from a seeded generator).
  o.speed = 0.0;
  RigSource again(analysis::paper_model(), o);
  BlockQueue queue(64, again.max_block_rows(), again.max_channels());
  again.start(queue);
  std::uint64_t compared = 0;
  bool same = true;
  ASSERT_TRUE(testing::eventually(
      [&] {
        for (RawBlock* b = queue.front(); b != nullptr && compared < held; b = queue.front()) {
          for (int r = 0; r < b->rows && compared < held; ++r, ++compared) {
            for (int c = 0; c < b->channels; ++c) {
              same &= recording.samples_stored(static_cast<Eigen::Index>(compared), c) ==
                      b->value(r, c);
            }
          }
          queue.pop();
        }
        return compared == held;
      },
      "the rig delivered again the samples the file holds"));
  again.stop();
  EXPECT_TRUE(same) << "the file's samples differ from the rig's stream";
  std::ifstream events(dir / "killed.events.jsonl");
  std::string line;
  int lines = 0;
  while (std::getline(events, line)) {
    EXPECT_TRUE(nlohmann::json::accept(line)) << line;  // whole lines only
    ++lines;
  }
  EXPECT_GE(lines, 2);  // recording-started, start, level
  fs::remove_all(dir);
}

// A sender as any DAQ program would write one: the protocol over a plain socket.
void send_blocks(TcpSocket& socket, const std::vector<ScriptedSource::Block>& blocks,
                 std::size_t from, std::size_t to) {
  std::vector<std::uint8_t> bytes;
  for (std::size_t i = from; i < to; ++i) {
    bytes.clear();
    stream_protocol::append_data(blocks[i].sequence, blocks[i].first_sample, blocks[i].rows, 2,
                                 blocks[i].values.data(), bytes);
    ASSERT_TRUE(socket.send_all(bytes.data(), bytes.size()));
  }
}

TEST(Acquisition, NetworkStreamSurvivesReconnectsHostileFramesAndWrongLayouts) {
  const fs::path dir = temp_dir("net");
  const Recording clean = clean_recording(dir);
  const std::vector<ScriptedSource::Block> blocks = ScriptedSource::cut(clean, 32);
  auto source = std::make_unique<NetSource>(NetSource::Options{});
  const std::uint16_t port = source->port();
  Acquisition acquisition(std::move(source), {});
  acquisition.start();

  // Each sender below is served to its end before the next connects: the source says so with
  // its n-th `disconnected` event.
  const auto served = [&](std::size_t n) {
    return testing::eventually([&] { return count_events(acquisition, "disconnected") == n; },
                               "the source served sender " + std::to_string(n) + " to its end");
  };
  const stream_protocol::Hello hello{"daq-42", clean.sidecar};
  std::vector<std::uint8_t> bytes;
  {  // the sender streams a while, then its connection drops
    TcpSocket socket = TcpSocket::connect_to("127.0.0.1", port);
    stream_protocol::append_hello(hello, bytes);
    ASSERT_TRUE(socket.send_all(bytes.data(), bytes.size()));
    send_blocks(socket, blocks, 0, 100);
  }
  ASSERT_TRUE(served(1));
  // Record from here: once the 100 blocks sent so far are processed.
  ASSERT_TRUE(testing::eventually([&] { return acquisition.status().samples == 100u * 32u; },
                                  "the 100 blocks of the first sender processed"));
  acquisition.start_recording((dir / "net.wav").string());
  {  // a hostile peer: a header announcing 4 GiB, then garbage
    TcpSocket socket = TcpSocket::connect_to("127.0.0.1", port);
    const std::uint8_t junk[16] = {'O',  'S',  'C',  'S',  1, 1, 0, 0,
                                   0xff, 0xff, 0xff, 0xff, 1, 2, 3, 4};
    socket.send_all(junk, sizeof junk);
  }
  ASSERT_TRUE(served(2));
  {  // another instrument at another rate: refused
    Sidecar other = clean.sidecar;
    other.sample_rate_hz = 1000;
    bytes.clear();
    stream_protocol::append_hello({"other", other}, bytes);
    TcpSocket socket = TcpSocket::connect_to("127.0.0.1", port);
    socket.send_all(bytes.data(), bytes.size());
  }
  ASSERT_TRUE(served(3));
  {  // the sender comes back; 10 blocks were lost meanwhile; it ends the stream
    TcpSocket socket = TcpSocket::connect_to("127.0.0.1", port);
    bytes.clear();
    stream_protocol::append_hello(hello, bytes);
    ASSERT_TRUE(socket.send_all(bytes.data(), bytes.size()));
    send_blocks(socket, blocks, 110, blocks.size());
    bytes.clear();
    stream_protocol::append_bye(bytes);
    socket.send_all(bytes.data(), bytes.size());
  }
  ASSERT_TRUE(testing::eventually([&] { return acquisition.finished(); },
                                  "the acquisition finished after the sender's BYE"));
  acquisition.stop();
  const AcquisitionStatus s = acquisition.status();
  EXPECT_EQ(s.network.connections, 4u);
  EXPECT_EQ(s.network.malformed_frames, 1u);
  EXPECT_EQ(s.network.layout_mismatches, 1u);
  EXPECT_EQ(s.gaps, 1u);
  EXPECT_EQ(s.gap_samples, 10u * 32u);
  EXPECT_EQ(s.samples, static_cast<std::uint64_t>(clean.sample_count()) - 320u);
  EXPECT_EQ(count_events(acquisition, "layout-mismatch"), 1u);
  EXPECT_EQ(count_events(acquisition, "malformed-frame"), 1u);
  // Both levels (from the HELLO's sidecar) analysed; the gap's cycles left out.
  EXPECT_EQ(acquisition.levels().size(), 2u);
  EXPECT_GE(s.excluded_cycles, 3);
  // The recording began after the first 100 blocks and holds the rest, the gap as NaN.
  const Recording recorded = read_recording((dir / "net.wav").string());
  EXPECT_EQ(recorded.sample_count(), clean.sample_count() - 100 * 32);
  EXPECT_TRUE(std::isnan(recorded.samples_stored(5 * 32, 1)));
  EXPECT_EQ(recorded.samples_stored(10 * 32, 1), clean.samples_stored(110 * 32, 1));
  fs::remove_all(dir);
}

TEST(Acquisition, NetSourceListensOnLocalhostAndNamesABusyPort) {
  NetSource first(NetSource::Options{});
  NetSource::Options same;
  same.port = first.port();
  try {
    NetSource second(same);
    FAIL() << "a second listener on the same port";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("127.0.0.1:" + std::to_string(first.port())),
              std::string::npos);
  }
  EXPECT_NE(first.describe().find("127.0.0.1"), std::string::npos);
}

// A stream at a rate its sidecar may declare but no live analysis can follow (100 MHz: the live
// filters and ten minutes of history would need terabytes) is recorded whole with the live
// analysis off and said so, and the history ring stays within its memory bound.
TEST(Acquisition, AStreamTooFastToAnalyseLiveIsRecordedWithTheAnalysisOff) {
  const fs::path dir = temp_dir("fast");
  const Recording clean = clean_recording(dir);
  Sidecar layout = clean.sidecar;
  layout.sample_rate_hz = 1e8;
  std::vector<ScriptedSource::Block> blocks = ScriptedSource::cut(clean, 32);
  blocks.resize(4);
  Acquisition acquisition(std::make_unique<ScriptedSource>(layout, blocks), {});
  const std::string path = (dir / "fast.wav").string();
  acquisition.start_recording(path);
  run_to_end(acquisition);
  const AcquisitionStatus s = acquisition.status();
  EXPECT_EQ(s.edc_message.rfind("live analysis off: the stream's 1e+08 Hz is above", 0), 0u)
      << s.edc_message;
  EXPECT_EQ(s.recorded_samples, 128u);
  const Recording recorded = read_recording(path);
  EXPECT_EQ(recorded.sample_count(), 128);
  EXPECT_EQ(recorded.sidecar.sample_rate_hz, 1e8);
  fs::remove_all(dir);
}

TEST(Acquisition, StartRecordingRejectsAContainerThatCannotBeCrashSafe) {
  Acquisition acquisition(std::make_unique<RigSource>(analysis::paper_model(), stepped_rig(0)), {});
  try {
    acquisition.start_recording((fs::temp_directory_path() / "x.flac").string());
    FAIL();
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(".wav, .w64 or .rf64"), std::string::npos);
  }
}

}  // namespace
}  // namespace oscilab::daq
