#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "analysis/hbm/harmonic_balance.h"
#include "analysis/model/model.h"

namespace oscilab::analysis::testing {

/// The largest difference between harmonic balance's analytic Jacobian (H = 5, 9 Hz, 1 N) and
/// central differences of its residual (step 1e-10 m), relative to the Jacobian's largest entry,
/// on a fixed orbit with harmonics 1 … 5 about the positive well.
inline double jacobian_error_rel(const Model& model) {
  HbmOptions options;
  options.harmonics = 5;
  HarmonicBalance hbm(model, 9.0, options);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(hbm.size());
  for (int i = 0; i < hbm.size(); ++i) x[i] = 4e-4 * std::sin(1.7 * i + 0.3) / (1 + i);
  x[0] = model.well(true).z_m;
  Eigen::VectorXd r, r_plus, r_minus;
  Eigen::MatrixXd jacobian;
  hbm.residual_and_jacobian(x, 1.0, r, jacobian);
  const double h = 1e-10;
  double worst = 0.0;
  for (int j = 0; j < hbm.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    hbm.residual(xp, 1.0, r_plus);
    hbm.residual(xm, 1.0, r_minus);
    worst = std::max(worst, ((r_plus - r_minus) / (2 * h) - jacobian.col(j)).cwiseAbs().maxCoeff());
  }
  return worst / jacobian.cwiseAbs().maxCoeff();
}

}  // namespace oscilab::analysis::testing
