#include "app/cli/live_source_options.h"

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "app/cli/option_parsing.h"
#include "daq/live/source_factory.h"
#include "daq/sources/rig_source.h"

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
                     "net: the layout to expect (a sidecar JSON); senders that differ are refused. "
                     "jack: the calibration, one channel per port in port order (unit, scale, "
                     "full_scale_v, ac_coupling_hz, range)");
  command.add_option("--jack-server", o.jack_server,
                     "jack: the JACK server's name (default: the default server)");
  command.add_option("--jack-client", o.jack_client, "jack: the client name to register")
      ->capture_default_str();
  command.add_option("--rate", o.rate_hz,
                     "jack: the analysis rate [Hz] the sound card's samples are resampled to "
                     "(default: the sidecar's sample_rate_hz)");
}

std::unique_ptr<daq::SampleSource> make_live_source(const std::string& spec,
                                                    const LiveSourceOptions& o, bool allow_net) {
  const daq::SourceKind kind = daq::source_kind(spec);
  if (!allow_net && (kind == daq::SourceKind::Network || kind == daq::SourceKind::Jack)) {
    throw InputError("--source " + spec.substr(0, spec.find(':') + 1) +
                     " is for record; stream sends to one");
  }
  daq::SourceOptions source;
  source.rig.model = o.model;
  source.rig.well = analysis::well_from_string(o.well);
  source.rig.seed = o.seed;
  source.rig.frequency_hz = o.freq_hz;
  source.rig.speed = source.replay.speed = o.speed;
  source.rig.duration_s = o.duration_s;
  if (kind == daq::SourceKind::Rig && !o.levels.empty()) {
    const std::vector<double> levels = parse_levels(o.levels, "--levels");
    if (!(o.hold_s > 0) || !(o.lead_in_s >= 0)) {
      throw InputError("--hold must be positive and --lead-in >= 0");
    }
    source.rig.schedule = daq::rig_schedule(levels, o.hold_s, o.lead_in_s, o.freq_hz);
  }
  if (kind == daq::SourceKind::Network && !o.sidecar.empty()) {
    source.network.expected = daq::read_sidecar(o.sidecar);
  }
  if (kind == daq::SourceKind::Jack) {
    if (o.sidecar.empty()) {
      throw InputError("--source " + spec +
                       ": give the calibration with --sidecar CAL.json (one channel per port)");
    }
    source.jack.calibration = daq::read_sidecar(o.sidecar);
    source.jack.server = o.jack_server;
    source.jack.client = o.jack_client;
    source.jack.analysis_rate_hz = o.rate_hz;
  }
  return daq::make_source(spec, source);
}

}  // namespace oscilab::cli
