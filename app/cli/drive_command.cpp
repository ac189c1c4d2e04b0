// `oscilab-cli drive --acceleration PORT --position PORT --drive PORT --mass KG --levels A:STEP:B
// --freq HZ [--hold S] [--events LOG.jsonl]` (contract §2): a stepped sine on a real shaker
// through a JACK output port, each level brought to its table acceleration f0/m by the sine
// controller (daq/drive/sine_controller.h) and held there, the controller's state in an event
// log. A crossed limit or a lost input stops the drive at once and ends the command (exit 2,
// naming the limit's option).
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "analysis/common/job.h"
#include "app/cli/commands.h"
#include "app/cli/drive_options.h"
#include "app/cli/option_parsing.h"
#include "daq/drive/drive_event_json.h"
#include "daq/drive/jack_drive_client.h"

namespace oscilab::cli {
namespace {

CancelToken g_drive_cancel;  // SIGINT and SIGTERM ramp the drive down and end the command
extern "C" void on_drive_signal(int) { g_drive_cancel.cancel(); }

struct DriveOptions {
  daq::JackDriveClient::Options drive;
  double mass_kg = 0.0;
  std::string levels;
  double frequency_hz = 9.0;
  double hold_s = 10.0;
  double settle_timeout_s = 30.0;
  std::string events_path;
};

std::string abort_text(const daq::DriveEvent& event, const DriveOptions& o) {
  return drive_abort_line(event, o.drive.controller, "--acceleration/--position");
}

class EventLog {
 public:
  EventLog(const std::string& path, double rate_hz) : rate_hz_(rate_hz) {
    if (path.empty()) return;
    file_.open(path, std::ios::app);
    if (!file_) throw InputError("--events " + path + ": cannot open for writing");
  }
  void write(const daq::DriveEvent& event) {
    if (!file_.is_open()) return;
    file_ << daq::drive_event_json(event, rate_hz_).dump() << '\n';
    file_.flush();
    if (!file_) throw InputError("--events: cannot write (disk full?)");
  }

