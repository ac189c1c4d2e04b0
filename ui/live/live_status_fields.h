#pragma once

#include <string>
#include <vector>

#include "daq/live/acquisition.h"
#include "ui/live/live_faults.h"

namespace oscilab::ui {

/// One figure of the status strip.
struct StatusField {
  std::string key;    // "rate", "time", "samples", "gaps", "duplicates", ...
  std::string label;  // what the strip writes before it, e.g. "gaps"
  std::string value;  // e.g. "32 samples"
  Severity severity = Severity::Normal;
  std::string tooltip;
};

/// The status strip: rate (and × real time), stream time, samples, gaps, duplicates, reordered,
/// NaN, saturated, overflow, queue fill / capacity, recording (and seconds recorded), cycles
/// (excluded), levels, last EDC latency, alarms, errors, a sound card's faults (xruns, server
/// losses, ports disconnected, rate changes; the rest of its counters in the tooltip). Fault
/// counters take their severity from `tracker`; a queue over 3/4 full is a Warning, a recorder
/// error a Fault.
std::vector<StatusField> status_fields(const daq::AcquisitionStatus& status,
                                       const FaultCounts& faults, const FaultTracker& tracker,
                                       double now_s, double samples_per_s);

}  // namespace oscilab::ui
