#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "daq/live/acquisition.h"
#include "daq/sources/rig_source.h"

// What the live monitor keeps in a session: the source, its fields and the rig's excitation,
// and the rig's unattended stepped sine.

namespace oscilab::ui {

/// Where the live monitor's samples come from.
enum class LiveSourceKind { Rig, Replay, Network, Jack };

/// "rig" | "replay" | "network" | "jack".
std::string to_string(LiveSourceKind kind);

/// What the live monitor keeps in a session (LiveMonitor::session_settings), SI inside.
struct LiveSettings {
  LiveSourceKind source = LiveSourceKind::Rig;
  std::string replay_path;
  bool replay_loop = false;  // start the file again at its end
  int port = 5025;           // network: listen on 127.0.0.1:port (0: any free port)
  // JACK (sound card): the server (empty: the default), the capture ports of the base and the
  // mass channels, and the calibration sidecar (one channel per port, in that order).
  std::string jack_server;
  std::string jack_base_port = "system:capture_1";
  std::string jack_mass_port = "system:capture_2";
  std::string jack_calibration;
  double rig_f0_n = 0.5;  // the excitation "Set" applies
  double rig_frequency_hz = 9.0;
  double rig_step_n = 0.1;  // "Step +ΔN"
  bool rig_positive_well = true;
  double speed = 1.0;      // × real time for the rig and a replay; 0: as fast as possible
  double window_s = 10.0;  // traces shown
  daq::AlarmLimits alarms;

  nlohmann::json to_json() const;
  /// Fields missing from `json` keep their defaults (settings of an older session); a field of
  /// the wrong type or out of range throws InputError naming it, e.g. `live.window_s: -3`.
  static LiveSettings from_json(const nlohmann::json& json);
};

/// An unattended stepped sine for the rig (§3.2): the levels of analysis::stepped_levels from
/// `from_n` to `to_n` by `step_n` (the rule the CLI's --levels A:STEP:B follows too), in
/// daq::rig_schedule. Throws InputError unless 0 < from ≤ to, step > 0, hold > 0, lead-in ≥ 0,
/// frequency > 0.
std::vector<daq::ExcitationStep> stepped_schedule(double from_n, double to_n, double step_n,
                                                  double hold_s, double lead_in_s,
                                                  double frequency_hz);

}  // namespace oscilab::ui
