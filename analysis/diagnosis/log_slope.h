#pragma once

#include <vector>

namespace oscilab::analysis {

/// The power law y ∝ x^slope fitted by least squares on (ln x, ln y), with the slope's standard
/// error and 95 % interval (Student t, n − 2 degrees of freedom). The EDC of a damping law grows
/// with the response amplitude Z as Z^p with p = 1 (Coulomb), 2 (viscous), 3 (quadratic damping,
/// small presliding loops) or 4 (cubic damping): the slope names the law.
struct LogSlope {
  int points = 0;  // pairs with x, y > 0 used
  double slope = 0.0;
  double standard_error = 0.0;  // inf with two points (no spread estimate)
  double lower_95 = 0.0;
  double upper_95 = 0.0;
  bool valid() const { return points >= 2; }
};

/// Pairs with x ≤ 0 or y ≤ 0 are skipped. Fewer than two usable pairs give points < 2.
LogSlope log_slope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace oscilab::analysis
