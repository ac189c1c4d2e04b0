#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/identification/edc_objective.h"

namespace oscilab::analysis {

/// What the data say about one identified parameter.
struct ParameterUncertainty {
  std::string name;
  double value = 0.0;
  double standard_error = 0.0;  // from the covariance at the optimum; inf when not identifiable
  double lower_95 = 0.0;        // value ∓ t₀.₉₇₅,ν · standard_error
  double upper_95 = 0.0;
  bool at_bound = false;  // the optimum sits on a search bound: the interval is one-sided
  // Bootstrap over levels (0 replicates: NaN).
  double bootstrap_std = 0.0;
  double bootstrap_lower_95 = 0.0;  // 2.5 % and 97.5 % percentiles of the replicates
  double bootstrap_upper_95 = 0.0;
  bool weakly_identified = false;
  std::string note;  // why it is weakly identified
};

/// Uncertainty of an EDC fit.
///
/// Covariance: with r(θ) the whitened residuals (EdcObjective) and J = ∂r/∂θ by central
/// differences at the optimum θ̂,
///
///   Cov(θ̂) = s² (JᵀJ)⁻¹,   s² = max{1, χ²(θ̂) / (n − p)},
///
/// the least-squares covariance, scaled by the reduced χ² when the misfit exceeds the stated σ
/// (a model error larger than the floor widens the intervals instead of being ignored; Press et
/// al., "Numerical Recipes", §15.6) but never shrunk below it: σ's model-error floor stands for
/// systematic error that does not average out over levels. Directions in which JᵀJ is singular
/// to working precision get an infinite standard error.
///
/// Bootstrap: replicates draw the levels of each well with replacement (multiplicity weights
/// on χ²) and refit locally from θ̂; their spread does not assume linearity.
///
/// A parameter is flagged weakly identified when its relative standard error exceeds 25 %, when
/// it correlates with another beyond |ρ| = 0.95, or when it sits on a bound; the note says
/// which. The paper found f_d(0), k_s and v_t poorly determined by EDCs (§5, Fig. 13, §5.1).
struct FitUncertainty {
  bool ok = false;
  std::string message;
  int levels = 0;
  int dof = 0;  // n − p
  double reduced_chi2 = 0.0;
  double t_quantile = 0.0;  // t₀.₉₇₅ for dof degrees of freedom
  Eigen::MatrixXd covariance;
  Eigen::MatrixXd correlation;
  std::vector<ParameterUncertainty> parameters;
  int bootstrap_replicates = 0;
  long evaluations = 0;
};

struct UncertaintyOptions {
  double difference_step = 1e-3;  // unit-cube step of the central differences
  int bootstrap_replicates = 0;
  long bootstrap_polish_evaluations = 300;
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all hardware threads
};

FitUncertainty fit_uncertainty(const EdcObjective& objective, const Eigen::VectorXd& theta,
                               const UncertaintyOptions& options, const CancelToken& cancel = {});

}  // namespace oscilab::analysis
