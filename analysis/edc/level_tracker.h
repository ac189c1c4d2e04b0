#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/edc/cycle_fit.h"
#include "analysis/edc/well.h"

namespace oscilab::analysis {

/// A stepped-sine level as the sidecar's excitation gives it: the steady part of a hold.
struct LevelWindow {
  double start_s = 0.0;
  double end_s = 0.0;
  double f0_nominal_n = std::numeric_limits<double>::quiet_NaN();
};

/// How cycles are grouped into levels and judged.
struct LevelOptions {
  std::vector<LevelWindow> windows;  // empty: levels are found from the cycles' force amplitude
  /// Levels come from windows even while there are none yet (a live, operated excitation adds
  /// them as it is set: LevelTracker::add_window); cycles outside every window are ramps.
  bool windowed = false;
  double freq_hz = 0.0;
  double mass_kg = 1.0;
  MotionQuantity base_quantity = MotionQuantity::Acceleration;
  MotionQuantity mass_quantity = MotionQuantity::Displacement;
  /// z between the wells: the paper's zero of y is the rods' horizontal configuration (§2),
  /// between z₋* and z₊*. A cycle whose z range contains it crosses wells.
  double well_boundary_m = 0.0;
  std::optional<bool> well_hint_positive;  // when z's mean is unknown (velocity channel)
  int min_steady_cycles = 5;
  /// Without windows: a cycle whose f0 differs from the level's median by more than this
  /// fraction (or 5 noise σ) starts a new level.
  double level_change_rel = 0.03;
  /// Steady-state test: the steady part starts at the first of three consecutive cycles within
  /// 4 robust σ + steady_rel_tol·|value| of the level's final value (median of its last third).
  double steady_rel_tol = 2e-4;
};

/// One row of the EDC table (docs/contracts.md §3 names) with what backs it.
struct LevelResult {
  Well well = Well::Unclassified;  // Unclassified until it has steady cycles
  double f0_n = 0.0;
  double edc_mean_j = 0.0;         // ∮ f dz, mean over steady cycles
  double edc_std_j = 0.0;          // standard deviation over steady cycles
  int cycles = 0;                  // steady cycles used
  double edc_eq13_mean_j = 0.0;    // eq. (13) first-harmonic estimate
  double edc_trapz_mean_j = 0.0;   // trapezoidal loop area
  double edc_noise_floor_j = 0.0;  // σ of edc_mean_j predicted from the sensor noise
  double z1_abs_m = 0.0;
  double lag_rad = 0.0;
  double z_mean_m = 0.0;
  double z_min_m = 0.0;
  double z_max_m = 0.0;
  double start_s = 0.0;         // first steady cycle start
  double end_s = 0.0;           // last cycle end
  int transient_cycles = 0;     // cycles dropped by the steady-state test
  double period1_change = 0.0;  // median relative change of the harmonics between cycles
  bool period1 = true;          // false: sub-harmonic or non-periodic motion (Fig. 17)
  bool cross_well = false;
  bool few_cycles = false;
  // Degenerate data, said and never scored (docs/contracts.md §3):
  bool base_constant = false;  // the force's first harmonic within the base channel's noise
  bool mass_constant = false;  // the mass's first harmonic within its channel's noise
  bool negative_edc = false;   // EDC below zero beyond its noise: roles or a sign swapped
  bool non_finite = false;     // a result overflowed: a channel's values or scale are absurd
  bool short_window = false;   // the sidecar's window is shorter than one forcing period
  bool beyond_record = false;  // the sidecar's window reaches past the end of the record
  /// Steady cycles of data that measure something: no degenerate-data flag. A level can be
  /// measured and still not usable (not period-1, cross-well).
  bool measured() const {
    return cycles > 0 && !base_constant && !mass_constant && !negative_edc && !non_finite;
  }
  bool usable() const { return period1 && !cross_well && measured(); }
  std::string flags() const;  // "" or e.g. "not-period-1;cross-well;few-cycles"
};

/// Groups fitted cycles into stepped-sine levels, finds each level's steady part, and reduces it
/// to a LevelResult. Streaming: push() cycles as they come, finish() at the end. The offline
/// analysis feeds all cycles at once, so live and offline give the same levels.
class LevelTracker {
 public:
  explicit LevelTracker(LevelOptions options);
  void push(const std::vector<CycleFit>& cycles, std::vector<LevelResult>& finished);
  /// Ends the stream at `stream_end_s` (the end of its last sample): closes the level being
  /// filled, and reports every window that got no cycle (flagged few-cycles, and short-window or
  /// beyond-record where that is why), so that each of the sidecar's levels has its row.
  void finish(std::vector<LevelResult>& finished,
              double stream_end_s = std::numeric_limits<double>::infinity());
  /// The level being filled, summarised so far (live display); empty when there is none. A
  /// summary reads all of the level's cycles, so it is made again only once they have grown by
  /// a 64th since the last (every cycle for the first 128): a live display of an hours-long hold
  /// costs a constant per cycle, not one growing with the hold, and lags its level by at most
  /// 1.6 % of its cycles.
  std::optional<LevelResult> current() const;
  /// Live: a level's steady window starts (end_s may be +∞ until end_window). Windows come in
  /// time order; the tracker becomes windowed.
  void add_window(const LevelWindow& window);
  /// Live: the open window ends at end_s (the next change of the excitation).
  void end_window(double end_s);

 private:
  void close_level(std::vector<LevelResult>& finished, double stream_end_s);
  void report_windows_without_cycles(std::size_t until, std::vector<LevelResult>& finished,
                                     double stream_end_s);
  bool starts_new_level(const CycleFit& cycle) const;
  int window_of(const CycleFit& cycle) const;

  LevelOptions options_;
  std::vector<CycleFit> level_cycles_;
  std::uint64_t levels_closed_ = 0;  // which level level_cycles_ holds, for the summary's cache
  mutable std::optional<LevelResult> current_summary_;
  mutable std::size_t summary_cycles_ = 0;  // of level_cycles_ when current_summary_ was made
  mutable std::uint64_t summary_level_ = 0;
  int level_window_ = -1;
  std::size_t next_window_ = 0;  // the first window not reported yet
};

/// Reduces one level's cycles (in time order, transient included) to its result.
LevelResult summarise_level(const std::vector<CycleFit>& cycles, const LevelOptions& options);

/// One note per degenerate-data flag the levels carry, with how many levels carry it and what
/// it means (docs/contracts.md §3), in the order of LevelResult::flags(); none when there is none.
std::vector<std::string> degenerate_level_notes(const std::vector<LevelResult>& levels);

}  // namespace oscilab::analysis
