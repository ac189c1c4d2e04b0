// The traces' time window: following, pausing and scrolling back.
#include "ui/live/live_timeline.h"

#include <gtest/gtest.h>

namespace oscilab::ui {
namespace {

TEST(LiveTimeline, FollowsTheStreamAndPausedStaysWhileTheAcquisitionGoesOn) {
  LiveTimeline timeline(10.0, 600.0);
  timeline.advance(3.0);  // less than a window: the first 10 s
  EXPECT_EQ(timeline.view().start_s, 0.0);
  EXPECT_EQ(timeline.view().end_s, 10.0);
  timeline.advance(42.0);
  EXPECT_EQ(timeline.view().start_s, 32.0);
  EXPECT_EQ(timeline.view().end_s, 42.0);

  timeline.pause();
  timeline.advance(100.0);
  EXPECT_FALSE(timeline.following());
  EXPECT_EQ(timeline.view().end_s, 42.0);  // the view stays, the stream went on
  timeline.scroll_to(20.0);
  EXPECT_EQ(timeline.view().end_s, 20.0);
  timeline.scroll_to(-5.0);  // before the oldest window: clamped to it
  EXPECT_EQ(timeline.view().start_s, 0.0);
  timeline.scroll_to(1e9);  // after now: clamped to now
  EXPECT_EQ(timeline.view().end_s, 100.0);

  // 10 minutes kept: once the history moved past the paused window, the oldest kept is shown.
  timeline.scroll_to(30.0);
  timeline.advance(700.0);
  EXPECT_EQ(timeline.scroll_range().start_s, 110.0);
  EXPECT_EQ(timeline.scroll_range().end_s, 700.0);
  EXPECT_EQ(timeline.view().start_s, 100.0);
  timeline.resume();
  EXPECT_EQ(timeline.view().end_s, 700.0);
  timeline.set_window_s(5000.0);  // no wider than the history
  EXPECT_EQ(timeline.window_s(), 600.0);
}

}  // namespace
}  // namespace oscilab::ui
