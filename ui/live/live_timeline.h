#pragma once

#include "ui/time_window.h"

namespace oscilab::ui {

/// The time window of the traces: it follows the stream (its right edge is the newest sample),
/// or, paused, stays where the operator left it while the acquisition goes on; a scroll bar moves
/// a paused window over the history kept (the last history_s of stream time).
class LiveTimeline {
 public:
  static constexpr double kMinWindowS = 0.1;  // the shortest window shown

  explicit LiveTimeline(double window_s = 10.0, double history_s = 600.0);

  void set_window_s(double window_s);  // clamped to [0.1 s, history_s]
  double window_s() const { return window_s_; }
  double history_s() const { return history_s_; }

  /// The stream advanced to `stream_time_s` (the newest sample): a following window moves.
  void advance(double stream_time_s);
  /// Pauses the view at the window shown now; resume() follows the stream again.
  void pause();
  void resume();
  bool following() const { return following_; }

  /// The right edge a paused view can take: from the oldest sample kept + window, to now.
  TimeWindow scroll_range() const;
  /// Pauses (if following) and moves the right edge to `end_s`, clamped to scroll_range().
  void scroll_to(double end_s);
  /// The window to draw. Paused, the history may have moved past it: it is then the oldest
  /// window still kept.
  TimeWindow view() const;

 private:
  double window_s_;
  double history_s_;
  double now_s_ = 0.0;
  bool following_ = true;
  double paused_end_s_ = 0.0;
};

}  // namespace oscilab::ui
