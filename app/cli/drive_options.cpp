#include "app/cli/drive_options.h"

#include "app/cli/option_parsing.h"

namespace oscilab::cli {

void add_drive_controller_options(CLI::App& command, daq::SineControllerOptions& controller) {
  command
      .add_option("--tolerance", controller.tolerance,
                  "on target: the first harmonic of b̈ within this fraction of f0/m")
      ->check(CLI::Range(1e-4, 0.49))
      ->capture_default_str();
  command
      .add_option("--gain-guess", controller.gain_guess_m_s2_per_fs,
                  "first guess of the table acceleration per unit of drive, m/s² (err high)")
      ->check(positive_number())
      ->capture_default_str();
  command
      .add_option("--max-drive", controller.max_drive_fs,
                  "abort: drive amplitude limit, fraction of full scale")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  command
      .add_option("--max-acceleration", controller.max_table_acceleration_m_s2,
                  "abort: |b̈| limit, m/s²")
      ->check(positive_number())
      ->capture_default_str();
  command
      .add_option("--max-travel", controller.max_travel_m,
                  "abort: limit of |z| from the rest position, m")
      ->check(positive_number())
      ->capture_default_str();
}

std::string drive_abort_line(const daq::DriveEvent& event,
                             const daq::SineControllerOptions& controller,
                             const std::string& inputs_option) {
  std::string option = inputs_option;
  switch (event.abort) {
    case daq::DriveAbort::DriveLimit:
      option = "--max-drive";
      break;
    case daq::DriveAbort::TableAccelerationLimit:
      option = "--max-acceleration";
      break;
    case daq::DriveAbort::TravelLimit:
      option = "--max-travel";
      break;
    case daq::DriveAbort::InputLost:
    case daq::DriveAbort::None:
      break;
  }
  return option + ": " + daq::drive_abort_text(event, controller);
}

}  // namespace oscilab::cli
