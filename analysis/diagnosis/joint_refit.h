#pragma once

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/diagnosis/response_fingerprints.h"
#include "analysis/identification/edc_objective.h"

namespace oscilab::analysis {

/// A local refit of all parameters by Levenberg–Marquardt (Eigen's unsupported module, after
/// Moré 1978, "The Levenberg–Marquardt algorithm: implementation and theory") on the whitened
/// residuals: the EDC's (S_mes − S_mod)/σ_k and, with `fingerprints`, the response fingerprints'
/// per-level residuals (ResponseFingerprints). A least-squares problem of ~50–200 residuals in
/// 6–9 parameters converges in a handful of Gauss–Newton steps, each p + 1 model evaluations
/// (forward differences of step 1e-6 in the unit cube of the form's bounds, far above the
/// solver's rounding of ~1e-11 relative and far below the parameters' scales), where a
/// derivative-free method needs hundreds of evaluations to reach the same minimum.
///
/// Robust refit: with `cauchy_scale` c > 0 (in σ) the solver minimises the Cauchy loss
/// Σ c² ln(1 + (r/c)²) of the same residuals instead of their squares, so that a few levels far
/// off (a level just across a fold from the model's, on the other branch) cannot hold θ back; the
/// best point is then the one of least loss, and `joint_chi2` is still its plain χ².
///
/// Bounds: the parameters live in the unit cube of ModelForm::to_unit, clamped into [0, 1] before
/// each evaluation. Cancellation stops the solver at its next evaluation; the best point so far
/// is returned.
struct JointRefit {
  Eigen::VectorXd theta;
  EdcEvaluation evaluation;
  ResponseFingerprints fingerprints;
  double joint_chi2 = 0.0;  // EDC χ² plus, with fingerprints, their χ²
  long evaluations = 0;
};

JointRefit joint_refit(const EdcObjective& objective, const Eigen::VectorXd& start,
                       bool fingerprints, int max_evaluations, const CancelToken& cancel,
                       double cauchy_scale = 0.0);

/// The joint χ² of an evaluation (EDC χ², plus the fingerprints' when asked).
double joint_chi2(const EdcEvaluation& evaluation, const ResponseFingerprints& fingerprints,
                  bool use_fingerprints);

}  // namespace oscilab::analysis
