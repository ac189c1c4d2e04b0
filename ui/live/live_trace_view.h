#pragma once

#include <optional>
#include <vector>

#include <QWidget>

#include "daq/live/acquisition.h"
#include "ui/display_units.h"
#include "ui/live/live_axis_following.h"
#include "ui/live/live_timeline.h"

class QCPAxisRect;
class QCPGraph;
class QCPItemText;
class QCustomPlot;
class QDoubleSpinBox;
class QPushButton;
class QScrollBar;

namespace oscilab::ui {

/// The traces of b̈, b, y, z and f, stacked over one stream-time axis, over a window that
/// follows the stream, or paused (the acquisition goes on) and scrolled back over the history
/// kept (LiveTimeline); with the window length, Pause view and the scroll bar under them. Each
/// trace keeps its display unit and its value range while the data allow (live_axis_following.h),
/// so that axes do not flicker. Used from the UI thread only.
class LiveTraceView : public QWidget {
  Q_OBJECT

 public:
  explicit LiveTraceView(QWidget* parent = nullptr);

  /// Shows `acquisition` from now on (null: nothing), a fresh view that follows it, the traces
  /// named after `layout` (the channels' quantities; none: the defaults).
  void show_stream(const daq::Acquisition* acquisition, const std::optional<daq::Sidecar>& layout);
  /// The stream's layout became known (a network sender's): the traces' names and units.
  void set_layout(const std::optional<daq::Sidecar>& layout);

  /// Reads the window from the acquisition and redraws (a queued replot).
  void refresh();

  void set_window_s(double window_s);
  double window_s() const;
  /// Pauses the traces (the acquisition goes on) or follows the stream again.
  void set_paused(bool paused);
  bool paused() const { return !timeline_.following(); }
  /// Pauses the view and shows the window ending at `end_s` (stream time).
  void scroll_to(double end_s);
  /// The window of the traces, in stream time.
  TimeWindow view_window() const { return timeline_.view(); }
  /// Frames drawn since construction (QCustomPlot replots).
  long frames_drawn() const { return frames_; }

  QCustomPlot* plot() const { return plot_; }

 Q_SIGNALS:
  /// The operator changed the window length (the session keeps it).
  void window_changed(double window_s);

 protected:
  void resizeEvent(QResizeEvent* event) override;

 private:
  void sync_scroll_bar();
  void name_traces();
  void elide_names();  // each trace's name elided to its axes' width

  const daq::Acquisition* acquisition_ = nullptr;
  std::optional<daq::Sidecar> layout_;
  LiveTimeline timeline_;
  daq::TraceHistory traces_;  // reused buffer
  std::vector<std::optional<DisplayUnit>> units_;
  std::vector<std::optional<AxisRange>> ranges_;
  long frames_ = 0;

  QCustomPlot* plot_ = nullptr;
  std::vector<QCPAxisRect*> rects_;
  std::vector<QCPGraph*> graphs_;
  std::vector<QCPItemText*> names_;
  QDoubleSpinBox* window_box_ = nullptr;
  QPushButton* pause_button_ = nullptr;
  QScrollBar* scroll_bar_ = nullptr;
};

}  // namespace oscilab::ui
