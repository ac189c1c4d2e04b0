#pragma once

#include <nlohmann/json.hpp>

#include "daq/drive/sine_controller.h"

namespace oscilab::daq {

/// A drive event as one line of an event log: {"event": "drive", "t_s", "state", "abort",
/// "target_m_s2", "frequency_hz", "measured_m_s2", "drive_fs", "cycles", "value"}; t_s is the
/// controller's time (its sample count over the rate). "abort" and "value" only on an abort,
/// "cycles" only on target.
nlohmann::json drive_event_json(const DriveEvent& event, double sample_rate_hz);

}  // namespace oscilab::daq
