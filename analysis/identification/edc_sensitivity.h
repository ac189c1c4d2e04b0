#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/identification/edc_objective.h"

namespace oscilab::analysis {

/// One curve of the sensitivity study of §5.1 (Fig. 16): the model's EDC against f0 in one well
/// with one parameter (group) scaled by `factor` and the others at θ̄.
struct SensitivityCurve {
  std::string parameter;  // "kd" (all f_d values together, the paper's k_d), "ks", or a θ name
  double factor = 1.0;
  bool positive_well = true;
  double freq_hz = 0.0;
  std::vector<double> f0_n;
  std::vector<double> edc_j;
  bool ok = true;  // the model was solved at every level
};

/// §5.1: each parameter at `factors` × its identified value, the dynamic friction values of
/// eq. (9) together as k_d · f_d(z). For k_s the factor scales the static excess k_s − 1 of
/// eq. (6) (k_s itself below 1 would not be a friction law: 20 % of k_s = 1.07 is 0.21). Curves
/// are computed at each group's measured levels; factor 1 is the reference curve. Curves run in
/// parallel on `threads` threads.
std::vector<SensitivityCurve> edc_sensitivity(
    const EdcObjective& objective, const Eigen::VectorXd& theta,
    const std::vector<double>& factors = {0.2, 0.5, 0.7, 1.0, 1.2, 1.5}, int threads = 0);

}  // namespace oscilab::analysis
