#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "analysis/edc/cycle_analyzer.h"
#include "analysis/edc/level_tracker.h"
#include "analysis/pipeline/pipeline_settings.h"
#include "analysis/pipeline/sample_block.h"

namespace oscilab::analysis {

/// What the pipeline needs to know about a stream before the first sample.
struct StreamSetup {
  double sample_rate_hz = 512.0;
  double mass_kg = 1.0;  // 1 with energies per unit mass when the mass is unknown
  MotionQuantity base_quantity = MotionQuantity::Acceleration;
  MotionQuantity mass_quantity = MotionQuantity::Displacement;
  bool mass_is_relative = false;
  double excitation_freq_hz = 0.0;         // required: given, or detected offline beforehand
  std::vector<LevelWindow> level_windows;  // from the sidecar; empty: detect levels
  std::optional<bool> well_hint_positive;
  double t0_s = 0.0;  // first cycle start
  /// Levels come as windows while the stream runs (add_level_window), none yet at the start:
  /// cycles outside a window are ramps, never a detected level.
  bool windowed_levels = false;
};

/// The one measurement engine (§4.1): SampleBlocks in, per-cycle fits and per-level EDC out.
/// Live work pushes blocks as they arrive; offline work pushes a whole record as one block and
/// calls finish(). Both run the same code, so their results agree (a test replays a record in
/// odd block sizes). Not thread-safe: owned by the pipeline thread.
class MeasurementPipeline {
 public:
  /// `keep_cycles` false: cycles() stays empty (a day-long record has 800 000 of them) and only
  /// cycle_count() counts them; the levels are the same.
  MeasurementPipeline(const PipelineSettings& settings, const StreamSetup& setup,
                      bool keep_cycles = true);

  void push(const SampleBlock& block);
  /// The same for `count` samples from sample index `first_sample` on (t = index / rate, as
  /// the offline push of a whole record computes it), base and mass values in SI. Live path:
  /// no allocation once the buffers have grown to the largest block.
  void push(std::int64_t first_sample, const double* base, const double* mass, int count);
  /// Live, operated excitation: a level's steady window starts / the open one ends
  /// (LevelTracker::add_window, end_window).
  void add_level_window(const LevelWindow& window) { tracker_.add_window(window); }
  void end_level_window(double end_s) { tracker_.end_window(end_s); }
  /// Leaves out every cycle that touches [start_s, end_s] (CycleAnalyzer::exclude): call it
  /// before pushing the samples of a gap, of non-finite or saturated samples, or of a
  /// discontinuity.
  void exclude(double start_s, double end_s) { analyzer_.exclude(start_s, end_s); }
  long excluded_cycles() const { return analyzer_.excluded_cycles(); }
  /// Ends the stream: closes the level being filled and reports the sidecar's levels that got
  /// no cycle (LevelTracker::finish, with the end of the last sample pushed).
  void finish();

  const std::vector<CycleFit>& cycles() const { return cycles_; }
  std::size_t cycle_count() const { return cycle_count_; }
  /// The cycles the last push completed (kept or not): what a live reader takes after a push.
  const std::vector<CycleFit>& last_completed() const { return completed_; }
  const std::vector<LevelResult>& levels() const { return levels_; }
  /// The level being filled, summarised so far (for a live display).
  std::optional<LevelResult> current_level() const { return tracker_.current(); }
  const StreamSetup& setup() const { return setup_; }

 private:
  void analyse(const double* base, const double* mass, int count);  // times in t_scratch_

  StreamSetup setup_;
  CycleAnalyzer analyzer_;
  LevelTracker tracker_;
  bool keep_cycles_ = true;
  std::vector<CycleFit> cycles_;
  std::size_t cycle_count_ = 0;
  std::vector<CycleFit> completed_;  // scratch, reused between pushes
  std::vector<double> t_scratch_;
  std::vector<LevelResult> levels_;
  double stream_end_s_ = -std::numeric_limits<double>::infinity();  // end of the last sample
};

}  // namespace oscilab::analysis
