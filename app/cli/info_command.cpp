// `oscilab-cli info FILE`: what a recording holds (contract §2); for a file without a sidecar,
// what the file holds and a drafted sidecar to complete.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "app/cli/commands.h"
#include "daq/recording/format_reader.h"
#include "daq/recording/recording.h"
#include "daq/recording/recording_summary.h"
#include "daq/recording/sidecar_draft.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::cli {
namespace {

struct InfoOptions {
  std::string path;
  std::string draft_path;
  bool contents = false;
};

void write_draft(const daq::SidecarDraft& draft, const std::string& path) {
  if (std::filesystem::exists(path)) {
    throw InputError(path + ": exists; the draft is not written over a file");
  }
  daq::TemporaryFile file(path);
  {
    std::ofstream out(file.path());
    out << draft.sidecar.dump(2) << '\n';
    if (!out) throw InputError(path + ": cannot write");
  }
  file.commit();
}

void run_info(const InfoOptions& options) {
  const daq::FormatReader& format = daq::format_for_file(options.path);
  const bool has_sidecar = std::filesystem::exists(daq::sidecar_path_for(options.path));
  if (has_sidecar && options.draft_path.empty()) {
    if (options.contents) {
      std::cout << daq::describe_file_contents(options.path, format.describe(options.path));
    }
    std::cout << daq::describe_recording(daq::read_recording(options.path)) << std::flush;
    return;
  }
  const daq::FileContents contents = format.describe(options.path);
  std::cout << daq::describe_file_contents(options.path, contents);
  const daq::SidecarDraft draft = daq::draft_sidecar(contents);
  if (!has_sidecar) {
    std::cout << "No sidecar (" << daq::sidecar_path_for(options.path)
              << "): it says which signals are the base and the mass, their calibration and the "
                 "rate. A draft to check and complete:\n"
              << draft.sidecar.dump(2) << "\n";
  }
  for (const std::string& note : draft.notes) std::cout << "  note: " << note << "\n";
  if (!options.draft_path.empty()) {
    write_draft(draft, options.draft_path);
    std::cout << "Draft written to " << options.draft_path
              << (draft.complete ? " (a valid sidecar; check the guesses)"
                                 : " (incomplete: see the notes)")
              << "\n";
  }
  std::cout << std::flush;
}

}  // namespace

void add_info_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "info",
      "Show what a recording holds: channels with units, rate, duration, excitation; for a file "
      "without a sidecar, the signals it holds and a drafted sidecar");
  auto options = std::make_shared<InfoOptions>();
  command
      ->add_option("FILE", options->path,
                   "a recording (WAV, FLAC, W64, RF64, AIFF, CAF, CSV, NI TDMS, UFF 58/58b, "
                   "MATLAB .mat, HDF5), with or without its JSON sidecar of the same stem")
      ->required();
  command->add_flag("--contents", options->contents,
                    "also list the signals the file holds when it has a sidecar");
  command->add_option("--draft-sidecar", options->draft_path,
                      "write the drafted sidecar to this JSON file (never over an existing one)");
  command->callback([options] { run_info(*options); });
}

}  // namespace oscilab::cli
