#pragma once

#include <string>
#include <vector>

#include "analysis/identification/edc_objective.h"

namespace oscilab::analysis {

/// Bias floors of the measured harmonic content, measured like kEdcEstimatorBiasRel
/// (scripts/estimator_bias_study.sh, 1248 levels): what the cycle fits get wrong that their
/// scatter does not show, rounded up from 3.5e-4 (|Z1|, relative; 2.8e-4 … 4.1e-4 per condition)
/// and 1.2e-4 / 0.9e-4 (|Z2|/|Z1| and |Z3|/|Z1|, absolute; at most 1.34e-4 per condition).
inline constexpr double kAmplitudeBiasRel = 4e-4;
inline constexpr double kHarmonicRatioBias = 1.5e-4;

/// One fingerprint beside the EDC: a per-level comparison of the measured response with the
/// model's harmonic-balance solution, in units of its σ (standard error over the cycles and the
/// bias floor above).
///
/// - `amplitude`: |Z1|. A missing stiffness power moves the resonance and with it the amplitude
///   at every level; damping laws change it mainly near resonance.
/// - `harmonic-2`, `harmonic-3`: |Z2|/|Z1| and |Z3|/|Z1|. Even harmonics come from the wells'
///   asymmetry (even powers of z), odd ones from odd powers and from friction's switch (a Coulomb
///   step makes 1/h harmonics, viscous and |ż|ż laws few); their growth with the amplitude tells
///   the laws apart where the EDC alone lets the paper's form mimic them.
struct ResponseFingerprint {
  std::string name;
  double chi2 = 0.0;                   // Σ residual²
  int levels = 0;                      // levels with a measurement
  std::vector<double> residual_sigma;  // per level in group order (NaN where not measured)
};

struct ResponseFingerprints {
  std::vector<ResponseFingerprint> items;  // amplitude, harmonic-2, harmonic-3
  double chi2 = 0.0;                       // their sum
  int count = 0;                           // residuals in it
};

/// The fingerprints of a model evaluation against the dataset it was evaluated on.
ResponseFingerprints response_fingerprints(const EdcDataset& data, const EdcEvaluation& evaluation);

}  // namespace oscilab::analysis
