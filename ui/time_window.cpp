#include "ui/time_window.h"

#include <algorithm>
#include <cmath>

namespace oscilab::ui {

TimeWindow clamp_time_window(TimeWindow requested, TimeWindow full, double min_width_s) {
  const bool finite = std::isfinite(requested.start_s) && std::isfinite(requested.end_s);
  if (!finite || !(requested.width_s() > 0.0) || requested.width_s() >= full.width_s()) {
    return full;
  }
  const double min_width = std::min(std::max(min_width_s, 0.0), full.width_s());
  if (requested.width_s() < min_width) {
    const double centre_s = 0.5 * (requested.start_s + requested.end_s);
    requested = {centre_s - 0.5 * min_width, centre_s + 0.5 * min_width};
  }
  const double width_s = requested.width_s();
  if (requested.start_s < full.start_s) requested = {full.start_s, full.start_s + width_s};
  if (requested.end_s > full.end_s) requested = {full.end_s - width_s, full.end_s};
  return requested;
}

}  // namespace oscilab::ui
