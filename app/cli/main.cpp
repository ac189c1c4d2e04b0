// oscilab-cli: every headless capability of Oscilab as a subcommand (contract §2).
#include <malloc.h>

#include <algorithm>
#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "app/cli/commands.h"

int main(int argc, char** argv) {
  // A run is batch work that allocates and frees record-sized arrays (megabytes) again and
  // again. By default glibc serves such blocks by a fresh mmap and returns freed heap to the
  // kernel, so every new array is touched page by page again (a page fault per 4 KiB). Kept in
  // the heap for the run instead: `analyze` on the two bundled records takes about 3 000 page
  // faults and 8 ms of CPU less (scripts/cli_speed.sh). Memory still returns to the system at
  // exit; its peak is unchanged.
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  CLI::App app{"Oscilab: measurement, simulation and identification of nonlinear oscillators",
               "oscilab-cli"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "oscilab-cli 0.1.0");
  oscilab::cli::add_model_command(app);
  oscilab::cli::add_simulate_command(app);
  oscilab::cli::add_info_command(app);
  oscilab::cli::add_import_command(app);
  oscilab::cli::add_analyze_command(app);
  oscilab::cli::add_hbm_command(app);
  oscilab::cli::add_fit_command(app);
  oscilab::cli::add_merge_command(app);
  oscilab::cli::add_diagnose_command(app);
  oscilab::cli::add_record_command(app);
  oscilab::cli::add_recover_command(app);
  oscilab::cli::add_stream_command(app);
  oscilab::cli::add_export_command(app);
  oscilab::cli::add_adaptive_test_command(app);
  oscilab::cli::add_drive_command(app);
  oscilab::cli::add_plant_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help and --version print and succeed; a wrong option is bad input like any other:
    // exit status 2 and one line (contracts.md §2).
    if (error.get_exit_code() == 0) return app.exit(error);
    std::string message = error.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::cerr << "oscilab-cli: " << message << " (see --help)\n";
    return 2;
  } catch (const oscilab::InputError& error) {
    std::cerr << "oscilab-cli: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "oscilab-cli: internal error: " << error.what() << '\n';
    return 3;
  }
  return 0;
}
