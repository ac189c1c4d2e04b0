#pragma once

#include <string>
#include <vector>

#include "daq/recording/opened_recording.h"
#include "ui/display_units.h"

namespace oscilab::ui {

/// What the plot cursor reads: the sample nearest to the cursor time and every channel's value
/// there. Qt-free: the record view only shows it.
struct CursorReadout {
  Eigen::Index sample = -1;       // -1: nothing to read (empty recording)
  double t_s = 0.0;               // time of `sample`, = sample / sample_rate_hz
  std::vector<double> values_si;  // one per channel, SI
};

/// The readout at the sample nearest to `t_s`, clamped to the recording, read where its samples
/// live (nothing when its file can no longer be read). The cursor snaps to a sample rather than
/// interpolating, so that it shows measured values only.
CursorReadout read_cursor(const daq::OpenedRecording& recording, double t_s);

/// One line of text for a readout, e.g. "t = 1.234 s   base_acc =  2.500 m/s²   y = -3.100 mm",
/// with each channel in its display unit, right-aligned to a width that fits the channel's
/// largest value, and t to the sampling resolution.
std::string format_readout(const CursorReadout& readout, const daq::OpenedRecording& recording,
                           const std::vector<DisplayUnit>& units);

}  // namespace oscilab::ui
