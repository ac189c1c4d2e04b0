#pragma once

#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "daq/sources/sample_source.h"

namespace oscilab::cli {

/// The options `record` and `stream` give a live source made from `--source
/// rig|net:HOST:PORT|jack:PORT,PORT[,...]|file:REC` (record) or `REC|rig` (stream); the source
/// itself comes from daq::make_source.
struct LiveSourceOptions {
  std::string model = "paper";
  std::string well = "positive";
  double freq_hz = 9.0;
  std::string levels;  // A:STEP:B: an unattended stepped sine (empty: the rig rests)
  double hold_s = 10.0;
  double lead_in_s = 2.5;
  std::uint64_t seed = 1;
  double speed = 1.0;   // × real time; 0: as fast as possible
  std::string sidecar;  // net: the layout to expect; jack: the calibration (a sidecar JSON)
  std::optional<double> duration_s;
  std::string jack_server;              // empty: the default server
  std::string jack_client = "oscilab";  // the JACK client name asked for
  std::optional<double> rate_hz;        // jack: the analysis rate (default: the sidecar's)
};

/// Adds the options above to a command (`--sidecar` and the JACK options only where a network or
/// JACK source is possible: `record`).
void add_live_source_options(CLI::App& command, LiveSourceOptions& options, bool net);

/// The source `spec` names: "rig", "file:REC" or a bare REC path (replay), "net:HOST:PORT"
/// (listen), "jack:PORT_BASE,PORT_MASS[,...]" (capture). Throws InputError naming the option,
/// the file, the server or the port.
std::unique_ptr<daq::SampleSource> make_live_source(const std::string& spec,
                                                    const LiveSourceOptions& options,
                                                    bool allow_net);

}  // namespace oscilab::cli
