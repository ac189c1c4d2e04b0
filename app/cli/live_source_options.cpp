#include "app/cli/live_source_options.h"

#include "analysis/common/input_error.h"
#include "analysis/model/model_json.h"
#include "app/cli/option_parsing.h"
#include "daq/live/net_source.h"
#include "daq/live/replay_source.h"
#include "daq/live/rig_source.h"
#include "daq/live/tcp_socket.h"

namespace oscilab::cli {

void add_live_source_options(CLI::App& command, LiveSourceOptions& o, bool net) {
  command.add_option("--model", o.model, "rig: paper | illustrative | MODEL.json")
      ->capture_default_str();
  command.add_option("--well", o.well, "rig: positive | negative (the well it starts in)")
      ->check(CLI::IsMember({"positive", "negative"}))
      ->capture_default_str();
  command.add_option("--freq", o.freq_hz, "rig: excitation frequency [Hz]")->capture_default_str();
  command.add_option("--levels", o.levels,
                     "rig: run a stepped sine unattended, amplitudes A:STEP:B [N] (default: the "
                     "rig rests until told)");
  command.add_option("--hold", o.hold_s, "rig: seconds per level")->capture_default_str();
  command.add_option("--lead-in", o.lead_in_s, "rig: seconds at rest before the first level")
      ->capture_default_str();
  command.add_option("--seed", o.seed, "rig: seed of the sensor noise and creep")
      ->capture_default_str();
  command
      .add_option("--speed", o.speed,
                  "rig and replay: x real time (0: as fast as the consumer takes it)")
      ->capture_default_str();
  if (!net) return;
  command.add_option("--sidecar", o.sidecar,
                     "net: the layout to expect (a sidecar JSON); senders that differ are refused");
}

std::unique_ptr<daq::SampleSource> make_live_source(const std::string& spec,
                                                    const LiveSourceOptions& o, bool allow_net) {
  if (spec == "rig") {
    daq::RigSource::Options rig;
    rig.rig.positive_well = o.well == "positive";
    rig.rig.seed = o.seed;
    rig.frequency_hz = o.freq_hz;
    rig.speed = o.speed;
    rig.duration_s = o.duration_s;
    if (!o.levels.empty()) {
      const std::vector<double> levels = parse_levels(o.levels, "--levels");
      if (!(o.hold_s > 0) || !(o.lead_in_s >= 0)) {
        throw InputError("--hold must be positive and --lead-in >= 0");
      }
      rig.schedule = daq::rig_schedule(levels, o.hold_s, o.lead_in_s, o.freq_hz);
    }
    return std::make_unique<daq::RigSource>(analysis::model_from_spec(o.model), rig);
  }
  if (spec.rfind("net:", 0) == 0) {
    if (!allow_net) throw InputError("--source net: is for record; stream sends to one");
    daq::NetSource::Options net;
    daq::parse_host_port(spec.substr(4), "--source", net.host, net.port);
    if (!o.sidecar.empty()) net.expected = daq::read_sidecar(o.sidecar);
    return std::make_unique<daq::NetSource>(net);
  }
  const std::string path = spec.rfind("file:", 0) == 0 ? spec.substr(5) : spec;
  if (path.empty()) throw InputError("--source file: needs a recording path");
  daq::ReplaySource::Options replay;
  replay.speed = o.speed;
  return std::make_unique<daq::ReplaySource>(path, replay);
}

}  // namespace oscilab::cli
