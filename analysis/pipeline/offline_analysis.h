#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/common/job.h"
#include "analysis/pipeline/measurement_channels.h"
#include "analysis/pipeline/measurement_pipeline.h"
#include "analysis/rfs/motion_signals.h"
#include "analysis/rfs/restoring_force_slices.h"
#include "analysis/signal/frequency_estimator.h"

namespace oscilab::analysis {

/// Everything the offline analysis learns from one record.
struct RecordAnalysis {
  std::string name;
  StreamSetup setup;  // as the pipeline ran (frequency given or detected)
  bool frequency_detected = false;
  DominantTone tone;              // of the base channel
  bool stepped_sine = false;      // EDC levels were computed
  bool per_unit_mass = false;     // no mass_kg: forces in N/kg and energies in J/kg
  Eigen::Index sample_count = 0;  // per channel
  std::size_t cycle_count = 0;    // cycles fitted, whether kept or not
  std::vector<CycleFit> cycles;   // each fitted cycle, when OfflineRetention::cycles
  std::vector<LevelResult> levels;
  /// z, ż and R of the record (RFS), when OfflineRetention::motion; z_absolute always.
  MotionSignals motion;
  std::vector<std::string> notes;  // what a reader should know (detections, exclusions)
};

/// Several records analysed together: per-record EDC and one restoring surface over all.
struct CampaignAnalysis {
  PipelineSettings settings;
  std::vector<RecordAnalysis> records;
  std::optional<StiffnessSlice> stiffness;
  std::vector<DampingSlice> damping;  // at the stable zeros of the fitted K(z)
  std::string rfs_message;            // why there is no stiffness slice, when there is none
  /// No record measures the mass position (the vibrometer gives velocity): z is known up to its
  /// mean, and the slices are against z − z̄ of each record.
  bool z_about_mean = false;
  JobStatus status = JobStatus::Ok;
};

/// What the offline analysis keeps of each record beyond its levels, notes and the slices. A
/// record's motion takes 32 bytes a sample (1.4 GB for a day at 512 Hz) and its cycles about
/// 300 bytes each: a front end that does not show them (the CLI's analyze) keeps neither, and
/// the analysis then holds a bounded amount of any record (a streamed one never whole).
struct OfflineRetention {
  bool cycles = true;
  bool motion = true;
  /// When set, called with every cycle the pipeline fits, in time order, kept or not, and the
  /// record's index (analyze_campaign's order; 0 from analyze_record): so that a caller keeps
  /// what it needs of the cycles of a record of any length. Records are analysed in parallel:
  /// the calls for different records come from different threads.
  std::function<void(std::size_t record, const CycleFit& cycle)> each_cycle;
};

/// The pipeline's setup for a record: rate, mass (1 when unknown), channel quantities, the
/// sidecar's levels and frequency (0 when the sidecar does not give it).
StreamSetup stream_setup(const MeasurementChannels& channels);

/// The offline analysis of one record: detect the excitation when the sidecar does not say it
/// (from its first kToneSamples), run the measurement pipeline over the record in chunks, as a
/// live stream arrives, and compute the time signals of the restoring surface (motion_spans.h)
/// when `retention` keeps them. A cancelled token stops it between chunks of samples; what it
/// returns then is incomplete and only good for discarding.
RecordAnalysis analyze_record(const MeasurementChannels& channels, const PipelineSettings& settings,
                              const CancelToken& cancel = CancelToken(),
                              const OfflineRetention& retention = OfflineRetention());

/// The excitation tone is looked for in a record's first 2^21 samples (68 min at 512 Hz): the
/// whole of most records, and a bounded transform for a day-long one.
inline constexpr Eigen::Index kToneSamples = Eigen::Index{1} << 21;

/// Why a stepped-sine record has no level that measures anything (LevelResult::measured: every
/// level flagged base-constant, mass-constant, negative-edc or non-finite, or without steady
/// cycles), or none found at all; "" when it has one, or is no stepped sine. Levels that are
/// measured but not usable (not period-1, cross-well) are results, not a fault.
std::string no_measured_level_reason(const RecordAnalysis& record);

/// Throws InputError with no_measured_level_reason for the first record that has one: what
/// `analyze` and the EDC exports refuse.
void require_measured_levels(const CampaignAnalysis& campaign);

/// analyze_record for each, then the stiffness and damping slices over all of them: from the
/// records' motion where it is kept, else span by span from their samples again (a pass each
/// for the band, the stiffness slice and the damping slices).
CampaignAnalysis analyze_campaign(const std::vector<MeasurementChannels>& records,
                                  const PipelineSettings& settings, const ProgressFn& progress = {},
                                  const CancelToken& cancel = {},
                                  const OfflineRetention& retention = OfflineRetention());

/// The records the restoring-force slices stack: those that measure z itself; when none does,
/// every record, with z about its mean (z_about_mean).
std::vector<const MotionSignals*> slice_records(const std::vector<RecordAnalysis>& records);

/// A pass over the motion of the records the slices stack (slice_records' rule), span by span:
/// each record's kept motion, or its spans made again from `records`, the channels the campaign
/// was analysed from, in its order (motion_spans.h). What analyze_campaign's slices pass over,
/// for whatever else is drawn from the same samples (the review's slice clouds). `campaign` and
/// `records` must outlive the pass.
MotionPass campaign_motion_pass(const CampaignAnalysis& campaign,
                                const std::vector<MeasurementChannels>& records,
                                const CancelToken& cancel = CancelToken());

/// What a reader must know about slices against z − z̄ (the CLI's report, the app's review).
inline constexpr const char* kZAboutMeanNote =
    "the mass is measured as velocity, so z is known up to its mean: the slices are against "
    "z - mean(z) of each record, and K(z) is shifted by the unknown equilibrium";

/// Summary JSON (docs/contracts.md §3 `stiffness_fit`, plus settings, per-record detections,
/// noise).
nlohmann::json campaign_summary(const CampaignAnalysis& campaign);

}  // namespace oscilab::analysis
