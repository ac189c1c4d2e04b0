#pragma once

// What the JACK source's tests share: the rig's calibration as a lab would wire it, and the
// freewheeling soak (a unit test runs it for 5 minutes of signal, a `slow` one for an hour).

#include <cmath>
#include <cstdio>
#include <numbers>
#include <thread>

#include <gtest/gtest.h>

#include "analysis/model/reference_models.h"
#include "daq/sources/jack_source.h"
#include "tests/daq/eventually.h"
#include "tests/daq/jack/jack_test_server.h"

namespace oscilab::daq::testing {

using Clock = std::chrono::steady_clock;

constexpr double kServerRateHz = 48000.0;
constexpr double kRateHz = 512.0;
// Sensitivities of the virtual rig's sensors as a lab would wire them: an IEPE accelerometer of
// 1000 mV/g and a laser vibrometer's displacement output of 10 mV/mm, into an interface whose
// full scale is 5 V.
constexpr double kAccVPerMs2 = 1.0 / 9.80665;  // V per m/s²
constexpr double kVibVPerM = 10.0;             // V per m
constexpr double kFullScaleV = 5.0;

inline Sidecar calibration(double frequency_hz = 9.0) {
  Sidecar s;
  s.sample_rate_hz = kRateHz;
  s.mass_kg = analysis::paper_model().mass_kg();
  ChannelInfo base;
  base.name = "table_acc";
  base.role = ChannelRole::Base;
  base.quantity = Quantity::Acceleration;
  base.unit = "V";
  base.scale = 1.0 / kAccVPerMs2;  // m/s² per V
  base.full_scale_v = kFullScaleV;
  ChannelInfo mass = base;
  mass.name = "y";
  mass.role = ChannelRole::Mass;
  mass.quantity = Quantity::Displacement;
  mass.scale = 1.0 / kVibVPerM;  // m per V
  s.channels = {base, mass};
  Excitation excitation;
  excitation.type = "stepped-sine";
  excitation.frequency_hz = frequency_hz;
  s.excitation = excitation;
  return s;
}

inline JackSource::Options jack_options(const JackTestServer& server,
                                        const JackTestPlayer& player) {
  JackSource::Options o;
  o.server = server.name();
  o.ports = {player.port(0), player.port(1)};
  o.calibration = calibration();
  return o;
}

// Polls `done` until it holds or `seconds` pass (the benchmarks' wait; tests use eventually()).
template <typename Predicate>
bool wait_for(Predicate done, double seconds) {
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  while (!done()) {
    if (Clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// Resident memory now, in bytes (/proc/self/statm).
inline double resident_bytes() {
  std::FILE* statm = std::fopen("/proc/self/statm", "r");
  long pages = 0, resident = 0;
  if (statm == nullptr || std::fscanf(statm, "%ld %ld", &pages, &resident) != 2) resident = 0;
  if (statm != nullptr) std::fclose(statm);
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

// Freewheels `signal_s` seconds of two sines through the source and checks every sample against
// them: the sample clock does not drift (sample k is the signal at S0 + k × 48000 / 512 to the
// end), nothing is dropped (consecutive indices, no dropped frames), memory stays flat.
inline void soak(double signal_s) {
  JackTestServer server;
  JackTestPlayer player(server.name(), 2);
  const JackTestPlayer::Sine a{0.5, 9.0, 0.3}, b{0.25, 23.0, -1.1};
  auto source = std::make_unique<JackSource>(jack_options(server, player));
  BlockQueue queue(1024, source->max_block_rows(), 2);
  source->start(queue);
  ASSERT_TRUE(eventually([&] { return source->counters().samples_delivered > 0; },
                         "the source delivered its first samples"));
  player.play_sines({a, b});
  player.set_freewheel(true);
  const auto started = Clock::now();
  std::uint64_t samples = 0, next = 0, discontinuities = 0;
  double worst = 0.0, rss_early = 0.0;
  bool first = true, s0_known = false;
  std::vector<StreamEvent> events;  // all of them, printed at the end
  double s0 = 0.0;
  const auto target = static_cast<std::uint64_t>(signal_s * kRateHz);
  while (samples < target && Clock::now() - started < std::chrono::seconds(600)) {
    if (!s0_known) {
      for (StreamEvent& e : source->take_events()) {
        if (e.kind == EventKind::Connected)
          s0 = e.data.at("server_frame").get<double>(), s0_known = true;
        events.push_back(std::move(e));
      }
    }
    RawBlock* block = queue.front();
    if (block == nullptr) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      continue;
    }
    // From the first second of the signal on: the start (the ports' connection, the switch to
    // freewheeling) may bring an xrun on a loaded machine, whose samples are withheld before the
    // soak's signal is in.
    if (!first && block->first_sample != next && samples > 512) {
      ++discontinuities;
      std::printf("discontinuity at sample %llu (expected %llu), %llu samples in\n",
                  static_cast<unsigned long long>(block->first_sample),
                  static_cast<unsigned long long>(next), static_cast<unsigned long long>(samples));
    }
    first = false;
    for (int r = 0; r < block->rows; ++r) {
      const std::uint64_t k = block->first_sample + static_cast<std::uint64_t>(r);
      // Exact integer arithmetic for the frame, then the phase, as the player does.
      const double frame = s0 + static_cast<double>(k) * (kServerRateHz / kRateHz);
      for (int c = 0; c < 2; ++c) {
        const JackTestPlayer::Sine& s = c == 0 ? a : b;
        const double cycles = std::fmod(frame * s.frequency_hz / kServerRateHz, 1.0);
        const double expected =
            kFullScaleV * s.amplitude * std::sin(2 * std::numbers::pi * cycles + s.phase_rad);
        // The player's sines start at its first cycle after play_sines: before, silence.
        if (samples > 512) worst = std::max(worst, std::abs(block->value(r, c) - expected));
      }
    }
    samples += static_cast<std::uint64_t>(block->rows);
    next = block->first_sample + static_cast<std::uint64_t>(block->rows);
    queue.pop();
    if (rss_early == 0.0 && samples > static_cast<std::uint64_t>(60 * kRateHz)) {
      rss_early = resident_bytes();
    }
  }
  for (StreamEvent& e : source->take_events()) events.push_back(std::move(e));
  for (const StreamEvent& e : events) {
    std::printf("event %s at %.4f s: %s\n", e.kind_name().c_str(), e.t_s, e.text.c_str());
  }
  const double rss_late = resident_bytes();
  player.set_freewheel(false);
  source->stop();
  const double wall_s = std::chrono::duration<double>(Clock::now() - started).count();
  std::printf("soak: %.0f s of signal in %.1f s (%.0f x real time), RSS %.1f -> %.1f MB\n",
              static_cast<double>(samples) / kRateHz, wall_s,
              static_cast<double>(samples) / kRateHz / wall_s, rss_early / 1e6, rss_late / 1e6);
  ASSERT_TRUE(s0_known);
  EXPECT_GE(samples, target);
  EXPECT_EQ(discontinuities, 0u) << "consecutive sample indices: nothing dropped";
  EXPECT_EQ(source->counters().jack.dropped_frames, 0u);
  EXPECT_EQ(source->counters().blocks_overflowed, 0u);
  EXPECT_LT(worst / kFullScaleV, 2e-6) << "no drift of the sample clock, to the last sample";
  EXPECT_LT(rss_late - rss_early, 2e6) << "memory flat";
}

}  // namespace oscilab::daq::testing
