// The JACK source against a real jackd (dummy backend, no sound hardware): the sample clock and
// phase through the resampler, the live EDC of the virtual rig played through JACK, faults
// (xruns, a killed server, a pulled cable, clipping), the error messages, and a freewheeling
// soak. Each test starts its own server (JackTestServer) and fails, naming the reason, when it
// cannot.
#include "daq/sources/jack_source.h"

#include <soxr.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <thread>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/reference_models.h"
#include "daq/live/acquisition.h"
#include "daq/live/source_factory.h"
#include "daq/recording/recording.h"
#include "daq/rig/virtual_rig.h"
#include "daq/sources/replay_source.h"
#include "tests/daq/eventually.h"
#include "tests/daq/jack/jack_test_server.h"
#include "tests/daq/sources/jack_test_helpers.h"
#include "tests/input_error_of.h"

namespace oscilab::daq {
namespace {

using oscilab::testing::input_error_of;
using testing::calibration;
using testing::Clock;
using testing::eventually;
using testing::jack_options;
using testing::JackTestPlayer;
using testing::JackTestServer;
using testing::kAccVPerMs2;
using testing::kFullScaleV;
using testing::kRateHz;
using testing::kServerRateHz;
using testing::kVibVPerM;

std::size_t count_events(const std::vector<StreamEvent>& events, const std::string& kind) {
  return static_cast<std::size_t>(std::count_if(
      events.begin(), events.end(), [&](const StreamEvent& e) { return e.kind_name() == kind; }));
}

// Reads a source's blocks straight from its queue (no acquisition): every sample with its index.
struct Drain {
  std::vector<std::uint64_t> index;
  std::vector<double> values;  // interleaved
  void take(BlockQueue& queue) {
    while (RawBlock* block = queue.front()) {
      for (int r = 0; r < block->rows; ++r) {
        index.push_back(block->first_sample + static_cast<std::uint64_t>(r));
        for (int c = 0; c < block->channels; ++c) values.push_back(block->value(r, c));
      }
      queue.pop();
    }
  }
};

std::uint32_t server_frame_of_sample0(const std::vector<StreamEvent>& events) {
  for (const StreamEvent& e : events) {
    if (e.kind == EventKind::Connected) return e.data.at("server_frame").get<std::uint32_t>();
  }
  ADD_FAILURE() << "no connected event";
  return 0;
}

// The events, one per line, for a failure's message.
std::string events_text(const std::vector<StreamEvent>& events) {
  std::string text;
  for (const StreamEvent& e : events) {
    text += "\n  " + e.kind_name() + " at " + std::to_string(e.t_s) + " s: " + e.text;
  }
  return text;
}

// The largest difference, relative to full scale, between the drained samples and sines `a`
// (channel 0) and `b` (channel 1) on the server's clock: sample k is the signal at frame
// s0 + k × 48000 / 512. Also where it is (the sample's index).
struct ClockError {
  double worst = 0.0;
  std::uint64_t at = 0;
};
ClockError server_clock_error(const Drain& drain, double s0, const JackTestPlayer::Sine& a,
                              const JackTestPlayer::Sine& b) {
  ClockError e;
  for (std::size_t i = 0; i < drain.index.size(); ++i) {
    const double t_s = s0 / kServerRateHz + static_cast<double>(drain.index[i]) / kRateHz;
    for (int c = 0; c < 2; ++c) {
      const JackTestPlayer::Sine& s = c == 0 ? a : b;
      const double expected = kFullScaleV * s.amplitude *
                              std::sin(2 * std::numbers::pi * s.frequency_hz * t_s + s.phase_rad);
      const double error =
          std::abs(drain.values[2 * i + static_cast<std::size_t>(c)] - expected) / kFullScaleV;
      if (error > e.worst) e.worst = error, e.at = drain.index[i];
    }
  }
  return e;
}

// Two sines referenced to the server's frame clock, one per channel, at different frequencies
// and phases, played through a test server and captured by a JackSource: at least 3 s of its
// samples (a loaded machine takes longer, which is no error; a minute at most, so that a source
// that delivers nothing fails instead of hanging). `stall_after` samples in, the player stalls
// its process callback for 50 ms (0: never).
struct SineCapture {
  const JackTestPlayer::Sine a{0.5, 9.0, 0.3}, b{0.25, 37.0, -1.1};
  Drain drain;
  std::vector<StreamEvent> events;
  SourceCounters counters;
  int reach = 0;
};
void capture_sines(SineCapture& capture, std::size_t stall_after) {
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  player.play_sines({capture.a, capture.b});
  auto source = std::make_unique<JackSource>(jack_options(server, player));
  BlockQueue queue(256, source->max_block_rows(), 2);
  source->start(queue);
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  bool stalled = stall_after == 0;
  while (capture.drain.index.size() < 3u * 512u && Clock::now() < deadline) {
    capture.drain.take(queue);
    if (!stalled && capture.drain.index.size() > stall_after) {
      player.stall(std::chrono::milliseconds(50));
      stalled = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  source->stop();
  capture.drain.take(queue);
  capture.events = source->take_events();
  capture.counters = source->counters();
  capture.reach = source->resampler_reach();
}

TEST(JackSource, AnalysisSamplesSitOnTheServerClockWithTheSameDelayOnEveryChannel) {
  // Sample k of the stream is the signal at frame S0 + k × 48000 / 512 (S0: the frame of sample
  // 0, from the `connected` event), on both channels: soxr removes the filter's group delay and
  // one interleaved instance gives both channels the same one. The tolerance, 2e-6 of full
  // scale, is float32 input (6e-8) plus SOXR_HQ's 20-bit precision (1e-6); a delay of a single
  // server frame would give 9 Hz × 2π / 48000 × 0.5 = 6e-4.
  SineCapture c;
  capture_sines(c, 0);
  const double s0 = server_frame_of_sample0(c.events);
  ASSERT_GT(c.drain.index.size(), 2u * 512u) << "at least 2 s of samples";
  const ClockError error = server_clock_error(c.drain, s0, c.a, c.b);
  EXPECT_LT(error.worst, 2e-6) << "at sample " << error.at << ", xruns " << c.counters.jack.xruns
                               << "; events:" << events_text(c.events);
  EXPECT_EQ(c.reach, 24);  // the design's impulse response, ±47 ms
  EXPECT_EQ(c.counters.jack.dropped_frames, 0u);
}

// After an xrun (the player stalled for 50 ms, nine periods) JACK 2 may run a period again with
// its frame clock one period back, or skip periods. Either way the stream keeps the server's
// clock: every sample delivered after it is still the signal at S0 + k × 48000 / 512 within the
// tolerance above, the xrun's stretch is withheld rather than delivered, and no discontinuity (a
// new time base) is reported.
TEST(JackSource, SamplesAfterAnXrunStayOnTheServerClock) {
  SineCapture c;
  capture_sines(c, 512);
  const double s0 = server_frame_of_sample0(c.events);
  ASSERT_GT(c.drain.index.size(), 2u * 512u) << "at least 2 s of samples";
  EXPECT_GE(c.counters.jack.xruns, 1u) << events_text(c.events);
  EXPECT_EQ(count_events(c.events, "discontinuity"), 0u) << events_text(c.events);
  const ClockError error = server_clock_error(c.drain, s0, c.a, c.b);
  EXPECT_LT(error.worst, 2e-6) << "at sample " << error.at << "; events:" << events_text(c.events);
}

// The virtual rig's stepped sine (levels 0.5, 1.0, 1.5 N at 9 Hz), recorded at 512 Hz.
RigRecording rig_recording() {
  analysis::SteppedSineSchedule schedule;
  schedule.frequency_hz = 9.0;
  schedule.levels_n = {0.5, 1.0, 1.5};
  schedule.hold_s = 8.0;
  schedule.lead_in_s = 1.0;
  RigSpec spec;
  spec.sample_rate_hz = kRateHz;
  return record_stepped_sine(analysis::paper_model(), schedule, spec);
}

std::vector<analysis::LevelResult> by_level(std::vector<analysis::LevelResult> levels) {
  levels.erase(std::remove_if(levels.begin(), levels.end(),
                              [](const auto& l) { return l.f0_n < 0.2 || l.cycles < 10; }),
               levels.end());
  std::sort(levels.begin(), levels.end(),
            [](const auto& x, const auto& y) { return x.f0_n < y.f0_n; });
  return levels;
}

TEST(JackSource, LiveEdcOfTheRigThroughJackMatchesTheSameSignalsAt512Hz) {
  // The rig's b̈ and y in volts (the sensitivities above), upsampled to 48 kHz (soxr_oneshot,
  // very high quality), played into JACK while the server freewheels, resampled back by the
  // source and analysed live. Reference: the same 512 Hz signals through the same live chain
  // (a replay). Per level the EDCs agree within 0.5 % + 5 σ of the difference of the means.
  const RigRecording rig = rig_recording();
  ASSERT_EQ(rig.status, analysis::TimeSimulator::Status::Ok) << rig.message;
  // The same SI values as stored values of unit SI, the levels left out: both chains find the
  // levels themselves.
  Recording reference = rig.recording;
  reference.samples_stored = reference.samples_si;
  reference.sidecar.channels[0].unit = "m/s^2";
  reference.sidecar.channels[1].unit = "m";
  for (ChannelInfo& channel : reference.sidecar.channels) channel.scale = 1.0, channel.offset = 0.0;
  reference.sidecar.excitation->levels.clear();
  Acquisition replayed(std::make_unique<ReplaySource>(reference, ReplaySource::Options{0.0, 64}),
                       {});
  replayed.start();
  ASSERT_TRUE(
      eventually([&] { return replayed.finished(); }, "the replay of the 512 Hz signals finished"));
  replayed.stop();
  const auto expected = by_level(replayed.levels());
  ASSERT_EQ(expected.size(), 3u);

  const Eigen::Index n = rig.recording.samples_si.rows();
  std::vector<double> volts(static_cast<std::size_t>(2 * n));
  for (Eigen::Index i = 0; i < n; ++i) {
    volts[static_cast<std::size_t>(2 * i)] = rig.recording.samples_si(i, 0) * kAccVPerMs2;
    volts[static_cast<std::size_t>(2 * i + 1)] = rig.recording.samples_si(i, 1) * kVibVPerM;
  }
  const auto frames = static_cast<std::size_t>(static_cast<double>(n) * kServerRateHz / kRateHz);
  std::vector<double> up(2 * frames);
  const soxr_io_spec_t io = soxr_io_spec(SOXR_FLOAT64_I, SOXR_FLOAT64_I);
  const soxr_quality_spec_t quality = soxr_quality_spec(SOXR_VHQ, 0);
  std::size_t made = 0;
  ASSERT_EQ(soxr_oneshot(kRateHz, kServerRateHz, 2, volts.data(), static_cast<std::size_t>(n),
                         nullptr, up.data(), frames, &made, &io, &quality, nullptr),
            nullptr);
  std::vector<float> played(2 * made);
  for (std::size_t i = 0; i < played.size(); ++i) {
    played[i] = static_cast<float>(up[i] / kFullScaleV);
  }

  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  auto made_source = std::make_unique<JackSource>(jack_options(server, player));
  JackSource* source = made_source.get();
  Acquisition live(std::move(made_source), {});
  live.start();
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > 0; },
                         "the source delivered its first samples"));
  player.play(std::move(played));
  player.set_freewheel(true);
  ASSERT_TRUE(eventually([&] { return player.done(); }, "the player played all its frames"));
  // One more second of silence flushes the last level through the resampler and the chain.
  const std::uint64_t after = player.frames_played();
  (void)after;
  const std::uint64_t delivered = source->counters().samples_delivered;
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > delivered + 512; },
                         "a second of silence after the signal delivered"));
  player.set_freewheel(false);
  live.stop();
  const AcquisitionStatus status = live.status();
  EXPECT_EQ(status.jack.dropped_frames, 0u);
  const auto measured = by_level(live.levels());
  ASSERT_EQ(measured.size(), expected.size());
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const auto& m = measured[i];
    const auto& e = expected[i];
    const double sigma =
        std::sqrt(m.edc_std_j * m.edc_std_j / m.cycles + e.edc_std_j * e.edc_std_j / e.cycles);
    std::printf(
        "level %.3f N: EDC through JACK %.6g J (%d cycles), at 512 Hz %.6g J (%d), "
        "difference %.3f %% = %.2f sigma\n",
        e.f0_n, m.edc_mean_j, m.cycles, e.edc_mean_j, e.cycles,
        100 * (m.edc_mean_j - e.edc_mean_j) / e.edc_mean_j, (m.edc_mean_j - e.edc_mean_j) / sigma);
    EXPECT_NEAR(m.edc_mean_j, e.edc_mean_j, 0.005 * std::abs(e.edc_mean_j) + 5 * sigma)
        << "level " << i << " f0 " << e.f0_n << " N, " << m.cycles << " vs " << e.cycles
        << " cycles";
    EXPECT_NEAR(m.f0_n, e.f0_n, 0.005 * e.f0_n);
  }
}

