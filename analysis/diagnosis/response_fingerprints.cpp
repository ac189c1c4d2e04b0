#include "analysis/diagnosis/response_fingerprints.h"

#include <cmath>
#include <limits>

namespace oscilab::analysis {

ResponseFingerprints response_fingerprints(const EdcDataset& data,
                                           const EdcEvaluation& evaluation) {
  ResponseFingerprints out;
  for (const char* name : {"amplitude", "harmonic-2", "harmonic-3"}) {
    out.items.push_back({name, 0.0, 0, {}});
  }
  std::size_t k = 0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const EdcGroup& group : data.groups) {
    for (const MeasuredLevel& m : group.levels) {
      // A level whose branch the model side cannot tell at its H (SigmaBudget::branch_ambiguous)
      // is left out: the fingerprints' σ has no model error to carry the gap.
      const bool ambiguous =
          k < evaluation.branch_ambiguous.size() && evaluation.branch_ambiguous[k];
      const bool measured = m.harmonic_cycles > 1 && k < evaluation.z1_abs_m.size() && !ambiguous;
      double residuals[3] = {nan, nan, nan};
      if (measured) {
        const double sigma_amplitude = std::hypot(m.z1_abs_se_m, kAmplitudeBiasRel * m.amplitude_m);
        residuals[0] = (m.amplitude_m - evaluation.z1_abs_m[k]) / sigma_amplitude;
        residuals[1] =
            (m.h2_ratio - evaluation.h2_ratio[k]) / std::hypot(m.h2_ratio_se, kHarmonicRatioBias);
        residuals[2] =
            (m.h3_ratio - evaluation.h3_ratio[k]) / std::hypot(m.h3_ratio_se, kHarmonicRatioBias);
      }
      for (int i = 0; i < 3; ++i) {
        ResponseFingerprint& f = out.items[static_cast<std::size_t>(i)];
        f.residual_sigma.push_back(residuals[i]);
        if (std::isfinite(residuals[i])) {
          f.chi2 += residuals[i] * residuals[i];
          ++f.levels;
        } else if (measured) {
          // The model has no solution at a measured level: the largest misfit a level can show
          // counts (as S_mod = 0 does in the EDC cost).
          f.chi2 += 1e6;
          ++f.levels;
        }
      }
      ++k;
    }
  }
  for (const ResponseFingerprint& f : out.items) {
    out.chi2 += f.chi2;
    out.count += f.levels;
  }
  return out;
}

}  // namespace oscilab::analysis
