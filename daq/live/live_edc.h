#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "analysis/edc/cycle_fit.h"
#include "analysis/edc/level_tracker.h"
#include "analysis/pipeline/measurement_pipeline.h"
#include "analysis/pipeline/pipeline_settings.h"
#include "daq/live/acquisition.h"
#include "daq/recording/sidecar.h"

namespace oscilab::daq {

/// The live EDC of a stream (§4.1, the same per-cycle fit and per-level EDC as offline): one
/// MeasurementPipeline per excitation frequency (a new frequency starts a new cycle grid), the
/// level windows the stream's `level` events open, and what it found as the acquisition
/// publishes it: the cycles, the finished levels of every pipeline and the one being filled, and
/// each cycle's latency from the arrival of its first sample to its EDC.
///
/// Thread-safety: owned by the acquisition thread. The methods marked "published" read or write
/// what the controlling thread reads: call them with the acquisition's mutex held.
class LiveEdc {
 public:
  /// The stream the pipelines analyse: its rate, mass and channels (`stream`; each pipeline's
  /// frequency, start and level windows are its own) and the excitation its sidecar gives.
  void configure(const analysis::PipelineSettings& settings, const analysis::StreamSetup& stream,
                 std::optional<Excitation> excitation);
  /// A pipeline for the excitation frequency `freq_hz`, its cycle grid from t0_s on.
  void start(double freq_hz, double t0_s);
  bool running() const { return pipeline_ != nullptr; }
  /// The excitation frequency of the pipeline running.
  double freq_hz() const { return freq_hz_; }

  /// When a block's samples [first_sample, end_sample) reached the acquisition.
  void note_arrival(std::uint64_t first_sample, std::uint64_t end_sample,
                    std::chrono::steady_clock::time_point delivered);
  /// The block's calibrated base and mass (SI), from sample `first_sample` on.
  void push(std::uint64_t first_sample, const double* base_si, const double* mass_si, int rows);
  /// Leaves out every cycle that touches [from_s, to_s].
  void exclude(double from_s, double to_s);
  /// The end of the stream: the last cycles and levels (then publish_finished).
  void finish();

  /// Published: the new cycles and levels, their counts and latencies in `status`.
  void publish(std::chrono::steady_clock::time_point now, AcquisitionStatus& status);
  /// Published: a `level` event at change_s (steady over [from_s, to_s)); f0_n = 0 is the table
  /// at rest, which ends the level before it and starts none. Another frequency finishes the
  /// pipeline and starts one on a new grid from change_s.
  void apply_level(double f0_n, double freq_hz, double change_s, double from_s, double to_s,
                   AcquisitionStatus& status);
  /// Published: after finish(), the last pipeline's levels among the finished ones.
  void publish_finished(AcquisitionStatus& status);

  // Published: what the controlling thread reads.
  const std::vector<analysis::LevelResult>& levels() const { return levels_; }
  const std::optional<analysis::LevelResult>& current_level() const { return current_level_; }
  /// The newest kKeptCycles cycles (a day-long stream fits 800 000 of them at 9 Hz, 240 MB: the
  /// levels hold what is measured, and the cycles are for the live plots and readers).
  const std::deque<analysis::CycleFit>& cycles() const { return cycles_; }
  /// Cycles fitted so far; the kept ones are the last cycles().size() of them.
  std::size_t cycle_count() const { return cycle_count_; }
  /// Per cycle, the last kMaxLatencies.
  const std::vector<double>& latencies_s() const { return latencies_s_; }

  static constexpr std::size_t kMaxLatencies = 10000;
  static constexpr std::size_t kKeptCycles = 65536;  // 2 h at 9 Hz, about 20 MB
  /// How many of the newest cycles are kept (kKeptCycles unless changed; at least 1).
  void keep_cycles(std::size_t kept) { kept_cycles_ = std::max<std::size_t>(1, kept); }

 private:
  // When a block's samples reached the acquisition: a cycle's EDC latency is measured from the
  // arrival of its first sample. A fixed ring of the newest kArrivals blocks.
  struct BlockArrival {
    std::uint64_t first_sample = 0, end_sample = 0;
    std::chrono::steady_clock::time_point delivered;
  };
  static constexpr std::size_t kArrivals = 512;

  void close_pipeline(AcquisitionStatus& status);  // published

  analysis::PipelineSettings settings_;
  analysis::StreamSetup stream_;
  std::optional<Excitation> excitation_;
  std::unique_ptr<analysis::MeasurementPipeline> pipeline_;
  double freq_hz_ = 0.0;
  std::vector<analysis::CycleFit> fresh_;  // completed by pushes since the last publish
  std::size_t levels_seen_ = 0;
  std::vector<BlockArrival> arrivals_ = std::vector<BlockArrival>(kArrivals);
  std::size_t arrivals_next_ = 0;

  // --- published ---
  std::vector<analysis::LevelResult> levels_done_;  // of pipelines already finished
  std::vector<analysis::LevelResult> levels_;       // levels_done_ + the current pipeline's
  std::optional<analysis::LevelResult> current_level_;
  std::deque<analysis::CycleFit> cycles_;
  std::size_t cycle_count_ = 0;
  std::size_t kept_cycles_ = kKeptCycles;
  std::vector<double> latencies_s_;
};

}  // namespace oscilab::daq
