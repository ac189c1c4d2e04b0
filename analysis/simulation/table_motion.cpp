#include "analysis/simulation/table_motion.h"

namespace oscilab::analysis {

SmoothStep smooth_step(double s) {
  if (s <= 0.0) return {0.0, 0.0, 0.0};
  if (s >= 1.0) return {1.0, 0.0, 0.0};
  const double s2 = s * s;
  return {s2 * s * (10.0 + s * (-15.0 + 6.0 * s)), 30.0 * s2 * (1.0 - s) * (1.0 - s),
          60.0 * s * (1.0 - s) * (1.0 - 2.0 * s)};
}

}  // namespace oscilab::analysis
