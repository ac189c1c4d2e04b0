// The shaker drive and the shaker plant as JACK clients on a real jackd (dummy backend), the
// loop closed through real JACK ports: the controller settles over a stepped sine's levels
// (checked on the plant's port by a third client), and a lost input or a crossed limit sets the
// drive to zero within the period it is seen in.

#include "daq/drive/jack_drive_client.h"

#include <jack/jack.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <thread>
#include <vector>

#include "analysis/model/reference_models.h"
#include "daq/drive/drive_event_json.h"
#include "daq/jack/jack_capture_client.h"
#include "daq/rig/jack_plant.h"
#include "tests/daq/jack/jack_test_server.h"

namespace oscilab::daq {
namespace {

using testing::JackTestServer;

constexpr int kServerRateHz = 48000;
constexpr int kPeriod = 256;
constexpr double kDriveFrequencyHz = 9.0;
constexpr double kAccelerationScale = 50.0;  // m/s² per unit of the plant's port
constexpr double kPositionScale = 0.1;       // m per unit

// The frames of some ports, captured by a client of the test's own beside the drive.
struct Tap {
  Tap(const std::string& server, std::vector<std::string> ports)
      : client(JackCaptureClient::Options{server, "tap", ports, {"a", "b"}, 30.0}) {
    EXPECT_EQ(client.open(), "");
    EXPECT_EQ(client.activate(), "");
  }
  /// Moves what the ring holds into `frames` (frame time of each frame, channel values).
  void drain() {
    while (const FrameSlot* slot = client.ring().front()) {
      for (std::uint32_t f = 0; f < slot->frames; ++f) {
        frame_time.push_back(slot->frame_time + f);
        first.push_back(slot->data[2 * f]);
        second.push_back(slot->data[2 * f + 1]);
      }
      client.ring().pop();
    }
  }
  JackCaptureClient client;
  std::vector<std::uint32_t> frame_time;
  std::vector<float> first, second;
};

// The first-harmonic amplitude of the last `cycles` whole cycles of x, by least squares on sin,
// cos and a constant (normal equations solved by Gaussian elimination).
double first_harmonic_of_last_cycles(const std::vector<float>& x, double cycles) {
  const auto n = static_cast<std::size_t>(std::llround(cycles * kServerRateHz / kDriveFrequencyHz));
  double a[3][4] = {};
  for (std::size_t k = x.size() - n; k < x.size(); ++k) {
    const double phase =
        2.0 * std::numbers::pi * kDriveFrequencyHz * static_cast<double>(k) / kServerRateHz;
    const double basis[3] = {std::sin(phase), std::cos(phase), 1.0};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) a[i][j] += basis[i] * basis[j];
      a[i][3] += basis[i] * x[k];
    }
  }
  for (int p = 0; p < 3; ++p) {
    for (int i = p + 1; i < 3; ++i) {
      const double factor = a[i][p] / a[p][p];
      for (int j = p; j < 4; ++j) a[i][j] -= factor * a[p][j];
    }
  }
  double c[3];
  for (int i = 2; i >= 0; --i) {
    double sum = a[i][3];
    for (int j = i + 1; j < 3; ++j) sum -= a[i][j] * c[j];
    c[i] = sum / a[i][i];
  }
  return std::hypot(c[0], c[1]);
}