TEST(JackSource, XrunsAreCountedLoggedAndLeftOutOfTheStream) {
  // A client that sleeps 50 ms in its process callback (ten periods of 5.3 ms) makes the server
  // report an xrun; the source counts it, logs it, withholds the samples around it (a gap
  // downstream) and goes on.
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  player.play_sines({{0.5, 9.0, 0.0}, {0.5, 9.0, 1.0}});
  auto made = std::make_unique<JackSource>(jack_options(server, player));
  JackSource* source = made.get();
  Acquisition live(std::move(made), {});
  live.start();
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > 256; },
                         "the source delivered 256 samples"));
  player.stall(std::chrono::milliseconds(50));
  ASSERT_TRUE(eventually([&] { return source->counters().jack.xruns > 0; },
                         "the stalled player made the server report an xrun"));
  const std::uint64_t before = source->counters().samples_delivered;
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > before + 256; },
                         "samples after the xrun: the source goes on"));
  live.stop();
  const AcquisitionStatus status = live.status();
  EXPECT_GE(status.jack.xruns, 1u);
  EXPECT_GE(status.gaps, 1u) << "the samples around the xrun are left out";
  const auto events = live.events_since(0);
  EXPECT_GE(count_events(events, "xrun"), 1u);
  EXPECT_GE(count_events(events, "gap"), 1u);
}

