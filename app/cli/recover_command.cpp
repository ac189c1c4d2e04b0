// `oscilab-cli recover REC`: a recording cut short (a power cut before its header was rewritten,
// a copy stopped short) made to open again with every whole sample it holds (docs/live.md).
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "app/cli/commands.h"
#include "daq/live/live_recorder.h"
#include "daq/recording/recording.h"

namespace oscilab::cli {
namespace {

void run_recover(const std::string& path) {
  try {
    const daq::Recording recording = daq::read_recording(path);
    std::printf("%s: whole (%lld samples per channel); nothing to recover\n", path.c_str(),
                static_cast<long long>(recording.sample_count()));
    return;
  } catch (const InputError& error) {
    // Only a file cut short is repaired; any other problem is the reader's to name.
    if (std::string(error.what()).find(": truncated: ") == std::string::npos) throw;
  }
  const std::int64_t kept = daq::recover_live_recording(path);
  const daq::Recording recording = daq::read_recording(path);
  std::printf(
      "%s: recovered %lld samples per channel (%.3f s); the sidecar's levels and invalid "
      "intervals end there\n",
      path.c_str(), static_cast<long long>(kept),
      static_cast<double>(kept) / recording.sidecar.sample_rate_hz);
}

}  // namespace

void add_recover_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "recover",
      "Make a recording cut short (a power cut, a copy stopped short) open again: every whole "
      "sample it holds is kept, the header rewritten to match and the sidecar's levels and "
      "invalid intervals clipped to them; a whole recording is left as it is");
  auto path = std::make_shared<std::string>();
  command->add_option("REC", *path, "a WAV, W64 or RF64 recording with its sidecar")->required();
  command->callback([path] { run_recover(*path); });
}

}  // namespace oscilab::cli
