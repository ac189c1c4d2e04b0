#include "daq/drive/drive_event_json.h"

namespace oscilab::daq {

nlohmann::json drive_event_json(const DriveEvent& event, double sample_rate_hz) {
  nlohmann::json line = {
      {"event", "drive"},
      {"t_s", static_cast<double>(event.sample) / sample_rate_hz},
      {"state", drive_state_name(event.state)},
      {"target_m_s2", event.target_m_s2},
      {"frequency_hz", event.frequency_hz},
      {"measured_m_s2", event.measured_m_s2},
      {"drive_fs", event.drive_fs},
  };
  if (event.state == DriveState::OnTarget) line["cycles"] = event.cycles;
  if (event.state == DriveState::Aborted) {
    line["abort"] = drive_abort_name(event.abort);
    line["value"] = event.value;
  }
  return line;
}

}  // namespace oscilab::daq
