#pragma once

#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "daq/live/sample_source.h"

namespace oscilab::cli {

/// How `record` and `stream` make a live source from `--source rig|net:HOST:PORT|file:REC`
/// (record) or `REC|rig` (stream), with the rig's and the replay's options.
struct LiveSourceOptions {
  std::string model = "paper";
  std::string well = "positive";
  double freq_hz = 9.0;
  std::string levels;  // A:STEP:B: an unattended stepped sine (empty: the rig rests)
  double hold_s = 10.0;
  double lead_in_s = 2.5;
  std::uint64_t seed = 1;
  double speed = 1.0;   // × real time; 0: as fast as possible
  std::string sidecar;  // net: the layout to expect (a sidecar JSON)
  std::optional<double> duration_s;
};

/// Adds the options above to a command (`--sidecar` only where a network source is possible).
void add_live_source_options(CLI::App& command, LiveSourceOptions& options, bool net);

/// The source `spec` names: "rig", "file:REC" or a bare REC path (replay), "net:HOST:PORT"
/// (listen). Throws InputError naming the option or the file.
std::unique_ptr<daq::SampleSource> make_live_source(const std::string& spec,
                                                    const LiveSourceOptions& options,
                                                    bool allow_net);

}  // namespace oscilab::cli
