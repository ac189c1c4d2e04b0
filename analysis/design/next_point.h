#pragma once

#include <string>
#include <vector>

#include "analysis/common/job.h"
#include "analysis/design/model_hypothesis.h"

namespace oscilab::analysis {

/// The settings an adaptive test may choose from, and what each costs in shaker time.
struct AdmissibleSettings {
  /// Forcing amplitude f0 on the grid f0_min, f0_min + step, … ≤ f0_max: the rig's limits.
  double f0_min_n = 0.2;
  double f0_max_n = 2.7;
  double f0_step_n = 0.1;
  /// Frequencies freq_hz − span … freq_hz + span in steps of freq_step_hz (span 0: freq_hz only),
  /// the stated range around the current one.
  double freq_hz = 9.0;
  double freq_span_hz = 0.0;
  double freq_step_hz = 0.25;
  bool positive_well = true;
  bool negative_well = true;
  /// Shaker time of one level: its dwell (ramp and steady cycles) and the settling before it
  /// (the lead-in at rest); a change of well costs well_change_s more (bringing the mass over).
  double dwell_s = 10.0;
  double settling_s = 2.5;
  double well_change_s = 10.0;
  bool current_positive_well = true;

  std::vector<double> f0_grid() const;
  std::vector<double> freq_grid() const;
  /// Throws InputError naming the field for an empty or non-finite grid, no well, or a
  /// non-positive dwell.
  void validate() const;
};

struct NextPointOptions {
  /// Hypotheses of smaller weight are not predicted (they add little to the criterion), except
  /// that the `min_models` of largest weight always are, their weights in the criterion floored
  /// at min_weight: when the BIC weights saturate (one model far ahead but its misfit still above
  /// the noise), the test keeps separating it from its closest rivals instead of stopping to
  /// learn.
  double min_weight = 1e-3;
  int min_models = 2;
  double difference_step = 1e-3;  // unit-cube step of the Jacobians (unit_covariance)
  bool use_amplitude = true;      // |Z1| joins the EDC in the criterion
  bool use_fingerprints = true;   // in the parameters' covariance (as the refits weigh them)
  /// Whether a setting already measured (same well and frequency, f0 within half a grid step)
  /// may be proposed again. Off by default: a repeated level merges with the first (edc_dataset)
  /// and only its cycles' scatter averages down, not the estimator's bias floor that bounds its
  /// σ, while the fitted models already pass through it.
  bool repeat_measured = false;
  /// Settings the operator skipped: never proposed again, nor counted in max_discrimination
  /// (what the test could still tell apart is what it may still measure). Matched as measured
  /// settings are: the same well and frequency, f0 within half a grid step.
  struct Skipped {
    double f0_n = 0.0;
    double freq_hz = 0.0;
    bool positive_well = true;
  };
  std::vector<Skipped> skipped;
  int threads = 0;  // 0: all hardware threads
};

/// One admissible setting and its score.
struct SettingScore {
  double f0_n = 0.0;
  double freq_hz = 0.0;
  bool positive_well = true;
  bool admissible = false;
  std::string why_not;     // when not admissible: which model's response jumps wells
  double criterion = 0.0;  // D of propose_next_point
  double shaker_s = 0.0;   // dwell + settling (+ a well change)
  double criterion_per_s = 0.0;
  /// The pair and quantity contributing most: hypotheses i, j, "EDC" or "|Z1|", and by how many
  /// σ their predictions differ there.
  int pair_i = -1, pair_j = -1;
  std::string quantity;
  double separation_sigma = 0.0;  // |μ_i − μ_j| / √(s² + v_i + v_j)
  double spread_sigma = 0.0;      // √(max(v_i, v_j) / s²): how uncertain the vaguer one is
  int uncertain = -1;             // which of i, j has the larger v
  /// The largest unweighted pair term ½[…] of D here: ~(Δμ/s)² for well-known models, so 1 is an
  /// expected separation of one measurement σ.
  double pair_discrimination = 0.0;
};

struct NextPoint {
  JobStatus status = JobStatus::Ok;
  std::string message;
  bool found = false;  // an admissible setting exists
  SettingScore best;
  std::string reason;  // "quadratic-damping vs baseline differ by 7.1σ in EDC at 2.40 N, …"
  std::vector<SettingScore> settings;  // every setting, in grid order (well, frequency, f0)
  std::vector<int> plausible;          // the hypotheses predicted (weight ≥ min_weight)
  /// The largest pair_discrimination over the admissible settings: what the best setting could
  /// still tell apart (StopRule::min_discrimination).
  double max_discrimination = 0.0;
};

/// The next level of an adaptive test: the admissible setting that best tells the plausible
/// hypotheses apart per second of shaker time.
///
/// Each plausible hypothesis i predicts at every setting s its EDC μ_i,EDC(s) and |Z1|
/// μ_i,Z(s) (predict_levels: harmonic balance swept up from rest, the objective's defect
/// correction) with the σ_i of its parameters' uncertainty propagated linearly
/// (unit_covariance). The criterion is Box & Hill's (1967, "A discrimination criterion for
/// Box–Hunter designs") in its Gaussian upper bound, the weighted sum over pairs of the squared
/// difference of predictions and of their variances over the variance a measurement would see:
///
///   D(s) = Σ_{i<j} w_i w_j Σ_q ½ [ (v_i − v_j)² / ((s² + v_i)(s² + v_j))
///                                  + (μ_i − μ_j)² (1/(s² + v_i) + 1/(s² + v_j)) ],
///
/// v_i = σ_i,q², s² = σ_meas,q². The second term separates models whose predictions differ;
/// the first sends the test where one model's prediction is still uncertain (a candidate whose
/// strength the levels so far do not constrain), where its effect could show.
///
/// q ∈ {EDC, |Z1|}, w the BIC weights (floored at NextPointOptions::min_weight). With a single
/// solved hypothesis D is instead Σ_q v_i / s²: where its own prediction is least certain. σ_meas
/// is what one new level would measure: the estimator's bias floors (kEdcEstimatorBiasRel,
/// kAmplitudeBiasRel) and the cycles' relative standard error typical of the levels measured so far
/// (their median), at the predictions' weighted mean. A setting is scored by D / (dwell + settling
/// (+ well change)). It is not admissible when any plausible model's response there reaches the
/// saddle between the wells (or is not solved): the test never proposes a setting that would jump
/// wells; nor, unless asked, one already measured (NextPointOptions::repeat_measured).
///
/// Progress is the fraction of hypotheses predicted; `cancel` returns status Cancelled.
NextPoint propose_next_point(const std::vector<ModelHypothesis>& hypotheses,
                             const AdmissibleSettings& settings, const NextPointOptions& options,
                             const ProgressFn& progress = {}, const CancelToken& cancel = {});

}  // namespace oscilab::analysis
