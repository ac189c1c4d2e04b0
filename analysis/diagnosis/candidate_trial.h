#pragma once

#include <functional>
#include <optional>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/diagnosis/diagnosis.h"
#include "analysis/diagnosis/effect_candidates.h"
#include "analysis/diagnosis/response_fingerprints.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/identification/model_form.h"

namespace oscilab::analysis {

/// What every candidate of one diagnosis step is measured against: the settled current model,
/// its shared σ budget and its evaluation.
struct TrialContext {
  const ModelForm& lab_form;  // the form the diagnosis started from (the lab's friction)
  const ModelForm& current;
  const Eigen::VectorXd& theta;  // the current model's settled θ
  const EdcDataset& data;
  const EdcCostSettings& cost;       // with the current model's σ budget (shared by the step)
  const EdcCostSettings& base_cost;  // without a budget: what a calibration starts from
  const EdcEvaluation& evaluation;   // of the current model
  const ResponseFingerprints& fingerprints;
  bool use_fingerprints = true;
  int levels = 0;
  /// φ ≥ 1 dividing every Δχ² of the step (quasi-likelihood, DiagnosisStep::dispersion).
  double dispersion = 1.0;
  long candidate_evaluations = 600;
  int max_harmonics = 63;  // of the diagnosis's σ budget
};

/// A candidate refitted: its scores, the extended form and the cost settings with the
/// candidate's own defect correction (its σ stays the shared budget's).
struct TrialOutcome {
  CandidateTrial trial;
  std::optional<ModelForm> form;  // empty when the refit failed or was cancelled
  EdcCostSettings own_cost;
};

/// The model evaluations a trial may spend: its grid, scan and refits (candidate_evaluations),
/// and the refit with its own correction (half that again). What a progress report divides by.
long trial_budget(long candidate_evaluations);

/// One candidate of a step, in two stages: (1) a grid over the new term's own parameters and its
/// scan points, the others at the current θ (one evaluation each); (2) Levenberg–Marquardt refits
/// of all parameters from the two best grid points, the two best scan points and, when the
/// current friction has moved from the lab's, the best grid point about the lab's friction. The
/// best refit gets the candidate's own defect correction and one more refit with it, and is
/// scored against the current model (ΔBIC of the EDC and joint with the fingerprints).
/// `spent(evaluations)` is called as the trial spends its budget (from the worker's thread).
TrialOutcome try_candidate(const EffectCandidate& candidate, double fingerprint_score,
                           const TrialContext& context,
                           const std::function<void(long evaluations)>& spent,
                           const CancelToken& cancel);

/// The longer refit of a finalist (`evaluations`), from its trial's θ, with its own cost
/// settings; the trial is rescored when the refit improves its joint χ² and solves every level.
void refine_finalist(CandidateTrial& trial, const ModelForm& extended,
                     const EdcCostSettings& own_cost, const TrialContext& context, long evaluations,
                     const CancelToken& cancel);

}  // namespace oscilab::analysis