TEST(JackSource, AKilledServerIsReportedAndTheSourceReconnectsWhenItComesBack) {
  JackTestServer server;
  auto player = std::make_unique<JackTestPlayer>(server.name(), 2);
  player->play_sines({{0.5, 9.0, 0.0}, {0.5, 9.0, 1.0}});
  JackSource::Options options = jack_options(server, *player);
  options.reconnect_interval_s = 0.1;
  auto made = std::make_unique<JackSource>(options);
  JackSource* source = made.get();
  Acquisition live(std::move(made), {});
  live.start();
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > 256; },
                         "the source delivered 256 samples"));
  server.stop(SIGKILL);  // no goodbye: the clients find the server gone
  ASSERT_TRUE(eventually([&] { return source->counters().jack.server_losses == 1; },
                         "the source saw the server killed"));
  EXPECT_TRUE(eventually([&] { return source->server_rate_hz() == 0.0; },
                         "the source closed its client of the killed server"));
  ASSERT_TRUE(eventually([&] { return player->gone(); }, "the player found its server gone"));
  player.reset();  // its server is gone
  // The source keeps trying while the server is away: it comes back after a failed try.
  ASSERT_TRUE(eventually([&] { return source->counters().jack.failed_reconnects >= 1; },
                         "the source tried to reopen the server while it was away"));
  server.start();
  JackTestPlayer back(server.name(), 2);
  back.play_sines({{0.5, 9.0, 0.0}, {0.5, 9.0, 1.0}});
  ASSERT_TRUE(eventually([&] { return source->counters().jack.reconnections == 1; },
                         "the source reconnected to the server back"));
  const std::uint64_t before = source->counters().samples_delivered;
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > before + 256; },
                         "samples from the server back"));
  live.stop();
  const AcquisitionStatus status = live.status();
  EXPECT_EQ(status.jack.server_losses, 1u);
  EXPECT_EQ(status.jack.reconnections, 1u);
  EXPECT_GE(status.gaps, 1u) << "the time away is a gap of the stream";
  const auto events = live.events_since(0);
  EXPECT_EQ(count_events(events, "server-shutdown"), 1u);
  EXPECT_EQ(count_events(events, "reconnected"), 1u);
  EXPECT_EQ(count_events(events, "error"), 0u);
}

