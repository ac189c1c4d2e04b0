#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "daq/live/acquisition.h"
#include "daq/sources/stream_event.h"

// The fault counters of a live stream and how alarming each is.

namespace oscilab::ui {

/// How alarming a figure is: the status strip colours it (none, amber, red).
enum class Severity { Normal, Warning, Fault };

/// Fault counters of a live stream. The acquisition counts some only when it stops (gaps,
/// duplicates, reordering: its StreamMonitor's counters), so while it runs they are counted
/// here from the events it logged; `merge` takes the larger of the two counts of each.
struct FaultCounts {
  std::uint64_t gaps = 0, gap_samples = 0, duplicates = 0, reordered = 0, late = 0;
  std::uint64_t non_finite_samples = 0, saturated_samples = 0, overflowed_blocks = 0;
  std::uint64_t alarms = 0, errors = 0;
  /// A sound card's faults (JACK): xruns, server losses, ports disconnected, rate changes.
  std::uint64_t sound_card = 0;

  /// Adds what one logged event says (gap: data.samples; non-finite, saturated: data.samples;
  /// overflow: data.blocks when given, else 1; alarm, error, malformed-frame,
  /// layout-mismatch: one each).
  void add(const daq::StreamEvent& event);
  /// The larger of this and the acquisition's own count, field by field.
  FaultCounts merged(const daq::AcquisitionStatus& status) const;
};

/// Remembers when each fault counter last rose (wall time, s): a counter is a Fault (red) for
/// `fresh_s` after it rose, then a Warning (amber) while it is non-zero.
class FaultTracker {
 public:
  explicit FaultTracker(double fresh_s = 5.0) : fresh_s_(fresh_s) {}
  void reset() { last_.clear(), rose_at_.clear(); }
  /// Feeds the counts at wall time `now_s`.
  void update(const FaultCounts& counts, double now_s);
  /// Severity of counter `name` (a key of fault_values) at `now_s`.
  Severity severity(const std::string& name, double now_s) const;

  /// The counters by name: gaps, duplicates, reordered, late, nan, saturated, overflow,
  /// alarms, errors, card (gaps counts samples: what the operator lost).
  static std::map<std::string, std::uint64_t> fault_values(const FaultCounts& counts);

 private:
  double fresh_s_;
  std::map<std::string, std::uint64_t> last_;
  std::map<std::string, double> rose_at_;
};

}  // namespace oscilab::ui
