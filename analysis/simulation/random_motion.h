#pragma once

#include <cstdint>
#include <vector>

#include "analysis/simulation/table_motion.h"

namespace oscilab::analysis {

/// Band-limited random table motion (§3.1's random tests): the force f = −m b̈ has a flat
/// spectrum between `low_hz` and `high_hz` and the given rms, random phases from `seed`. The
/// displacement fades in and out over `fade_s` (C²), so the table starts and ends at rest.
struct RandomMotionSpec {
  double duration_s = 120.0;
  double low_hz = 2.0;
  double high_hz = 30.0;
  double force_rms_n = 1.0;  // rms of −m b̈ over the steady middle part
  double fade_s = 2.0;
  std::uint64_t seed = 1;
};

/// Synthesised once on a fine grid (FFTW, inverse real DFT of the band spectrum), evaluated by
/// cubic Hermite interpolation between grid points. The grid runs at `grid_rate_hz`
/// (≥ 64 × high_hz), so the interpolation error is below 1e-6 of the signal (Hermite error
/// ∝ (Δt·ω)⁴/384).
class RandomMotion final : public TableMotion {
 public:
  RandomMotion(const RandomMotionSpec& spec, double mass_kg);  // throws InputError on bad spec

  TableState at(double t_s) const override;
  double duration_s() const override { return spec_.duration_s; }
  const RandomMotionSpec& spec() const { return spec_; }

 private:
  RandomMotionSpec spec_;
  double grid_dt_s_ = 0.0;
  // Grid values of b and its first three derivatives (the third is the slope of b̈ for Hermite).
  std::vector<double> b_, b_dot_, b_ddot_, b_dddot_;
};

}  // namespace oscilab::analysis
