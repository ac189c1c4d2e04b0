#pragma once

#include <string>
#include <vector>

namespace oscilab::analysis {

/// The forcing levels of a stepped sine from `from_n` to `to_n` in steps of `step_n`: from,
/// from + step, … up to `to` inclusive when (to − from)/step is whole (within 1e-9 of a step, so
/// that 0.2 to 2.7 by 0.1 gives 26 levels despite rounding), otherwise up to the last whole step
/// below `to` (never beyond it). The one rule the simulation, the CLI and the app's rig share.
///
/// Throws InputError naming `what` (e.g. "--levels") unless the values are finite, from ≥ 0,
/// step > 0, to ≥ from, and the levels number at most 10 000.
std::vector<double> stepped_levels(double from_n, double step_n, double to_n,
                                   const std::string& what);

}  // namespace oscilab::analysis