// The frequency of channel 0 over the newest `samples` of a drain: positive-going zero crossings,
// interpolated linearly between samples, timed only between crossings with no gap between them
// (an xrun, which a loaded machine can cause, withholds samples). 0 when there are none.
double frequency_of_newest(const Drain& drain, std::size_t samples) {
  if (drain.index.size() < samples) return 0.0;
  double last = -1.0, timed_s = 0.0;
  int periods = 0;
  for (std::size_t i = drain.index.size() - samples + 1; i < drain.index.size(); ++i) {
    if (drain.index[i] != drain.index[i - 1] + 1) {
      last = -1.0;  // a gap: the next crossing starts afresh
      continue;
    }
    const double a = drain.values[2 * (i - 1)], b = drain.values[2 * i];
    if (a < 0.0 && b >= 0.0) {
      const double t = (static_cast<double>(drain.index[i - 1]) + a / (a - b)) / kRateHz;
      if (last >= 0) timed_s += t - last, ++periods;
      last = t;
    }
  }
  return periods > 0 ? periods / timed_s : 0.0;
}

// A server that comes back at another rate (44.1 kHz after 48 kHz, as after a restart with other
// settings): the source opens its resampler for the new rate, so the stream stays at 512 Hz and a
// 9 Hz sine stays 9 Hz (a resampler left at 48 kHz would make it 9 × 48 / 44.1 = 9.80 Hz).
TEST(JackSource, AServerBackAtAnotherRateIsResampledFromItsNewRate) {
  JackTestServer server;
  auto player = std::make_unique<JackTestPlayer>(server.name(), 2);
  player->play_sines({{0.5, 9.0, 0.0}, {0.5, 9.0, 1.0}});
  JackSource::Options options = jack_options(server, *player);
  options.reconnect_interval_s = 0.1;
  auto source = std::make_unique<JackSource>(options);
  BlockQueue queue(1024, source->max_block_rows(), 2);
  source->start(queue);
  Drain before;
  ASSERT_TRUE(eventually(
      [&] {
        before.take(queue);
        return before.index.size() > 3 * 512;
      },
      "3 s of samples from the first server"));
  EXPECT_NEAR(frequency_of_newest(before, 1024), 9.0, 0.01);
  server.stop(SIGKILL);
  ASSERT_TRUE(eventually([&] { return source->counters().jack.server_losses == 1; },
                         "the source saw the server killed"));
  // The source has closed its client (its rate reads 0) before a server of the same name comes
  // back: libjack 1.9.21 can crash closing a client of a killed server once a new one runs.
  ASSERT_TRUE(eventually([&] { return source->server_rate_hz() == 0.0; },
                         "the source closed its client of the killed server"));
  ASSERT_TRUE(eventually([&] { return player->gone(); }, "the player found its server gone"));
  player.reset();
  server.set_rate_hz(44100);
  server.start();
  JackTestPlayer back(server.name(), 2);
  back.play_sines({{0.5, 9.0, 0.0}, {0.5, 9.0, 1.0}});
  ASSERT_TRUE(eventually([&] { return source->counters().jack.reconnections == 1; },
                         "the source reconnected to the server back at 44.1 kHz"));
  EXPECT_EQ(source->server_rate_hz(), 44100.0);
  Drain after;
  before.take(queue);  // what the first server delivered before it went
  ASSERT_TRUE(eventually(
      [&] {
        after.take(queue);
        return after.index.size() > 3 * 512;
      },
      "3 s of samples from the server back at 44.1 kHz"));
  source->stop();
  EXPECT_NEAR(frequency_of_newest(after, 1024), 9.0, 0.01);
  EXPECT_GT(after.index.front(), before.index.back()) << "the stream clock runs on";
  bool reported = false;
  for (const StreamEvent& e : source->take_events()) {
    if (e.kind == EventKind::Reconnected) reported = e.data.at("server_rate_hz") == 44100;
  }
  EXPECT_TRUE(reported) << "the reconnected event names the new rate";
}

