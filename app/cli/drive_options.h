#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "daq/drive/sine_controller.h"

namespace oscilab::cli {

/// The sine controller's options a command that drives a shaker offers (`drive`,
/// `adaptive-test --drive`): --tolerance, --gain-guess, --max-drive, --max-acceleration,
/// --max-travel.
void add_drive_controller_options(CLI::App& command, daq::SineControllerOptions& controller);

/// The option that set the limit an abort crossed ("--max-drive", ...; the inputs' options for
/// a lost input), followed by the abort in words: one line for an InputError.
std::string drive_abort_line(const daq::DriveEvent& event,
                             const daq::SineControllerOptions& controller,
                             const std::string& inputs_option);

}  // namespace oscilab::cli
