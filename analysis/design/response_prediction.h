#pragma once

#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/identification/edc_objective.h"

namespace oscilab::analysis {

/// The covariance of a fitted θ in the unit cube of its form (ModelForm::to_unit), from the
/// whitened residuals r (the EDC's and, with `fingerprints`, the response fingerprints') and
/// J = ∂r/∂u by forward differences of step `step` at θ:
///
///   C_u = s² (JᵀJ + 12 I)⁻¹,   s² = max{1, χ²/(n − p)}  (1 when n ≤ p),
///
/// the least-squares covariance (as fit_uncertainty, scaled up but never down by the misfit)
/// with the bounds as a prior: a uniform prior over the unit interval has variance 1/12, and its
/// Gaussian stand-in adds 12 I to the information JᵀJ. A direction the levels measured so far do
/// not constrain (few levels, a term whose effect has not been reached) keeps the spread of its
/// bounds instead of an infinite variance. p + 1 model evaluations.
Eigen::MatrixXd unit_covariance(const EdcObjective& objective, const Eigen::VectorXd& theta,
                                bool fingerprints, double step = 1e-3,
                                const CancelToken& cancel = {});

/// A model's predicted response at forcing levels of one well and frequency, with the linearly
/// propagated spread of its parameters.
struct PredictedLevels {
  bool positive_well = true;
  double freq_hz = 0.0;
  std::vector<double> f0_n;
  std::vector<double> edc_j, edc_sigma_j;  // S_mod (eq. (13), defect-corrected) and its σ
  std::vector<double> z1_m, z1_sigma_m;    // |Z1| and its σ
  /// Whether the level's prediction stands: solved, and the orbit stays in its well (every
  /// level at and after the first whose orbit reaches the saddle between the wells is out, as a
  /// sweep up would have jumped there).
  std::vector<char> valid;
  int first_well_jump = -1;  // index of the first level whose orbit reaches the saddle; -1: none
};

/// The responses of the objective's model at θ at increasing levels `f0_n`, as a sweep up from
/// rest reaches them (level_response at the objective's H, the same prediction the EDC objective
/// makes), with the objective's defect correction interpolated in f0 between the measured levels
/// of that well and frequency (EdcObjective::edc_at; held at the ends, none elsewhere). The σ of
/// each prediction is √(gᵀ C_u g), g = ∂prediction/∂u by forward differences of step `step` in
/// the unit cube (p + 1 level responses). `f0_n` must increase.
PredictedLevels predict_levels(const EdcObjective& objective, const Eigen::VectorXd& theta,
                               const Eigen::MatrixXd& unit_cov, bool positive_well, double freq_hz,
                               const std::vector<double>& f0_n, double step = 1e-3,
                               const CancelToken& cancel = {});

}  // namespace oscilab::analysis