TEST(JackSource, AServerGoneForGoodEndsCleanlyOnStop) {
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  JackSource::Options options = jack_options(server, player);
  options.reconnect_interval_s = 0.05;
  auto source = std::make_unique<JackSource>(options);
  BlockQueue queue(256, source->max_block_rows(), 2);
  source->start(queue);
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > 0; },
                         "the source delivered its first samples"));
  // The test's player leaves first, so that the source's is the process's only client when the
  // server goes, as in the field. With the player's client still open on the stopped server while
  // the source retried, the process crashed inside libjack 1.9.21 in 1 run of 20 (and once in
  // CI); with it closed first, in none of 40.
  player.close();
  server.stop(SIGTERM);
  ASSERT_TRUE(eventually([&] { return source->counters().jack.server_losses == 1; },
                         "the source saw the server stopped"));
  ASSERT_TRUE(eventually([&] { return source->counters().jack.failed_reconnects >= 3; },
                         "three failed tries to reopen the stopped server"));
  // Stopped while it keeps trying, it ends: stop() returns, with no reconnection.
  ASSERT_TRUE(testing::returns([&] { source->stop(); }, "stop() of a source that is reconnecting"));
  EXPECT_EQ(source->counters().jack.reconnections, 0u);
  EXPECT_EQ(source->server_rate_hz(), 0.0);
}

