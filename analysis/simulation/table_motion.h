#pragma once

namespace oscilab::analysis {

/// Motion of the shaking table at time t: displacement b, velocity ḃ and acceleration b̈ (SI).
struct TableState {
  double b_m = 0.0;
  double b_dot_m_s = 0.0;
  double b_ddot_m_s2 = 0.0;
};

/// The imposed base motion b(t) of §2. The oscillator feels f(t) = −m b̈(t) (eq. (1)).
///
/// Thread-safety: `at` is const and safe to call concurrently.
class TableMotion {
 public:
  virtual ~TableMotion() = default;
  virtual TableState at(double t_s) const = 0;
  /// Length of the motion in s; at() returns rest outside [0, duration_s()].
  virtual double duration_s() const = 0;
};

/// C²-smooth step from 0 (s ≤ 0) to 1 (s ≥ 1): the quintic 6s⁵ − 15s⁴ + 10s³, with its first and
/// second derivatives, so that a ramped amplitude keeps b̈ continuous.
struct SmoothStep {
  double value = 0.0;
  double slope = 0.0;      // d/ds
  double curvature = 0.0;  // d²/ds²
};
SmoothStep smooth_step(double s);

}  // namespace oscilab::analysis
