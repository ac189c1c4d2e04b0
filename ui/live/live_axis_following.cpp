#include "ui/live/live_axis_following.h"

#include <algorithm>
#include <cmath>

namespace oscilab::ui {

DisplayUnit sticky_display_unit(const std::optional<DisplayUnit>& current,
                                const std::string& si_unit, double max_abs) {
  if (current && std::isfinite(max_abs) && max_abs > 0) {
    const double reading = current->to_display(max_abs);
    if (reading >= 0.5 && reading < 2000.0) return *current;
  }
  if (current && !(max_abs > 0)) return *current;  // no data: keep what is shown
  return choose_display_unit(si_unit, max_abs);
}

AxisRange follow_range(std::optional<AxisRange> current, double data_lo, double data_hi) {
  if (!std::isfinite(data_lo) || !std::isfinite(data_hi) || data_hi < data_lo) {
    return current.value_or(AxisRange{});
  }
  double span = data_hi - data_lo;
  if (span <= 0) span = std::max(std::abs(data_hi), 1e-12) * 0.2;
  const AxisRange fitted{data_lo - 0.1 * span, data_hi + 0.1 * span};
  if (!current) return fitted;
  const bool holds = current->lo <= data_lo && current->hi >= data_hi;
  const bool too_wide = (data_hi - data_lo) < 0.4 * (current->hi - current->lo);
  if (holds && !too_wide) return *current;
  return fitted;
}

}  // namespace oscilab::ui
