#include "analysis/rfs/restoring_force_slices.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "analysis/common/input_error.h"
#include "analysis/common/quantile.h"

namespace oscilab::analysis {
namespace {

std::vector<SliceBin> bin_samples(const std::vector<double>& x, const std::vector<double>& y,
                                  double lo, double hi, int bins) {
  std::vector<SliceBin> out(static_cast<std::size_t>(bins));
  const double width = (hi - lo) / bins;
  for (int b = 0; b < bins; ++b) out[static_cast<std::size_t>(b)].x = lo + (b + 0.5) * width;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const int b = static_cast<int>(std::floor((x[i] - lo) / width));
    if (b < 0 || b >= bins) continue;
    out[static_cast<std::size_t>(b)].force_n += y[i];
    ++out[static_cast<std::size_t>(b)].samples;
  }
  std::vector<SliceBin> filled;
  for (SliceBin& bin : out) {
    if (bin.samples == 0) continue;
    bin.force_n /= bin.samples;
    filled.push_back(bin);
  }
  return filled;
}

}  // namespace

StiffnessSlice stiffness_slice(const std::vector<const MotionSignals*>& records,
                               const PipelineSettings& settings, int degree) {
  Eigen::Index total = 0;
  for (const MotionSignals* s : records) total += s->t_s.size();
  std::vector<double> speeds;
  speeds.reserve(static_cast<std::size_t>(total));
  for (const MotionSignals* s : records) {
    for_each_slice_sample(*s, settings.edge_trim_s,
                          [&](Eigen::Index i) { speeds.push_back(std::abs(s->z_dot_m_s[i])); });
  }
  StiffnessSlice slice;
  slice.velocity_band_m_s =
      settings.stiffness_velocity_band_rel * quantile(std::move(speeds), 0.99);
  std::vector<double> z, r;
  z.reserve(static_cast<std::size_t>(total));  // an upper bound: pages beyond the band's untouched
  r.reserve(static_cast<std::size_t>(total));
  for (const MotionSignals* s : records) {
    for_each_slice_sample(*s, settings.edge_trim_s, [&](Eigen::Index i) {
      if (std::abs(s->z_dot_m_s[i]) < slice.velocity_band_m_s) {
        z.push_back(s->z_m[i]);
        r.push_back(s->restoring_force_n[i]);
      }
    });
  }
  if (static_cast<int>(z.size()) < 10 * (degree + 1)) {
    throw InputError("restoring force: only " + std::to_string(z.size()) +
                     " samples with |z_dot| < " + std::to_string(slice.velocity_band_m_s) +
                     " m/s: too few for the stiffness slice");
  }
  const std::vector<double> z_range = quantiles(z, {0.01, 0.99});
  slice.z_min_m = z_range[0];
  slice.z_max_m = z_range[1];
  slice.bins = bin_samples(z, r, slice.z_min_m, slice.z_max_m, settings.stiffness_bins);
  slice.fit = fit_polynomial(
      Eigen::Map<const Eigen::VectorXd>(z.data(), static_cast<Eigen::Index>(z.size())),
      Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size())), degree);
  return slice;
}

DampingSlice damping_slice(const std::vector<const MotionSignals*>& records,
                           const StiffnessSlice& stiffness, double z_center_m,
                           const PipelineSettings& settings) {
  DampingSlice slice;
  slice.z_center_m = z_center_m;
  slice.position_band_m =
      settings.damping_position_band_rel * (stiffness.z_max_m - stiffness.z_min_m);
  std::vector<double> v, d;
  for (const MotionSignals* s : records) {
    for_each_slice_sample(*s, settings.edge_trim_s, [&](Eigen::Index i) {
      if (std::abs(s->z_m[i] - z_center_m) < slice.position_band_m) {
        v.push_back(s->z_dot_m_s[i]);
        d.push_back(s->restoring_force_n[i] - stiffness.fit.value(s->z_m[i]));
      }
    });
  }
  if (v.size() < 10) return slice;
  const std::vector<double> v_range = quantiles(v, {0.01, 0.99});
  const double extent = std::max(std::abs(v_range[0]), std::abs(v_range[1]));
  slice.bins = bin_samples(v, d, -extent, extent, settings.damping_bins);
  return slice;
}

}  // namespace oscilab::analysis
