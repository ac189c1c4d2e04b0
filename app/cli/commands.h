#pragma once

#include <CLI/CLI.hpp>

namespace oscilab::cli {

// Each subcommand lives in its own file and registers itself here (contract §2). A command's
// callback throws oscilab::InputError for bad input; main() prints it as one line and exits 2.
void add_model_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_import_command(CLI::App& app);
void add_analyze_command(CLI::App& app);
void add_hbm_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_merge_command(CLI::App& app);
void add_diagnose_command(CLI::App& app);
void add_record_command(CLI::App& app);
void add_recover_command(CLI::App& app);
void add_stream_command(CLI::App& app);
void add_export_command(CLI::App& app);
void add_adaptive_test_command(CLI::App& app);
void add_drive_command(CLI::App& app);
void add_plant_command(CLI::App& app);

}  // namespace oscilab::cli