 private:
  std::ofstream file_;
  double rate_hz_;
};

// Drains the drive's events into the log until one in `state` (or an abort, or the signal).
// Returns whether such an event came (`ended_by`) before the timeout or the signal.
bool wait_for(daq::JackDriveClient& drive, EventLog& log, daq::DriveState state, double timeout_s,
              daq::DriveEvent& ended_by, bool stop_on_signal = true, double target_m_s2 = 0.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    for (const daq::TimedDriveEvent& timed : drive.take_events()) {
      log.write(timed.event);
      // An on-target event of an earlier level (one that left and re-entered the tolerance
      // just before the new level was set) does not count for this one.
      const bool earlier_level =
          state == daq::DriveState::OnTarget && timed.event.target_m_s2 != target_m_s2;
      if ((timed.event.state == state && !earlier_level) ||
          timed.event.state == daq::DriveState::Aborted) {
        ended_by = timed.event;
        return true;
      }
    }
    if (drive.shut_down()) throw InputError("--jack-server: the JACK server shut down");
    if (stop_on_signal && g_drive_cancel.cancelled()) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

void ramp_down_and_wait(daq::JackDriveClient& drive, EventLog& log, double ramp_s) {
  if (drive.status().state == daq::DriveState::Idle ||
      drive.status().state == daq::DriveState::Aborted) {
    return;
  }
  (void)drive.ramp_down();
  daq::DriveEvent ended{};
  // The ramp down itself is not cut short by the signal.
  wait_for(drive, log, daq::DriveState::Idle, ramp_s + 5.0, ended, false);
}

void run(DriveOptions o) {
  const std::vector<double> levels_n = parse_levels(o.levels, "--levels");
  daq::JackDriveClient drive(o.drive);
  if (const std::string why = drive.start(); !why.empty()) throw InputError(why);
  EventLog log(o.events_path, drive.rate_hz());
  std::signal(SIGINT, on_drive_signal);
  std::signal(SIGTERM, on_drive_signal);
  std::printf("drive on %s at %.0f Hz; %zu level(s) at %g Hz\n", drive.port_name("drive").c_str(),
              drive.rate_hz(), levels_n.size(), o.frequency_hz);
  for (std::size_t i = 0; i < levels_n.size(); ++i) {
    const double target = levels_n[i] / o.mass_kg;
    if (const std::string why = drive.set_level(target, o.frequency_hz); !why.empty()) {
      ramp_down_and_wait(drive, log, o.drive.controller.ramp_s);
      throw InputError("--levels " + std::to_string(levels_n[i]) + ": " + why);
    }
    daq::DriveEvent ended{};
    const bool got = wait_for(drive, log, daq::DriveState::OnTarget,
                              o.drive.controller.ramp_s + o.settle_timeout_s, ended, true, target);
    if (g_drive_cancel.cancelled()) break;
    if (got && ended.state == daq::DriveState::Aborted) throw InputError(abort_text(ended, o));
    if (!got) {
      ramp_down_and_wait(drive, log, o.drive.controller.ramp_s);
      throw InputError("--levels " + std::to_string(levels_n[i]) +
                       " N: the table acceleration did not come within --tolerance of f0/m in " +
                       std::to_string(o.settle_timeout_s) + " s after the ramp");
    }
    std::printf(
        "level %zu/%zu: f0 %.4g N (%.4g m/s²) on target after %d cycle(s): measured "
        "%.4g m/s², drive %.4g of full scale\n",
        i + 1, levels_n.size(), levels_n[i], target, ended.cycles, ended.measured_m_s2,
        ended.drive_fs);
    std::fflush(stdout);
    // The hold: the level stays on; an abort or the signal ends it.
    const bool aborted = wait_for(drive, log, daq::DriveState::Aborted, o.hold_s, ended);
    if (aborted && ended.state == daq::DriveState::Aborted) throw InputError(abort_text(ended, o));
    if (g_drive_cancel.cancelled()) break;
  }
  ramp_down_and_wait(drive, log, o.drive.controller.ramp_s);
  drive.stop();
  std::printf("drive ramped down and stopped\n");
}

}  // namespace

void add_drive_command(CLI::App& app) {
  auto o = std::make_shared<DriveOptions>();
  CLI::App* command = app.add_subcommand(
      "drive",
      "Run a stepped sine on a shaker through a JACK output port, each level brought to f0/m by "
      "a closed-loop sine controller on the accelerometer, with abort limits");
  command->add_option("--jack-server", o->drive.server, "JACK server name (default: the default)");
  command->add_option("--drive", o->drive.drive_port, "playback port of the shaker amplifier")
      ->required();
  command
      ->add_option("--acceleration", o->drive.acceleration_port,
                   "capture port of the table's accelerometer")
      ->required();
  command->add_option("--position", o->drive.position_port, "capture port of the mass's vibrometer")
      ->required();
  command
      ->add_option("--acceleration-scale", o->drive.acceleration_scale_m_s2,
                   "m/s² per unit of the accelerometer's port")
      ->check(positive_number())
      ->required();
  command
      ->add_option("--position-scale", o->drive.position_scale_m,
                   "m per unit of the vibrometer's port")
      ->check(positive_number())
      ->required();
  command->add_option("--mass", o->mass_kg, "the oscillator's mass, kg (level: f0/m)")
      ->check(positive_number())
      ->required();
  command->add_option("--levels", o->levels, "force levels f0 in N, A:STEP:B or A,B,...")
      ->required();
  command->add_option("--freq", o->frequency_hz, "frequency, Hz")
      ->check(positive_number())
      ->capture_default_str();
  command->add_option("--hold", o->hold_s, "seconds each level is held on target")
      ->check(CLI::Range(0.0, 86400.0))
      ->capture_default_str();
  command->add_option("--ramp", o->drive.controller.ramp_s, "ramp between levels, s")
      ->check(CLI::Range(0.0, 600.0))
      ->capture_default_str();
  command
      ->add_option("--settle-timeout", o->settle_timeout_s,
                   "seconds after the ramp for a level to come on target")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  add_drive_controller_options(*command, o->drive.controller);
  command->add_option("--events", o->events_path,
                      "append the drive's events to this JSON-lines log as they happen");
  command->add_option("--client-name", o->drive.client_name, "the drive's JACK client name")
      ->capture_default_str();
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
