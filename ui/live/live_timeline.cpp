#include "ui/live/live_timeline.h"

#include <algorithm>
#include <cmath>

namespace oscilab::ui {

LiveTimeline::LiveTimeline(double window_s, double history_s)
    : window_s_(window_s), history_s_(std::max(history_s, kMinWindowS)) {
  set_window_s(window_s);
}

void LiveTimeline::set_window_s(double window_s) {
  window_s_ = std::isfinite(window_s) ? std::clamp(window_s, kMinWindowS, history_s_) : 10.0;
}

void LiveTimeline::advance(double stream_time_s) {
  if (std::isfinite(stream_time_s)) now_s_ = stream_time_s;
}

void LiveTimeline::pause() {
  if (!following_) return;
  paused_end_s_ = view().end_s;
  following_ = false;
}

void LiveTimeline::resume() { following_ = true; }

TimeWindow LiveTimeline::scroll_range() const {
  const double end = std::max(now_s_, window_s_);
  const double oldest = std::max(0.0, now_s_ - history_s_);
  return {std::min(end, oldest + window_s_), end};
}

void LiveTimeline::scroll_to(double end_s) {
  following_ = false;
  const TimeWindow range = scroll_range();
  paused_end_s_ =
      std::isfinite(end_s) ? std::clamp(end_s, range.start_s, range.end_s) : range.end_s;
}

TimeWindow LiveTimeline::view() const {
  const TimeWindow range = scroll_range();
  const double end = following_ ? range.end_s : std::max(paused_end_s_, range.start_s);
  return {end - window_s_, end};
}

}  // namespace oscilab::ui
