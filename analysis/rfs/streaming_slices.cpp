#include "analysis/rfs/streaming_slices.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "analysis/common/quantile.h"

namespace oscilab::analysis {
namespace {

template <typename T>
void keep_newest(std::deque<T>& values, std::size_t max_size) {
  while (values.size() > max_size) values.pop_front();
}

}  // namespace

StreamingSlices::StreamingSlices(Options options) : options_(options) {}

void StreamingSlices::reset() {
  taken_until_s_ = -1.0;
  recent_z_.clear();
  recent_z_dot_.clear();
  stiffness_.clear();
  damping_.clear();
  velocity_band_m_s_ = centre_m_ = position_band_m_ = 0.0;
}

std::size_t StreamingSlices::add(const std::vector<double>& t_s, const std::vector<double>& z_m,
                                 const std::vector<double>& z_dot_m_s,
                                 const std::vector<double>& restoring_force_n,
                                 double sample_rate_hz) {
  assert(z_m.size() == t_s.size() && z_dot_m_s.size() == t_s.size() &&
         restoring_force_n.size() == t_s.size());
  struct Sample {
    double z, z_dot, r;
  };
  std::vector<Sample> fresh;
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    if (!(t_s[i] > taken_until_s_)) continue;
    const double z = z_m[i], z_dot = z_dot_m_s[i], r = restoring_force_n[i];
    if (!std::isfinite(z) || !std::isfinite(z_dot) || !std::isfinite(r)) continue;
    fresh.push_back({z, z_dot, r});
    taken_until_s_ = t_s[i];
  }
  if (fresh.empty()) return 0;

  // The bands from the last N cycles, these samples included.
  const double per_cycle = options_.frequency_hz > 0 && sample_rate_hz > 0
                               ? sample_rate_hz / options_.frequency_hz
                               : 64.0;
  const auto recent = static_cast<std::size_t>(std::max(64.0, options_.cycles * per_cycle));
  for (const Sample& s : fresh) {
    recent_z_.push_back(s.z);
    recent_z_dot_.push_back(std::abs(s.z_dot));
  }
  keep_newest(recent_z_, recent);
  keep_newest(recent_z_dot_, recent);
  const std::vector<double> z(recent_z_.begin(), recent_z_.end());
  velocity_band_m_s_ =
      options_.velocity_band_rel * quantile({recent_z_dot_.begin(), recent_z_dot_.end()}, 0.99);
  const std::vector<double> z_levels = quantiles(z, {0.01, 0.5, 0.99});
  centre_m_ = z_levels[1];
  position_band_m_ = options_.position_band_rel * (z_levels[2] - z_levels[0]);

  for (const Sample& s : fresh) {
    const bool positive = s.z > options_.well_boundary_m;
    if (std::abs(s.z_dot) < velocity_band_m_s_) stiffness_.push_back({s.z, s.r, positive});
    if (std::abs(s.z - centre_m_) < position_band_m_) damping_.push_back({s.z_dot, s.r, positive});
  }
  keep_newest(stiffness_, options_.max_points);
  keep_newest(damping_, options_.max_points);
  return fresh.size();
}

}  // namespace oscilab::analysis
