#pragma once

#include <optional>
#include <string>

#include "ui/display_units.h"

// Axes of live traces that follow the data without flicker or jitter.

namespace oscilab::ui {

/// The display unit of a live trace, kept while the values still read between 0.5 and 2000 in
/// it (so an axis does not flicker between mm and µm at a boundary), chosen afresh otherwise.
DisplayUnit sticky_display_unit(const std::optional<DisplayUnit>& current,
                                const std::string& si_unit, double max_abs);

/// A value axis that follows live data without jitter: it grows at once to hold [lo, hi] with a
/// 10 % margin, and shrinks to it only when the data fill less than 40 % of the range.
struct AxisRange {
  double lo = -1.0, hi = 1.0;
};
AxisRange follow_range(std::optional<AxisRange> current, double data_lo, double data_hi);

}  // namespace oscilab::ui
