#pragma once

#include <string>
#include <vector>

#include "daq/recording/opened_recording.h"

namespace oscilab::ui {

/// A unit to show SI values in: display value = SI value / si_per_unit. Qt-free so that the
/// choice is unit tested headless; widgets only apply it.
struct DisplayUnit {
  std::string symbol;        // UTF-8, e.g. "mm", "µm", "m/s²"
  double si_per_unit = 1.0;  // e.g. 1e-3 for mm
  int decimals = 3;          // readout decimals: 4 significant digits at the largest value

  double to_display(double value_si) const { return value_si / si_per_unit; }
};

/// The SI unit in which samples_si holds a quantity: "m/s^2", "m/s", "m" or "N".
std::string si_unit_of(daq::Quantity quantity);

/// Chooses an SI-prefixed display unit for values of SI unit `si_unit` whose largest magnitude
/// is `max_abs` (in that SI unit), so that the numbers on the axis are neither tiny nor huge:
///
/// - "m" → m, mm, µm or nm; "m/s" → m/s, mm/s or µm/s; "N" → kN, N, mN or µN: the largest
///   prefix with which max_abs reads at least 1 (4 mm, 20 µm, 350 mN).
/// - "m/s^2" stays m/s² down to 0.1 m/s² (how shaker levels are quoted), below it mm/s².
/// - Zero, non-finite max_abs or an unknown unit: the unit itself, unprefixed ("V" stays "V").
///
/// "^2" is written as "²" in the symbol. `decimals` gives the largest value 4 significant digits
/// (4.3 mm → 3 decimals, 250 mN → 1), so that a readout keeps one resolution across the channel.
DisplayUnit choose_display_unit(const std::string& si_unit, double max_abs);

/// One display unit per channel of `recording`, chosen from each channel's largest |sample|.
std::vector<DisplayUnit> choose_display_units(const daq::OpenedRecording& recording);

/// `value_si` in `unit` with the unit's decimals and its symbol, e.g. "-3.142 mm".
std::string format_value(double value_si, const DisplayUnit& unit);

}  // namespace oscilab::ui
