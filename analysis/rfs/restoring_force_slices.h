#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "analysis/pipeline/pipeline_settings.h"
#include "analysis/rfs/motion_signals.h"
#include "analysis/rfs/motion_spans.h"
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

/// Calls visit(i) for every sample i of a span of a record's motion that the slices may use: away
/// from the record's ends (within trim_s of its first sample at t = 0 or of its last at
/// record_end_s the zero-phase filters ring) and with a finite restoring force (the analysis
/// marks samples near invalid intervals non-finite).
template <typename Visit>
void for_each_slice_sample(const MotionSignals& s, double record_end_s, double trim_s,
                           Visit visit) {
  const Eigen::Index n = s.t_s.size();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (s.t_s[i] < trim_s || s.t_s[i] > record_end_s - trim_s) continue;
    if (!std::isfinite(s.restoring_force_n[i])) continue;
    visit(i);
  }
}

/// The same over a whole record's motion.
template <typename Visit>
void for_each_slice_sample(const MotionSignals& s, double trim_s, Visit visit) {
  if (s.t_s.size() == 0) return;
  for_each_slice_sample(s, s.t_s[s.t_s.size() - 1], trim_s, visit);
}

/// One pass over the motion of every record the slices stack: calls visit(span, record_end_s)
/// for each span of each record (motion_spans.h), in the same order on every call. The slices
/// make six passes in all, so a record streamed from its file is never held whole.
using MotionPass = std::function<void(const MotionSpanVisit& visit)>;

/// Stacks several records (the paper stacks both stepped-sine tests, §3.2). Samples within
/// edge_trim_s of a record's ends are left out (zero-phase filters ring there). `max_samples`
/// bounds the samples a pass gives (the p99 of |ż| keeps its upper 1 %). Throws InputError when
/// too few samples fall in the band for the fit.
StiffnessSlice stiffness_slice(const MotionPass& pass, Eigen::Index max_samples,
                               const PipelineSettings& settings, int degree = 3);

/// The damping slice at each of `z_centers_m`, in two passes (`max_samples` as for the stiffness
/// slice).
std::vector<DampingSlice> damping_slices(const MotionPass& pass, Eigen::Index max_samples,
                                         const StiffnessSlice& stiffness,
                                         const std::vector<double>& z_centers_m,
                                         const PipelineSettings& settings);

/// The same over records in memory.
StiffnessSlice stiffness_slice(const std::vector<const MotionSignals*>& records,
                               const PipelineSettings& settings, int degree = 3);

DampingSlice damping_slice(const std::vector<const MotionSignals*>& records,
                           const StiffnessSlice& stiffness, double z_center_m,
                           const PipelineSettings& settings);

}  // namespace oscilab::analysis
