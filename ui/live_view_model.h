#pragma once

#include <complex>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/edc/level_tracker.h"
#include "daq/live/acquisition.h"
#include "daq/live/rig_source.h"
#include "daq/live/stream_event.h"
#include "ui/display_units.h"
#include "ui/time_window.h"

// The Qt-free logic of the live monitor (ui/live_monitor.h): which stretch of the history to
// show and how far back the operator scrolled, the fault counters and how alarming they are, the
// status and event-log texts, and the EDC points per well
// (the restoring-force slices and the cycle loop are analysis/rfs/). The widget only
// shows what these compute; GoogleTest checks them headless.
namespace oscilab::ui {

/// Where the live monitor's samples come from.
enum class LiveSourceKind { Rig, Replay, Network, Jack };

/// "rig" | "replay" | "network" | "jack".
std::string to_string(LiveSourceKind kind);

/// What the live monitor keeps in a session (MainWindow::live_settings), SI inside.
struct LiveSettings {
  LiveSourceKind source = LiveSourceKind::Rig;
  std::string replay_path;
  bool replay_loop = false;  // start the file again at its end
  int port = 5025;           // network: listen on 127.0.0.1:port (0: any free port)
  // JACK (sound card): the server (empty: the default), the capture ports of the base and the
  // mass channels, and the calibration sidecar (one channel per port, in that order).
  std::string jack_server;
  std::string jack_base_port = "system:capture_1";
  std::string jack_mass_port = "system:capture_2";
  std::string jack_calibration;
  double rig_f0_n = 0.5;  // the excitation "Set" applies
  double rig_frequency_hz = 9.0;
  double rig_step_n = 0.1;  // "Step +ΔN"
  bool rig_positive_well = true;
  double speed = 1.0;      // × real time for the rig and a replay; 0: as fast as possible
  double window_s = 10.0;  // traces shown
  daq::AlarmLimits alarms;

  nlohmann::json to_json() const;
  /// Fields missing from `json` keep their defaults (settings of an older session); a field of
  /// the wrong type or out of range throws InputError naming it, e.g. `live.window_s: -3`.
  static LiveSettings from_json(const nlohmann::json& json);
};

/// An unattended stepped sine for the rig (§3.2): the levels of analysis::stepped_levels from
/// `from_n` to `to_n` by `step_n` (the rule the CLI's --levels A:STEP:B follows too), in
/// daq::rig_schedule. Throws InputError unless 0 < from ≤ to, step > 0, hold > 0, lead-in ≥ 0,
/// frequency > 0.
std::vector<daq::ExcitationStep> stepped_schedule(double from_n, double to_n, double step_n,
                                                  double hold_s, double lead_in_s,
                                                  double frequency_hz);

/// The time window of the traces: it follows the stream (its right edge is the newest sample),
/// or, paused, stays where the operator left it while the acquisition goes on; a scroll bar moves
/// a paused window over the history kept (the last history_s of stream time).
class LiveTimeline {
 public:
  explicit LiveTimeline(double window_s = 10.0, double history_s = 600.0);

  void set_window_s(double window_s);  // clamped to [0.1 s, history_s]
  double window_s() const { return window_s_; }
  double history_s() const { return history_s_; }

  /// The stream advanced to `stream_time_s` (the newest sample): a following window moves.
  void advance(double stream_time_s);
  /// Pauses the view at the window shown now; resume() follows the stream again.
  void pause();
  void resume();
  bool following() const { return following_; }

  /// The right edge a paused view can take: from the oldest sample kept + window, to now.
  TimeWindow scroll_range() const;
  /// Pauses (if following) and moves the right edge to `end_s`, clamped to scroll_range().
  void scroll_to(double end_s);
  /// The window to draw. Paused, the history may have moved past it: it is then the oldest
  /// window still kept.
  TimeWindow view() const;

