// `oscilab-cli info REC`: what a recording holds (contract §2).
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "app/cli/commands.h"
#include "daq/recording/recording.h"
#include "daq/recording/recording_summary.h"

namespace oscilab::cli {

void add_info_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "info", "Show what a recording holds: channels with units, rate, duration, excitation");
  auto path = std::make_shared<std::string>();
  command
      ->add_option("REC", *path,
                   "Recording: a sound file (WAV, FLAC, W64, RF64, AIFF, CAF) or a CSV, with its "
                   "JSON sidecar of the same stem")
      ->required();
  command->callback(
      [path] { std::cout << daq::describe_recording(daq::read_recording(*path)) << std::flush; });
}

}  // namespace oscilab::cli
