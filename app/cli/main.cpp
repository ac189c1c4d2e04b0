// oscilab-cli: every headless capability of Oscilab as a subcommand (contract §2).
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "app/cli/commands.h"

int main(int argc, char** argv) {
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
  oscilab::cli::add_stream_command(app);
  oscilab::cli::add_export_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  } catch (const oscilab::InputError& error) {
    std::cerr << "oscilab-cli: " << error.what() << '\n';
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "oscilab-cli: internal error: " << error.what() << '\n';
    return 3;
  }
  return 0;
}
