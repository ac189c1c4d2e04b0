// `oscilab-cli import FILE --out REC`: an Oscilab recording (samples + sidecar) from any file the
// readers know, mapped by a sidecar beside FILE or given with --sidecar.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "app/cli/commands.h"
#include "daq/recording/recording.h"
#include "daq/recording/recording_summary.h"

namespace oscilab::cli {
namespace {

struct ImportOptions {
  std::string path;
  std::string sidecar_path;
  std::string out_path;
};

void run_import(const ImportOptions& options) {
  const daq::Recording recording =
      options.sidecar_path.empty()
          ? daq::read_recording(options.path)
          : daq::read_recording(options.path, daq::read_sidecar(options.sidecar_path));
  daq::write_recording(recording, options.out_path);
  std::cout << "Wrote " << options.out_path << " and " << daq::sidecar_path_for(options.out_path)
            << " (" << recording.sidecar.channels.size() << " channels, "
            << recording.sample_count() << " samples from " << recording.container << ")\n"
            << std::flush;
}

}  // namespace

void add_import_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "import",
      "Write an Oscilab recording from a file another program wrote (TDMS, UFF 58, MATLAB, HDF5, "
      "CSV, sound files), mapped by its sidecar");
  auto options = std::make_shared<ImportOptions>();
  command->add_option("FILE", options->path, "the file to import")->required();
  command->add_option("--sidecar", options->sidecar_path,
                      "the sidecar that maps FILE's signals (default: FILE's stem + .json)");
  command
      ->add_option("--out", options->out_path,
                   "recording to write (.wav .flac .w64 .rf64 .aiff .caf .csv); its sidecar goes "
                   "beside it")
      ->required();
  command->callback([options] { run_import(*options); });
}

}  // namespace oscilab::cli
