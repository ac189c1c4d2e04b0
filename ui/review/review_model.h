#pragma once

#include <compare>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/edc/well.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/opened_recording.h"
#include "ui/time_window.h"

namespace oscilab::ui {

/// Points of a scatter plot, thinned to at most a given count by an even stride.
struct ScatterPoints {
  std::vector<double> x, y;
  std::size_t selected = 0;  // samples that met the condition, before thinning
};

/// The samples behind the restoring-force slices, thinned for drawing.
struct SlicePoints {
  /// Same selection as analysis::stiffness_slice (away from the records' ends, |ż| < ε_s):
  /// x = z [m], y = R [N].
  ScatterPoints stiffness;
  /// One per campaign damping slice (|z − z̄| < ε_d): x = ż [m/s], y = D = R − K_fit(z) [N].
  std::vector<ScatterPoints> damping;
};

/// The points the review draws of the slices: at most this many of the stiffness slice, and as
/// many of all damping slices together.
inline constexpr std::size_t kSlicePointsShown = 20000;

/// What the cycle plot shows of a fitted cycle (24 bytes, where the cycle's fit takes about 280:
/// a day-long record has 800 000 cycles).
struct ReviewCycle {
  double start_s = 0.0, end_s = 0.0;
  double edc_j = 0.0;
};

/// What the record review shows of the opened recordings: the offline analysis of those that
/// could be analysed (campaign.records[i] is recordings[i]), each record's cycles and the
/// samples behind its slices. Neither the records' motion nor their cycles' fits are kept (a
/// loop is made again from its window, level_loop), so the review of a record of any length
/// stays within its overview's memory and 24 bytes a cycle. Built on a worker thread by
/// analyze_review, then only read. Qt-free.
struct ReviewAnalysis {
  analysis::CampaignAnalysis campaign;
  std::vector<std::shared_ptr<const daq::OpenedRecording>> recordings;  // one per campaign record
  std::vector<std::vector<ReviewCycle>> cycles;  // one per campaign record, in time order
  SlicePoints slice_points;
  std::vector<std::string> errors;  // recordings left out, each message naming the file
};

/// Maps each recording to the analysis's channels (a recording that cannot be mapped is left out
/// and named in `errors`), runs analysis::analyze_campaign on the rest (the same analysis as
/// daq::analyze_recordings; a record whose samples live in its file is streamed from it, its
/// motion and its cycles' fits not kept) and gathers the slices' points in one more pass. Never
/// throws: a record the core rejects is reported in `errors`; a cancelled run returns
/// campaign.status == Cancelled.
ReviewAnalysis analyze_review(
    const std::vector<std::shared_ptr<const daq::OpenedRecording>>& recordings,
    const analysis::PipelineSettings& settings, const ProgressFn& progress = {},
    const CancelToken& cancel = {});

/// The slices' points of `campaign` in one pass over its records' motion
/// (analysis::campaign_motion_pass): at most `max_stiffness` of the stiffness slice and
/// `max_damping` of each damping slice, each thinned by an even stride over its samples in time
/// order.
SlicePoints slice_points(const analysis::MotionPass& pass,
                         const analysis::CampaignAnalysis& campaign, std::size_t max_stiffness,
                         std::size_t max_damping);

/// A level of the review: record index into ReviewAnalysis::campaign.records and level index
/// into that record's levels.
struct LevelKey {
  int record = -1;
  int level = -1;

  bool valid() const { return record >= 0 && level >= 0; }
  auto operator<=>(const LevelKey&) const = default;
};

/// One row of the level table (docs/contracts.md §3 names, SI).
struct LevelRow {
  LevelKey key;
  std::string record;  // the record's name (its file name)
  analysis::Well well = analysis::Well::Unclassified;
  double f0_n = 0.0;
  double edc_mean_j = 0.0;
  double edc_std_j = 0.0;
  int cycles = 0;
  std::string flags;  // LevelResult::flags(), plus "per-unit-mass" when the record has no mass
};

/// One row per level of one record, in the record's order.
std::vector<LevelRow> level_rows(int record, const std::string& record_name,
                                 const std::vector<analysis::LevelResult>& levels,
                                 bool per_unit_mass = false);
/// One row per level of every record, record by record.
std::vector<LevelRow> level_rows(const analysis::CampaignAnalysis& campaign);

/// The level at `key`, or null when there is none.
const analysis::LevelResult* find_level(const analysis::CampaignAnalysis& campaign, LevelKey key);

/// The loops shown before any level is selected: in each well, its usable levels with the
/// lowest, the middle and the highest forcing amplitude (fewer when it has fewer), positive well
/// first, each well's by rising f0.
std::vector<LevelKey> overview_levels(const analysis::CampaignAnalysis& campaign);

/// Where the time cursor goes when a level is selected: the middle of its steady cycles.
double level_cursor_time_s(const analysis::LevelResult& level);
/// The time window that shows a level's steady cycles with `margin_rel` of their span on each
/// side (the transient before them included, for context).
TimeWindow level_time_window(const analysis::LevelResult& level, double margin_rel = 0.1);

/// The response-input loop of a level (Fig. 9): z and f at every sample of its steady cycles,
/// [start_s, end_s]. Samples the analysis left out (non-finite R or f) break the loop: they are
/// skipped.
struct LevelLoop {
  analysis::Well well = analysis::Well::Unclassified;
  int cycles = 0;  // steady cycles the samples span
  std::vector<double> t_s, z_m, f_n;
};
LevelLoop level_loop(const analysis::MotionSignals& motion, const Eigen::VectorXd& force_n,
                     const analysis::LevelResult& level);

/// A loop shows at most this many samples (128 s at 512 Hz, over 1 000 cycles at 9 Hz): the
/// last ones of a longer hold, where it has settled most.
inline constexpr Eigen::Index kLoopSamples = Eigen::Index{1} << 16;

/// The loop of a level of `recording`, made from a window of the record read where its samples
/// live and transformed with the analysis's margin (analysis::window_motion, equal to the
/// record's motion there to its accuracy); the last kLoopSamples of a longer level, its cycles
/// counted in proportion. Throws InputError when the file can no longer be read.
LevelLoop level_loop(const daq::OpenedRecording& recording,
                     const analysis::PipelineSettings& settings,
                     const analysis::LevelResult& level);

/// ∮ f dz of a sampled loop by the trapezoidal rule, J (positive when z lags f).
double loop_area_j(const std::vector<double>& z_m, const std::vector<double>& f_n);

/// The fitted K(z) of eq. (2) with standard errors, in the paper's signs (k1 = −c1), e.g.
/// "K(z) = k₃z³ + k₂z² − k₁z + k₀ (eq. 2): k₃ = 2.041e+05 ± 12 N/m³, ...".
/// With `per_unit_mass` (no mass_kg) the forces are in N/kg and the coefficients in N/(kg m^k).
std::string stiffness_fit_text(const analysis::StiffnessSlice& slice, bool per_unit_mass = false);

/// A value and its standard error, "2.041e+05 ± 12": the value to 4 significant digits, the
/// error to 2.
std::string value_with_error(double value, double error);

}  // namespace oscilab::ui
