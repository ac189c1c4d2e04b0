#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "analysis/edc/cycle_fit.h"
#include "analysis/edc/level_tracker.h"
#include "analysis/pipeline/pipeline_settings.h"
#include "daq/live/alarm_monitor.h"
#include "daq/live/history_ring.h"
#include "daq/sources/block_queue.h"
#include "daq/sources/sample_source.h"
#include "daq/sources/stream_event.h"

namespace oscilab::daq {

class LiveRecorder;

struct AcquisitionOptions {
  analysis::PipelineSettings settings;  // the same analysis as offline
  std::size_t queue_blocks = 256;       // source → acquisition queue (8 s of 16-row blocks)
  int reorder_window_blocks = 8;        // StreamMonitor
  double history_s = 600.0;             // traces kept for scroll-back (10 minutes, 256 MB at most)
  /// Derived traces (b, z, ż, R) by the live zero-phase filters (StreamingIntegrator); they
  /// lag the measured channels by this much. Off: only measured channels and f.
  bool derived_signals = true;
  double derived_latency_s = 2.0;
  std::optional<double> excitation_freq_hz;  // overrides the layout's; none there: EDC off
  /// How often at most a recording's samples and event log go to the disk (LiveRecorder).
  std::chrono::milliseconds recorder_sync_interval{1000};
  AlarmLimits alarms;
};

/// A snapshot of the live chain, for the status bar and the CLI.
struct AcquisitionStatus {
  std::string source;
  bool running = false;
  bool finished = false;  // the source ended and everything it sent was processed
  bool layout_known = false;
  double sample_rate_hz = 0.0;
  double stream_time_s = 0.0;  // time of the last sample processed
  std::uint64_t samples = 0, blocks = 0;
  std::uint64_t gaps = 0, gap_samples = 0, lost_blocks = 0, duplicates = 0, reordered = 0, late = 0,
                discontinuities = 0;
  std::uint64_t non_finite_samples = 0, saturated_samples = 0;
  std::uint64_t overflowed_blocks = 0;
  NetworkCounters network;  // a network receiver's (zero for other sources)
  JackCounters jack;        // a sound card's (zero for other sources)
  std::size_t queue_fill = 0, queue_capacity = 0;
  bool recording = false;
  std::string recording_path;
  std::uint64_t recorded_samples = 0;
  std::string recorder_error;
  long cycles = 0, excluded_cycles = 0;
  std::size_t levels = 0;
  std::string edc_message;            // why there is no live EDC, when there is none
  double edc_latency_s = 0.0;         // last cycle: arrival of its first sample → its EDC
  double edc_latency_median_s = 0.0;  // over the last 10 000 cycles
  double edc_latency_max_s = 0.0;
  std::uint64_t alarms = 0;
};

/// The live chain of one source: its thread delivers blocks into a lock-free queue; the
/// acquisition thread takes them in order (StreamMonitor: gaps, duplicates, reordering),
/// checks every sample (SampleChecker: non-finite, saturation), records them (LiveRecorder),
/// calibrates them to SI, feeds the measurement pipeline (the same per-cycle EDC as offline,
/// excluding every cycle that touches a fault), derives b, z, ż and R (DerivedSignals), watches
/// the alarm limits (AlarmMonitor) and keeps the last minutes of traces for display
/// (HistoryRing). Every fault is counted (status), logged (events) and recorded (invalid
/// intervals).
///
/// Thread-safety: every public method may be called from any one controlling thread (the UI or
/// the CLI). The acquisition thread works on a block without a lock and then publishes what it
/// found under the acquisition's mutex once per block; the traces go to the history ring under
/// the ring's own lock, so a display thinning minutes of traces never holds the acquisition up.
class Acquisition {
 public:
  Acquisition(std::unique_ptr<SampleSource> source, AcquisitionOptions options);
  ~Acquisition();
  Acquisition(const Acquisition&) = delete;
  Acquisition& operator=(const Acquisition&) = delete;

  /// Starts the source and the acquisition thread.
  void start();
  /// Stops the source, processes what it delivered, closes the levels and the recording.
  void stop();
  bool finished() const { return finished_.load(std::memory_order_acquire); }

  /// Records from the next block on (throws InputError for a bad path or container). Any
  /// source, while it runs; before a network source's first sender, from its first sample (a
  /// path that then cannot be written shows in status().recorder_error).
  void start_recording(const std::string& path);
  void stop_recording();
  /// An operator's mark in the event log at the current stream time.
  void mark(const std::string& text);

  SampleSource& source() { return *source_; }
  AcquisitionStatus status() const;
  std::optional<Sidecar> layout() const;
  /// Finished levels so far (all pipelines, in time order) and the one being filled.
  std::vector<analysis::LevelResult> levels() const;
  std::optional<analysis::LevelResult> current_level() const;
  /// The cycles fitted from index `next` on, and `next` moved past them (the count grows; a
  /// reader asks for the new ones). The newest LiveEdc::kKeptCycles are kept: a reader further
  /// behind gets those, and `next` still ends at the count.
  std::vector<analysis::CycleFit> cycles_since(std::size_t& next) const;
  /// Events from index `first` on.
  std::vector<StreamEvent> events_since(std::size_t first) const;
  /// Traces over [from_s, to_s] (stream time) decimated to at most 2 × buckets points each
  /// (HistoryRing::read); empty before the layout is known.
  void history(double from_s, double to_s, int buckets, TraceHistory& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<SampleSource> source_;
  std::atomic<bool> finished_{false};
};

}  // namespace oscilab::daq
