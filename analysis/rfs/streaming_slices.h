#pragma once

#include <cstddef>
#include <deque>
#include <vector>

namespace oscilab::analysis {

/// A point of a slice or loop, tagged with the well it belongs to.
struct WellPoint {
  double x = 0.0;
  double y = 0.0;
  bool positive = true;  // z above the well boundary
};

/// The stiffness and damping slices of the restoring-force surface as it grows live (§3.1–3.2):
/// samples of (z, ż, R) taken as they arrive; the stiffness slice keeps (z, R) where
/// |ż| < velocity_band_rel × p99(|ż|) of the last `cycles` cycles, the damping slice keeps
/// (ż, R) where |z − z̄| < position_band_rel × (z range), z̄ and the range over the last
/// `cycles` cycles (the current well's centre and travel). Each keeps its newest max_points.
///
/// With a window of cycles that holds a whole record fed at once, the stiffness slice selects
/// the samples of the offline stiffness_slice (restoring_force_slices.h): the same band rule
/// over the same samples.
class StreamingSlices {
 public:
  struct Options {
    double velocity_band_rel = 0.02;  // as PipelineSettings::stiffness_velocity_band_rel
    /// Wider than the offline 0.01 of the record's range: here the range is one level's.
    double position_band_rel = 0.05;
    int cycles = 30;  // N: the last N cycles set the bands
    double frequency_hz = 9.0;
    double well_boundary_m = 0.0;
    std::size_t max_points = 20000;
  };
  StreamingSlices() : StreamingSlices(Options()) {}
  explicit StreamingSlices(Options options);
  const Options& options() const { return options_; }
  void reset();
  /// The time up to which samples were taken; ask for samples from there on.
  double taken_until_s() const { return taken_until_s_; }
  /// Takes the samples (one per sample period; t_s, z_m, z_dot_m_s and restoring_force_n of
  /// equal length) after taken_until_s() whose z, ż and R are finite. Returns how many were
  /// new.
  std::size_t add(const std::vector<double>& t_s, const std::vector<double>& z_m,
                  const std::vector<double>& z_dot_m_s,
                  const std::vector<double>& restoring_force_n, double sample_rate_hz);

  const std::deque<WellPoint>& stiffness() const { return stiffness_; }
  const std::deque<WellPoint>& damping() const { return damping_; }
  double velocity_band_m_s() const { return velocity_band_m_s_; }
  double damping_centre_m() const { return centre_m_; }
  double position_band_m() const { return position_band_m_; }

 private:
  Options options_;
  double taken_until_s_ = -1.0;
  std::deque<double> recent_z_, recent_z_dot_;  // the last N cycles
  std::deque<WellPoint> stiffness_, damping_;
  double velocity_band_m_s_ = 0.0, centre_m_ = 0.0, position_band_m_ = 0.0;
};

}  // namespace oscilab::analysis
