#pragma once

namespace oscilab::ui {

/// A span of the time axis, in s.
struct TimeWindow {
  double start_s = 0.0;
  double end_s = 0.0;

  double width_s() const { return end_s - start_s; }
};

/// Keeps a requested view window (after a zoom or pan) inside the recording's span `full`: no
/// wider than `full`, no narrower than `min_width_s` (about its centre), and shifted back inside
/// `full` when it sticks out, keeping its width. A non-finite or reversed request yields `full`.
TimeWindow clamp_time_window(TimeWindow requested, TimeWindow full, double min_width_s);

}  // namespace oscilab::ui