TEST(JackSource, APulledCableIsCountedAndTheSourceReconnectsThePort) {
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  player.play_sines({{0.5, 9.0, 0.0}, {0.5, 9.0, 1.0}});
  JackSource::Options options = jack_options(server, player);
  options.reconnect_interval_s = 0.2;
  auto made = std::make_unique<JackSource>(options);
  JackSource* source = made.get();
  Acquisition live(std::move(made), {});
  live.start();
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > 256; },
                         "the source delivered 256 samples"));
  ASSERT_EQ(jack_disconnect(player.client(), player.port(1).c_str(), "oscilab:in_y"), 0);
  ASSERT_TRUE(eventually([&] { return source->counters().jack.port_disconnections == 1; },
                         "the source saw the cable pulled"));
  ASSERT_TRUE(eventually(
      [&] {
        return jack_port_connected_to(jack_port_by_name(player.client(), "oscilab:in_y"),
                                      player.port(1).c_str()) != 0;
      },
      "the source connected the port again"));
  const std::uint64_t before = source->counters().samples_delivered;
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > before + 256; },
                         "samples after the port was connected again"));
  live.stop();
  const auto events = live.events_since(0);
  EXPECT_EQ(count_events(events, "port-disconnected"), 1u);
  EXPECT_EQ(count_events(events, "port-connected"), 1u);
  EXPECT_GE(live.status().gaps, 1u) << "the unconnected stretch is left out";
}

TEST(JackSource, ClippedInputIsCountedAndRecordedAsInvalid) {
  // A sine of 1.2 × full scale clips at ±1 (JACK's floats pass it; the interface would not):
  // the source counts the samples at full scale and marks what they reach invalid.
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  player.play_sines({{1.2, 9.0, 0.0}, {0.5, 9.0, 1.0}});
  auto made = std::make_unique<JackSource>(jack_options(server, player));
  JackSource* source = made.get();
  Acquisition live(std::move(made), {});
  const auto dir =
      std::filesystem::temp_directory_path() / ("oscilab_jack_clip_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  live.start_recording((dir / "clip.wav").string());
  live.start();
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > 1024; },
                         "the source delivered 1024 samples"));
  live.stop();
  EXPECT_GT(live.status().jack.clipped_samples, 0u);
  EXPECT_GE(count_events(live.events_since(0), "clipped"), 1u);
  const Sidecar sidecar = read_sidecar((dir / "clip.json").string());
  ASSERT_FALSE(sidecar.invalid_intervals.empty());
  EXPECT_EQ(sidecar.invalid_intervals.front().reason, "clipped");
  std::filesystem::remove_all(dir);
}

TEST(JackSource, ListsTheServersCapturePorts) {
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  const std::vector<std::string> ports = JackSource::capture_ports(server.name());
  EXPECT_NE(std::find(ports.begin(), ports.end(), "system:capture_1"), ports.end());
  EXPECT_NE(std::find(ports.begin(), ports.end(), player.port(1)), ports.end());
  EXPECT_EQ(std::find(ports.begin(), ports.end(), "system:playback_1"), ports.end());
}

