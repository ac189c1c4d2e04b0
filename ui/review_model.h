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
#include "daq/recording/recording.h"
#include "ui/time_window.h"

namespace oscilab::ui {

/// What the record review shows of the opened recordings: the offline analysis of those that
/// could be analysed (campaign.records[i] is recordings[i]) and the excitation force of each.
/// Built on a worker thread by analyze_review, then only read. Qt-free.
struct ReviewAnalysis {
  analysis::CampaignAnalysis campaign;
  std::vector<std::shared_ptr<const daq::Recording>> recordings;  // one per campaign record
  std::vector<Eigen::VectorXd> force_n;  // f = −m b̈ per sample, one per campaign record
  std::vector<std::string> errors;       // recordings left out, each message naming the file
};

/// Maps each recording to the analysis's channels (a recording that cannot be mapped is left out
/// and named in `errors`), runs analysis::analyze_campaign on the rest (the same analysis as
/// daq::analyze_recordings, on recordings already in memory) and computes their excitation
/// force. Never throws: a record the core rejects is reported in `errors`; a cancelled run
/// returns campaign.status == Cancelled.
ReviewAnalysis analyze_review(const std::vector<std::shared_ptr<const daq::Recording>>& recordings,
                              const analysis::PipelineSettings& settings,
                              const ProgressFn& progress = {}, const CancelToken& cancel = {});

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

/// ∮ f dz of a sampled loop by the trapezoidal rule, J (positive when z lags f).
double loop_area_j(const std::vector<double>& z_m, const std::vector<double>& f_n);

/// Points of a scatter plot, thinned to at most a given count by an even stride.
struct ScatterPoints {
  std::vector<double> x, y;
  std::size_t selected = 0;  // samples that met the condition, before thinning
};

/// The samples behind the stiffness slice (same selection as analysis::stiffness_slice: away
/// from the records' ends, |ż| < ε_s): x = z [m], y = R [N].
ScatterPoints stiffness_points(const analysis::CampaignAnalysis& campaign, std::size_t max_points);
/// The samples behind a damping slice (|z − z̄| < ε_d): x = ż [m/s], y = D = R − K_fit(z) [N].
ScatterPoints damping_points(const analysis::CampaignAnalysis& campaign,
                             const analysis::DampingSlice& slice, std::size_t max_points);

/// The fitted K(z) of eq. (2) with standard errors, in the paper's signs (k1 = −c1), e.g.
/// "K(z) = k₃z³ + k₂z² − k₁z + k₀ (eq. 2): k₃ = 2.041e+05 ± 12 N/m³, ...".
/// With `per_unit_mass` (no mass_kg) the forces are in N/kg and the coefficients in N/(kg m^k).
std::string stiffness_fit_text(const analysis::StiffnessSlice& slice, bool per_unit_mass = false);

/// A value and its standard error, "2.041e+05 ± 12": the value to 4 significant digits, the
/// error to 2.
std::string value_with_error(double value, double error);

}  // namespace oscilab::ui
