#pragma once

#include <cmath>
#include <vector>

#include "analysis/pipeline/pipeline_settings.h"
#include "analysis/rfs/motion_signals.h"
#include "analysis/rfs/polynomial_fit.h"

namespace oscilab::analysis {

/// One bin of a slice of the restoring surface (CSV columns of docs/contracts.md §3).
struct SliceBin {
  double x = 0.0;        // bin centre: z_m for the stiffness slice, z_dot_m_s for a damping slice
  double force_n = 0.0;  // mean force of the samples in the bin
  int samples = 0;
};

/// The stiffness slice of §3.1–3.2: R at |ż| < ε_s approximates K(z) (the damping force is odd
/// in ż and averages out over a band symmetric in ż), binned in z, and the cubic of eq. (2)
/// fitted to the selected samples with standard errors.
struct StiffnessSlice {
  double velocity_band_m_s = 0.0;  // ε_s
  std::vector<SliceBin> bins;
  PolynomialFit fit;  // K(z) = Σ c_i z^i; paper: k3 = c3, k2 = c2, k1 = −c1, k0 = c0
  double z_min_m = 0.0, z_max_m = 0.0;  // travelled range of the selected samples (1–99 %)
};

/// A damping slice of Fig. 7c / Fig. 8: D = R − K_fit(z) at |z − z̄| < ε_d, binned in ż.
struct DampingSlice {
  double z_center_m = 0.0;
  double position_band_m = 0.0;  // ε_d
  std::vector<SliceBin> bins;
};

/// Calls visit(i) for every sample i of a record the slices may use: away from the record's ends
/// (within trim_s the zero-phase filters ring) and with a finite restoring force (the analysis
/// marks samples near invalid intervals non-finite).
template <typename Visit>
void for_each_slice_sample(const MotionSignals& s, double trim_s, Visit visit) {
  const Eigen::Index n = s.t_s.size();
  if (n == 0) return;
  const double t_end = s.t_s[n - 1];
  for (Eigen::Index i = 0; i < n; ++i) {
    if (s.t_s[i] < trim_s || s.t_s[i] > t_end - trim_s) continue;
    if (!std::isfinite(s.restoring_force_n[i])) continue;
    visit(i);
  }
}

/// Stacks several records (the paper stacks both stepped-sine tests, §3.2). Samples within
/// edge_trim_s of a record's ends are left out (zero-phase filters ring there). Throws
/// InputError when too few samples fall in the band for the fit.
StiffnessSlice stiffness_slice(const std::vector<const MotionSignals*>& records,
                               const PipelineSettings& settings, int degree = 3);

DampingSlice damping_slice(const std::vector<const MotionSignals*>& records,
                           const StiffnessSlice& stiffness, double z_center_m,
                           const PipelineSettings& settings);

}  // namespace oscilab::analysis
