#include "ui/live/live_source_request.h"

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "daq/recording/sidecar.h"

namespace oscilab::ui {

LiveSourceRequest live_source_request(const LiveSettings& s,
                                      const std::vector<daq::ExcitationStep>& schedule,
                                      std::optional<double> duration_s) {
  LiveSourceRequest request;
  daq::SourceOptions& o = request.options;
  o.what = "source";
  o.rig.well = analysis::well_of(s.rig_positive_well);
  o.rig.frequency_hz = s.rig_frequency_hz;
  o.rig.speed = o.replay.speed = s.speed;
  o.rig.schedule = schedule;
  o.rig.duration_s = duration_s;
  o.replay.loop = s.replay_loop;
  switch (s.source) {
    case LiveSourceKind::Rig:
      request.spec = "rig";
      break;
    case LiveSourceKind::Replay:
      if (s.replay_path.empty()) throw InputError("replay: choose a recording to replay (\u2026)");
      request.spec = "file:" + s.replay_path;
      break;
    case LiveSourceKind::Network:
      request.spec = "net:127.0.0.1:" + std::to_string(s.port);
      break;
    case LiveSourceKind::Jack:
      if (s.jack_calibration.empty()) {
        throw InputError("JACK: choose the calibration sidecar (base and mass channels)");
      }
      request.spec = "jack:" + s.jack_base_port + "," + s.jack_mass_port;
      o.jack.server = s.jack_server;
      o.jack.calibration = daq::read_sidecar(s.jack_calibration);
      break;
  }
  return request;
}

}  // namespace oscilab::ui
