#pragma once

#include <optional>
#include <vector>

#include "analysis/diagnosis/log_slope.h"
#include "analysis/diagnosis/response_fingerprints.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

/// One level: where model and measurement disagree, in energy and in units of σ.
struct LevelDiscrepancy {
  bool positive_well = true;
  double f0_n = 0.0;
  double amplitude_m = 0.0;  // |Z1| measured
  double edc_mes_j = 0.0;
  double edc_mod_j = 0.0;
  double sigma_j = 0.0;          // σ_k of the fit (cycles, noise floor and model-error floor)
  double sigma_cycles_j = 0.0;   // the standard error from the cycles alone
  double residual_sigma = 0.0;   // (S_mes − S_mod) / σ_k
  double residual_cycles = 0.0;  // (S_mes − S_mod) / σ_cycles (inf without cycles)
};

/// The EDC's power law in the response amplitude (Coulomb ~1, viscous ~2, quadratic damping and
/// presliding hysteresis ~3, cubic damping ~4): of the measured EDC, and of the energy the model
/// misses, ΔS = S_mes − S_mod over the levels where it exceeds 2σ_k, each over the lower and the
/// upper half of the amplitudes.
struct EnergySlopes {
  LogSlope measured_low, measured_high;
  LogSlope missing_low, missing_high, missing_all;
  int missing_levels = 0;  // ΔS > 2σ_k
  int excess_levels = 0;   // ΔS < −2σ_k: the model dissipates more than measured
};

/// The restoring force's stiffness slice (ż ≈ 0, §3.1) against the model's K(z): missing
/// stiffness powers shift the equilibria and the frequencies. Each power p ∈ {2, 3, 5} is tested
/// by the F statistic of adding c z^p to an offset-and-slope fit of the residual (the offset and
/// slope absorb the slice's calibration and the wells' shift).
struct StiffnessResidual {
  bool available = false;
  std::vector<double> z_m, residual_n;
  double rms_n = 0.0;
  struct PowerTest {
    int power = 0;
    double coefficient = 0.0;  // c in N/m^p
    double f_statistic = 0.0;  // 1 and n − 3 degrees of freedom
    double p_value = 1.0;
  };
  std::vector<PowerTest> tests;
};

struct DiscrepancyMaps {
  std::vector<LevelDiscrepancy> levels;
  double max_abs_residual_sigma = 0.0;
  double reduced_chi2 = 0.0;  // χ² / (levels − parameters)
  EnergySlopes slopes;
  StiffnessResidual stiffness;
  ResponseFingerprints response;  // amplitude and harmonic content against the model
};

/// The maps of a fitted model (θ of the objective's form) against the measurement.
DiscrepancyMaps discrepancy_maps(const EdcObjective& objective, const Eigen::VectorXd& theta,
                                 const EdcEvaluation& evaluation, const CampaignAnalysis& campaign);

}  // namespace oscilab::analysis