struct Loop {
  explicit Loop(const JackTestServer& server, SineControllerOptions controller = {})
      : plant(analysis::paper_model(), plant_options(server)),
        drive(drive_options(server, controller)) {
    EXPECT_EQ(plant.start(), "");
    drive_options_used = drive_options(server, controller);
    EXPECT_EQ(drive.start(), "");
  }
  static JackPlant::Options plant_options(const JackTestServer& server) {
    JackPlant::Options options;
    options.server = server.name();
    options.acceleration_scale_m_s2 = kAccelerationScale;
    options.position_scale_m = kPositionScale;
    options.sensors.creep.amplitude_m = 0.0;
    return options;
  }
  static JackDriveClient::Options drive_options(const JackTestServer& server,
                                                SineControllerOptions controller) {
    JackDriveClient::Options options;
    options.server = server.name();
    options.drive_port = "oscilab-plant:drive";
    options.acceleration_port = "oscilab-plant:acceleration";
    options.position_port = "oscilab-plant:position";
    options.acceleration_scale_m_s2 = kAccelerationScale;
    options.position_scale_m = kPositionScale;
    controller.ramp_s = 0.5;
    controller.gain_guess_m_s2_per_fs = 63.0;
    options.controller = controller;
    return options;
  }
  /// Waits (a minute at most, against a hang) for an event in `state`; returns it.
  TimedDriveEvent wait_for(DriveState state) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (std::chrono::steady_clock::now() < deadline) {
      for (const TimedDriveEvent& event : drive.take_events()) {
        events.push_back(event);
        if (event.event.state == state) return event;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ADD_FAILURE() << "no " << drive_state_name(state) << " event within a minute";
    return {};
  }

  JackPlant plant;
  JackDriveClient drive;
  JackDriveClient::Options drive_options_used;
  std::vector<TimedDriveEvent> events;
};

TEST(JackDrive, SettlesWithinTenCyclesOnAPlantThroughJackPorts) {
  JackTestServer server(kServerRateHz, kPeriod);
  Loop loop(server);
  Tap tap(server.name(), {"oscilab-plant:acceleration", "oscilab-drive:drive"});
  const double mass_kg = analysis::paper_model().mass_kg();
  for (const double f0_n : {0.5, 1.5, 2.5}) {
    const double target = f0_n / mass_kg;
    for (const TimedDriveEvent& event : loop.drive.take_events()) loop.events.push_back(event);
    ASSERT_EQ(loop.drive.set_level(target, kDriveFrequencyHz), "");
    const TimedDriveEvent on_target = loop.wait_for(DriveState::OnTarget);
    EXPECT_EQ(on_target.event.target_m_s2, target);
    EXPECT_GE(on_target.event.cycles, 1);
    EXPECT_LE(on_target.event.cycles, 10) << "f0 " << f0_n;
    EXPECT_NEAR(on_target.event.measured_m_s2 / target, 1.0, 0.01);
    // Held: the table acceleration of the last five cycles of a second on the plant's own port,
    // and the drive still on target. An xrun (the machine too busy for a period: a client's cycle
    // is skipped, its port holds stale samples) disturbs the cycles around it by a few per cent,
    // and the drive rightly leaves OnTarget; it must come back on target. A hold with an xrun in
    // it is held again (on a loaded machine under ctest -j 2 about one in two has one).
    bool held_without_xrun = false;
    for (int attempt = 0; attempt < 20 && !held_without_xrun; ++attempt) {
      for (const TimedDriveEvent& event : loop.drive.take_events()) loop.events.push_back(event);
      // Back on target (within wait_for's minute: xruns in a row may keep it off for a while).
      if (loop.drive.status().state != DriveState::OnTarget) loop.wait_for(DriveState::OnTarget);
      // A second on target (four cycles for a disturbance just before to pass), then the last
      // five cycles; the server's xrun notices come from another thread, so the count is read
      // again 100 ms after the hold.
      const std::uint64_t xruns = tap.client.xruns();
      std::this_thread::sleep_for(std::chrono::milliseconds(1000));
      tap.drain();
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      if (tap.client.xruns() != xruns) continue;
      held_without_xrun = true;
      const double measured = first_harmonic_of_last_cycles(tap.first, 5.0) * kAccelerationScale;
      EXPECT_NEAR(measured / target, 1.0, 0.01) << "f0 " << f0_n;
      const JackDriveClient::Status status = loop.drive.status();
      EXPECT_EQ(status.state, DriveState::OnTarget)
          << "f0 " << f0_n << ": measured/target " << status.measured_m_s2 / target << ", attempt "
          << attempt << ", xruns " << xruns;
    }
    // Twenty holds in a row, each with an xrun: the amplitude could not be checked, only that
    // the drive kept coming back on target.
    if (!held_without_xrun) {
      std::fprintf(stderr, "f0 %.1f N: every hold had an xrun (%llu in all)\n", f0_n,
                   static_cast<unsigned long long>(tap.client.xruns()));
    }
  }
  ASSERT_EQ(loop.drive.ramp_down(), "");
  loop.wait_for(DriveState::Idle);
  EXPECT_EQ(loop.drive.lost_events(), 0u);
  // The event log's line of the last on-target event.
  const nlohmann::json line = drive_event_json(loop.events.back().event, kServerRateHz);
  EXPECT_EQ(line["event"], "drive");
  EXPECT_EQ(line["state"], "idle");
}

// A pulled accelerometer cable: the drive's input port loses its connection. The drive is zero
// from the period that sees it: at most one period after the disconnection returned.
TEST(JackDrive, ALostInputSetsTheDriveToZeroWithinOnePeriod) {
  JackTestServer server(kServerRateHz, kPeriod);
  Loop loop(server);
  Tap tap(server.name(), {"oscilab-plant:acceleration", "oscilab-drive:drive"});
  ASSERT_EQ(loop.drive.set_level(1.5 / analysis::paper_model().mass_kg(), kDriveFrequencyHz), "");
  loop.wait_for(DriveState::OnTarget);
  std::string why;
  jack_client_t* hand = open_jack_client("hand", server.name(), why);
  ASSERT_NE(hand, nullptr) << why;
  ASSERT_EQ(jack_disconnect(hand, "oscilab-plant:acceleration", "oscilab-drive:acceleration"), 0);
  const jack_nframes_t pulled = jack_frame_time(hand);
  const TimedDriveEvent aborted = loop.wait_for(DriveState::Aborted);
  jack_client_close(hand);
  EXPECT_EQ(aborted.event.abort, DriveAbort::InputLost);
  const auto latency = static_cast<std::int32_t>(aborted.frame_time - pulled);
  EXPECT_LE(latency, 2 * kPeriod) << "the abort came " << latency << " frames after the pull";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  tap.drain();
  std::size_t zeros = 0, before = 0;
  for (std::size_t k = 0; k < tap.frame_time.size(); ++k) {
    const auto since = static_cast<std::int32_t>(tap.frame_time[k] - aborted.frame_time);
    if (since >= 0) {
      ASSERT_EQ(tap.second[k], 0.0f) << since << " frames after the abort";
      ++zeros;
    } else if (tap.second[k] != 0.0f) {
      ++before;
    }
  }
  EXPECT_GT(zeros, 10000u);   // the 300 ms after it
  EXPECT_GT(before, 10000u);  // the drive was on before
  EXPECT_EQ(loop.drive.status().state, DriveState::Aborted);
  EXPECT_EQ(loop.drive.set_level(1.0, kDriveFrequencyHz),
            "drive: aborted (input_lost): rearm it first");
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(loop.drive.status().state, DriveState::Aborted);
}

// The table-acceleration limit through JACK: aborted on the sample above it, drive zero after.
TEST(JackDrive, AbortsAtTheTableAccelerationLimit) {
  JackTestServer server(kServerRateHz, kPeriod);
  SineControllerOptions controller;
  controller.max_table_acceleration_m_s2 = 5.0;
  Loop loop(server, controller);
  ASSERT_EQ(loop.drive.set_level(2.0 / analysis::paper_model().mass_kg(), kDriveFrequencyHz), "");
  const TimedDriveEvent aborted = loop.wait_for(DriveState::Aborted);
  EXPECT_EQ(aborted.event.abort, DriveAbort::TableAccelerationLimit);
  EXPECT_GT(aborted.event.value, 5.0);
  const nlohmann::json line = drive_event_json(aborted.event, kServerRateHz);
  EXPECT_EQ(line["abort"], "table_acceleration_limit");
  EXPECT_EQ(loop.drive.status().drive_fs, 0.0);
}

TEST(JackDrive, RefusesMissingPortsAndAbsurdLevelsInOneLine) {
  JackTestServer server(kServerRateHz, kPeriod);
  JackDriveClient::Options options = Loop::drive_options(server, {});
  JackDriveClient drive(options);
  EXPECT_EQ(drive.start(), "port \"oscilab-plant:acceleration\" does not exist on JACK server \"" +
                               server.name() + "\"");
  JackPlant plant(analysis::paper_model(), Loop::plant_options(server));
  ASSERT_EQ(plant.start(), "");
  options.drive_port = "oscilab-plant:acceleration";
  JackDriveClient wrong(options);
  EXPECT_EQ(wrong.start(),
            "port \"oscilab-plant:acceleration\" is not a playback port of JACK "
            "server \"" +
                server.name() + "\"");
  options = Loop::drive_options(server, {});
  JackDriveClient right(options);
  ASSERT_EQ(right.start(), "");
  EXPECT_EQ(right.set_level(-1.0, 9.0), "drive level: the amplitude must be zero or positive");
  EXPECT_EQ(right.set_level(1.0, 1e9),
            "drive level: the frequency must be positive and at most an eighth of the server's "
            "48000 Hz");
  JackDriveClient::Options none = options;
  none.server = "oscilab-no-such-server";
  EXPECT_EQ(JackDriveClient(none).start(),
            "JACK server \"oscilab-no-such-server\" is not running (or refused the client "
            "\"oscilab-drive\")");
}

}  // namespace
}  // namespace oscilab::daq
