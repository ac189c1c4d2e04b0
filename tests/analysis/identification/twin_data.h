#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/hbm/level_response.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/model/model.h"

namespace oscilab::analysis::testing {

/// The stepped-sine levels of the paper (§4.1): 0.2 → 2.7 N in 0.1 N steps.
inline std::vector<double> paper_levels_n() {
  std::vector<double> levels;
  for (int i = 0; i <= 25; ++i) levels.push_back(0.2 + 0.1 * i);
  return levels;
}

/// Five of them, for the quick tests (a random θ of a search can take tens of ms per level set).
inline std::vector<double> few_levels_n() { return {0.3, 0.9, 1.5, 2.1, 2.7}; }

/// Noise-free twin data: the model's own EDCs at the paper's levels in both wells, computed with
/// the same harmonic balance as the fit (so the truth is an exact minimiser: these tests check the
/// optimisers; the pipeline tests check the whole chain on simulated recordings).
inline EdcDataset twin_dataset(const Model& truth, const HbmOptions& hbm = {},
                               const std::vector<double>& levels = paper_levels_n()) {
  const LevelResponse plus = level_response(truth, 9.0, true, levels, hbm);
  const LevelResponse minus = level_response(truth, 9.0, false, levels, hbm);
  return edc_dataset_from_values(9.0, plus.f0_n, plus.edc_j, minus.f0_n, minus.edc_j);
}

/// The cost settings of twin-data tests: the fit's model side is the twin's generator (H of
/// `hbm`, no defect correction), with the fixed 1 % model-error floor these tests were written
/// for (the σ budget's own tests use their own data).
inline EdcCostSettings twin_settings(const HbmOptions& hbm = {}) {
  EdcCostSettings settings;
  settings.model_error_rel = 0.01;
  settings.adaptive_harmonics = false;
  settings.hbm = hbm;
  return settings;
}

/// Largest relative error of a fit over the parameters the identification targets require
/// (f_d(z±*), k_s, c, v_t); f_d(0) is weakly identified from EDCs and is reported, not required.
inline double worst_required_error(const FitResult& fit, const Eigen::VectorXd& truth) {
  double worst = 0.0;
  for (int i = 0; i < truth.size(); ++i) {
    if (fit.names[i] == "fd_zero_n") continue;
    worst = std::max(worst, std::abs(fit.theta(i) / truth(i) - 1.0));
  }
  return worst;
}

}  // namespace oscilab::analysis::testing
