#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <QPointF>
#include <QString>
#include <QWidget>

#include "daq/recording/opened_recording.h"
#include "ui/display_units.h"
#include "ui/time_window.h"

class QCPAbstractItem;
class QCPAxisRect;
class QCPGraph;
class QCPItemStraightLine;
class QCPItemTracer;
class QCPLayer;
class QCPMarginGroup;
class QCPRange;
class QCustomPlot;
class QLabel;
class QMouseEvent;

namespace oscilab::ui {

/// Review of a whole recording: one plot per channel, stacked over a shared time axis, each in
/// its physical unit with an SI prefix chosen from its range (display_units.h).
///
/// Mouse: the wheel zooms and a drag pans the time axis of all channels together; a
/// double-click fits the whole record; value axes follow the data in view (optional); moving the
/// mouse places a cursor on every plot and shows t and each channel's value in a readout line above
/// the plots; a click places the cursor and holds it there (the mouse no longer moves it, see
/// set_cursor_follows_mouse). Annotations show as labelled vertical lines.
///
/// A record of any length is drawn in memory bounded by its overview (sample_overview.h): a time
/// window of up to kRawSamples samples is drawn from the samples themselves (read where they
/// live, with up to four windows on either side, kRawSamples in all at most, so that a pan
/// stays within what was read), a wider one from the min/max buckets of the overview's finest
/// level that gives at most kBucketsPerPixel buckets per pixel of the plot's width, over the
/// window and one window on either side, drawn without antialiasing (the strokes make a solid
/// band). A zoom or pan reads again only when the window leaves what was read or needs
/// another level. The curves are drawn with adaptive sampling, and the cursor lives on its own
/// buffered layer so that moving it does not redraw them.
///
/// Used from the UI thread only.
class RecordView : public QWidget {
  Q_OBJECT

 public:
  explicit RecordView(QWidget* parent = nullptr);
  ~RecordView() override;

  /// A window of up to this many samples per channel is drawn from the samples (512 s at
  /// 512 Hz); a wider one from the overview.
  static constexpr Eigen::Index kRawSamples = Eigen::Index{1} << 18;
  /// Overview buckets drawn per pixel of the plot's width (each bucket is a stroke from its
  /// least to its greatest value): one, the finest a pixel column shows.
  static constexpr int kBucketsPerPixel = 1;

  /// Shows `recording` (replacing what was shown) and fits the view to it. Null clears.
  void set_recording(std::shared_ptr<const daq::OpenedRecording> recording);
  /// The recording shown, or null.
  const daq::OpenedRecording* recording() const { return recording_.get(); }
  /// Samples per point of the curves drawn: 1 when they are the samples, the overview's bucket
  /// size otherwise; 0 with nothing shown.
  Eigen::Index samples_per_point() const { return loaded_.bucket_samples; }
  /// Display unit of each channel of the recording shown.
  const std::vector<DisplayUnit>& display_units() const { return units_; }

  /// Shows the whole record: time axis over all samples, each value axis over its data.
  void fit();
  /// Shows the time window [start_s, end_s] on all channels, limited to the record.
  void set_time_window(double start_s, double end_s);
  /// The time window shown, in s.
  TimeWindow time_window() const;

  /// On (the default): each value axis follows the data inside the time window shown, so a
  /// zoom also magnifies the values. Off: value axes keep the range of the whole record.
  void set_auto_value_range(bool on);
  bool auto_value_range() const { return auto_value_range_; }

  /// Places the cursor at the sample nearest to `t_s` and updates the readout.
  void set_cursor_time(double t_s);
  /// The cursor's time (a sample time), or nothing before the cursor was placed.
  std::optional<double> cursor_time() const { return cursor_t_s_; }
  /// On (the default): the cursor follows the mouse over the plots. Off: it stays where a click,
  /// set_cursor_time or a level selection put it. A click switches it off.
  void set_cursor_follows_mouse(bool on);
  bool cursor_follows_mouse() const { return cursor_follows_mouse_; }

  /// A labelled vertical line at a time on every channel plot (an annotation).
  struct Mark {
    double t_s = 0.0;
    QString text;
  };
  /// Replaces the marks drawn (they stay when the recording is replaced).
  void set_marks(std::vector<Mark> marks);
  const std::vector<Mark>& marks() const { return marks_; }
  /// The readout line: t and every channel's value at the cursor; empty without a cursor.
  QString cursor_text() const { return cursor_text_; }

  /// The plot, its per-channel axis rects and graphs (for tests and screenshots).
  QCustomPlot* plot() const { return plot_; }
  QCPAxisRect* channel_rect(int channel) const;
  QCPGraph* channel_graph(int channel) const;

 Q_SIGNALS:
  /// The readout changed (cursor moved, recording replaced).
  void cursor_text_changed(const QString& text);
  /// The cursor moved to `t_s` (by the mouse, a click or set_cursor_time).
  void cursor_moved(double t_s);
  /// A click (press and release without a drag) on a plot at time `t_s`; the cursor is there.
  void clicked(double t_s);
  /// set_cursor_follows_mouse changed, by a call or a click.
  void cursor_follows_mouse_changed(bool on);
  /// The time window shown changed (zoom, pan, fit, set_time_window).
  void time_window_changed(double start_s, double end_s);

 private:
  void rebuild_plots();
  void on_time_range_changed(const QCPRange& range);
  void on_mouse_move(QMouseEvent* event);
  void on_mouse_release(QMouseEvent* event);
  void draw_marks();
  TimeWindow full_window() const;
  void fit_value_axes(TimeWindow window);
  void load_window(TimeWindow window);
  struct SampleSpan {
    Eigen::Index first = 0, end = 0;
  };
  // The samples [first, end) a time window shows, clipped to the record.
  SampleSpan samples_in(TimeWindow window) const;

  // What the curves hold: samples [first, end) of every channel, one point per sample
  // (bucket_samples 1) or two per overview bucket.
  struct Loaded {
    Eigen::Index first = 0, end = 0, bucket_samples = 0;
  };

  std::shared_ptr<const daq::OpenedRecording> recording_;
  Loaded loaded_;
  std::vector<DisplayUnit> units_;
  QLabel* readout_ = nullptr;
  QCustomPlot* plot_ = nullptr;
  QCPLayer* cursor_layer_ = nullptr;
  QCPMarginGroup* margin_group_ = nullptr;  // aligns the plots' left and right edges
  std::vector<QCPAxisRect*> rects_;
  std::vector<QCPGraph*> graphs_;
  std::vector<QCPItemStraightLine*> cursor_lines_;
  std::vector<QCPItemTracer*> cursor_tracers_;
  QString cursor_text_;
  std::optional<double> cursor_t_s_;
  bool cursor_follows_mouse_ = true;
  QPointF press_position_;
  std::vector<Mark> marks_;
  std::vector<QCPAbstractItem*> mark_items_;
  bool syncing_time_axes_ = false;
  bool auto_value_range_ = true;
};

}  // namespace oscilab::ui