 private:
  double window_s_;
  double history_s_;
  double now_s_ = 0.0;
  bool following_ = true;
  double paused_end_s_ = 0.0;
};

/// How alarming a figure is: the status strip colours it (none, amber, red).
enum class Severity { Normal, Warning, Fault };

/// Fault counters of a live stream. The acquisition counts some only when it stops (gaps,
/// duplicates, reordering: its StreamMonitor's counters), so while it runs they are counted
/// here from the events it logged; `merge` takes the larger of the two counts of each.
struct FaultCounts {
  std::uint64_t gaps = 0, gap_samples = 0, duplicates = 0, reordered = 0, late = 0;
  std::uint64_t non_finite_samples = 0, saturated_samples = 0, overflowed_blocks = 0;
  std::uint64_t alarms = 0, errors = 0;

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
  /// alarms, errors (gaps counts samples: what the operator lost).
  static std::map<std::string, std::uint64_t> fault_values(const FaultCounts& counts);

 private:
  double fresh_s_;
  std::map<std::string, std::uint64_t> last_;
  std::map<std::string, double> rose_at_;
};

/// Samples per second of wall time, from the sample counter read at display rate: a running
/// figure over about the last `span_s`.
class ThroughputMeter {
 public:
  explicit ThroughputMeter(double span_s = 1.0) : span_s_(span_s) {}
  void reset() { readings_.clear(); }
  void add(double wall_s, std::uint64_t samples);
  /// Samples per second; 0 before two readings span a tenth of a second.
  double samples_per_s() const;

 private:
  double span_s_;
  std::deque<std::pair<double, std::uint64_t>> readings_;
};

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
/// (excluded), levels, last EDC latency, alarms. Fault counters take their severity from
/// `tracker`; a queue over 3/4 full is a Warning, a recorder error a Fault.
std::vector<StatusField> status_fields(const daq::AcquisitionStatus& status,
                                       const FaultCounts& faults, const FaultTracker& tracker,
                                       double now_s, double samples_per_s);

/// One row of the event log.
struct EventRow {
  std::string time;  // stream time "12.345 s", or "—" without one
  std::string kind;
  std::string text;  // the event's text, or a summary of its data
  Severity severity = Severity::Normal;
};
EventRow event_row(const daq::StreamEvent& event);

/// A measured EDC point (Fig. 10): the level's mean over its steady cycles with ±3σ bars.
struct EdcPoint {
  double f0_n = 0.0;
  double edc_j = 0.0;
  double error_j = 0.0;  // 3 edc_std_j: the bars of Fig. 10
  int cycles = 0;
  std::string flags;  // LevelResult::flags()
};

/// The EDC against f₀ of each well, level by level: finished levels in their well's series
/// (positive, negative, or other: cross-well or unknown), the level being filled apart.
struct EdcPlotData {
  std::vector<EdcPoint> positive, negative, other;
  std::optional<EdcPoint> current;
  std::string current_well;
  double max_f0_n = 0.0;  // over all points
};
EdcPlotData edc_plot_data(const std::vector<analysis::LevelResult>& levels,
                          const std::optional<analysis::LevelResult>& current);

/// Levels at which the model's EDC is drawn: 0.1 N to at least 2.7 N (the paper's range, §3.2)
/// or just past the largest level measured, in steps of 0.05 N.
std::vector<double> prediction_levels(double max_measured_f0_n);

/// The warning shown for the level being filled: "" when it is period-1 in one well, else its
/// flags in words ("not period-1 (sub-harmonic or non-periodic, Fig. 17)", "crosses wells").
std::string level_warning(const std::optional<analysis::LevelResult>& current);

/// The display unit of a live trace, kept while the values still read between 0.5 and 2000 in
/// it (so an axis does not flicker between mm and µm at a boundary), chosen afresh otherwise.
DisplayUnit sticky_display_unit(const std::optional<DisplayUnit>& current,
                                const std::string& si_unit, double max_abs);

/// A value axis that follows live data without jitter: it grows at once to hold [lo, hi] with a
/// 10 % margin, and shrinks to it only when the data fill less than 40 % of the range.
struct AxisRange {
  double lo = -1.0, hi = 1.0;
};
AxisRange follow_range(std::optional<AxisRange> current, double data_lo, double data_hi);

}  // namespace oscilab::ui
