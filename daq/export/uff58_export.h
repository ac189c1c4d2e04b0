#pragma once

#include <string>

#include "daq/recording/recording.h"

namespace oscilab::daq {

/// Where the channels sit in a modal-test geometry: the node and direction that record 6 of each
/// dataset 58 names. The rig has two points on one axis: the table and the moving mass.
struct Uff58Options {
  int base_node = 1;  // the shaking table: channels with role base, and the reference DOF
  int mass_node = 2;  // the moving mass: roles mass, relative (z = y − b) and force
  int direction = 1;  // +X translation (1..6 = ±X, ±Y, ±Z translation, rotation; 0 scalar)
  /// ID line 3, the creation date and time "DD-MMM-YY HH:MM:SS" (general note of record 3);
  /// empty: now, local time.
  std::string created;
};

/// Writes a recording as a Universal File: a dataset 164 (units: SI, factors 1) followed by one
/// dataset 58 (function at nodal DOF) per channel, in channel order, each a time response
/// (function type 1) of real double-precision ordinates (data type 4) on an even abscissa from
/// 0 s in steps of 1 / sample_rate_hz, ASCII, in the standard fields of the I-DEAS/SDRL
/// definition: record 6 Format(2(I5,I10),2(1X,10A1,I10,I4)), record 7 Format(3I10,3E13.5),
/// records 8–11 Format(I10,3I5,2(1X,20A1)), data 4E20.12, every line at most 80 characters,
/// each dataset between lines "    -1".
///
/// Record 8 is time (specific data type 17, unit "s"); record 9 the channel's quantity in SI:
/// acceleration 12 "m/s^2", velocity 11 "m/s", displacement 8 "m", force 13 (excitation force)
/// "N"; records 10 and 11 are unused (0). Unit exponents are 0: the specific data types imply
/// them (Addendum A of the definition). ID line 1 names the channel, 2 the recording's file, 3 the
/// date, 4 the excitation, 5 the sensor. Values print with 12 significant digits (relative rounding
/// ≤ 5e-12) and the abscissa increment with 7 (exact for 512 Hz: 1.953125E-03).
///
/// UFF has no missing value: a non-finite sample throws InputError naming the channel and the
/// time (the MAT export keeps NaN gaps). The file is written under a temporary name and renamed
/// into place. Throws InputError naming `path` on any failure.
void write_recording_uff58(const Recording& recording, const std::string& path,
                           const Uff58Options& options = {});

}  // namespace oscilab::daq