TEST(JackSource, RefusesWhatItCannotUseNamingTheServerOrThePort) {
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  JackSource::Options o = jack_options(server, player);
  const auto error_of = [](JackSource::Options options) {
    return input_error_of([&] { JackSource source(options); });
  };
  {
    JackSource::Options bad = o;
    bad.server = "oscilab-no-such-server";
    EXPECT_EQ(error_of(bad),
              "jack source: JACK server \"oscilab-no-such-server\" is not running (or refused the "
              "client \"oscilab\")");
  }
  {
    JackSource::Options bad = o;
    bad.ports[1] = "system:capture_9";
    EXPECT_EQ(error_of(bad),
              "jack source: port \"system:capture_9\" does not exist on JACK "
              "server \"" +
                  server.name() + "\"");
  }
  {
    JackSource::Options bad = o;
    bad.ports[0] = "system:playback_1";
    EXPECT_EQ(error_of(bad),
              "jack source: port \"system:playback_1\" is not an audio output (a "
              "capture port) of JACK server \"" +
                  server.name() + "\"");
  }
  {
    JackSource::Options bad = o;
    bad.ports.pop_back();
    EXPECT_EQ(error_of(bad),
              "jack source: 1 port(s) for the calibration's 2 channel(s): give "
              "one port per channel, in the calibration's order");
  }
  {
    JackSource::Options bad = o;
    bad.ports.assign(17, "system:capture_1");
    EXPECT_EQ(error_of(bad), "jack source: 17 ports, at most 16");
  }
  {
    JackSource::Options bad = o;
    bad.ports.clear();
    EXPECT_EQ(error_of(bad), "jack source: no capture port given");
  }
  {
    JackSource::Options bad = o;
    bad.ports[0].clear();
    EXPECT_EQ(error_of(bad), "jack source: port 1 is empty");
  }
  {
    JackSource::Options bad = o;
    bad.analysis_rate_hz = 0.0;
    EXPECT_EQ(error_of(bad), "jack source: analysis rate 0.000000 Hz must be positive");
  }
  {
    JackSource::Options bad = o;
    bad.analysis_rate_hz = 96000.0;
    bad.calibration.excitation.reset();
    EXPECT_EQ(error_of(bad), "jack source: JACK server \"" + server.name() +
                                 "\" runs at 48000.000000 Hz, not above the analysis rate "
                                 "96000.000000 Hz");
  }
  {
    JackSource::Options bad = o;
    bad.passband_end = 0.99;
    EXPECT_EQ(error_of(bad),
              "jack source: passband end 0.990000 must be within 0.1..0.95 of the "
              "analysis Nyquist frequency");
  }
  {
    JackSource::Options bad = o;
    bad.block_rows = 0;
    EXPECT_EQ(error_of(bad), "jack source: block size 0 samples must be within 1..65536");
  }
  {
    JackSource::Options bad = o;
    bad.ring_s = 0.0;
    EXPECT_EQ(error_of(bad),
              "jack source: the ring must hold at least 0.1 s and reconnection take time");
  }
  {
    JackSource::Options bad = o;
    bad.calibration.excitation->frequency_hz = 300.0;
    EXPECT_EQ(error_of(bad),
              "jack source: excitation 300.000000 Hz is not below the Nyquist "
              "frequency of the analysis rate 512.000000 Hz");
  }
  {
    JackSource::Options bad = o;
    bad.analysis_rate_hz = 100.0;
    bad.calibration.excitation.reset();
    bad.calibration.channels[1].ac_coupling_hz = 60.0;
    EXPECT_EQ(error_of(bad),
              "jack source: channel \"y\": ac_coupling_hz 60.000000 Hz is not "
              "below the analysis Nyquist frequency");
  }
  EXPECT_EQ(input_error_of([] { JackSource::capture_ports("oscilab-no-such-server"); }),
            "JACK server \"oscilab-no-such-server\" is not running (or refused the client "
            "\"oscilab-ports\")");
}

TEST(SourceFactory, MakesAJackSourceFromItsDescriptionAndRefusesBadOnes) {
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  SourceOptions o;
  o.jack.server = server.name();
  o.jack.calibration = calibration();
  const std::string spec = "jack:" + player.port(0) + ", " + player.port(1);
  EXPECT_EQ(source_kind(spec), SourceKind::Jack);
  const std::unique_ptr<SampleSource> source = make_source(spec, o);
  ASSERT_NE(dynamic_cast<JackSource*>(source.get()), nullptr);
  EXPECT_EQ(source->layout()->sample_rate_hz, 512.0);
  EXPECT_EQ(source->layout()->extra.at("jack").at("server_rate_hz"), 48000.0);
  o.jack.analysis_rate_hz = 1024.0;
  EXPECT_EQ(make_source(spec, o)->layout()->sample_rate_hz, 1024.0);
  EXPECT_EQ(input_error_of([&] { make_source("jack:a,,b", o); }),
            "--source jack:a,,b: port 2 is empty (jack:PORT_BASE,PORT_MASS[,...])");
  o.jack.calibration.reset();
  EXPECT_EQ(input_error_of([&] { make_source(spec, o); }),
            "--source " + spec +
                ": a JACK source needs its calibration (a sidecar with one channel per port)");
}

TEST(JackSource, FreewheelsFiveMinutesOfSignalLosslesslyOnItsClock) { testing::soak(300.0); }

}  // namespace
}  // namespace oscilab::daq
