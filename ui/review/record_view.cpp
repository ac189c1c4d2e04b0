#include "ui/review/record_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <QLabel>
#include <QMouseEvent>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "ui/plots/plot_hover_readout.h"
#include "ui/plots/plot_theme.h"
#include "ui/review/cursor_readout.h"
#include "ui/review/time_marks.h"

namespace oscilab::ui {
namespace {

// Channel colours (matplotlib's "tab10"): distinct, readable on white, colour-blind aware.
constexpr std::array<QRgb, 6> kChannelColours = {0x1f77b4, 0xd62728, 0x2ca02c,
                                                 0xff7f0e, 0x9467bd, 0x8c564b};
// The narrowest time window a zoom may reach, in samples.
constexpr double kMinWindowSamples = 10.0;
// Space left above and below the data when a value axis is fitted, as a fraction of its span.
constexpr double kValueMargin = 0.05;
// A press and release closer than this (Manhattan distance, px) is a click, not a drag.
constexpr double kClickTolerancePx = 4.0;

// "y — laser vibrometer (mass)": the channel, its sensor and what it measures (its role).
QString title_text(const daq::ChannelInfo& channel) {
  const QString role = QString::fromStdString(daq::to_string(channel.role));
  const QString name = QString::fromStdString(channel.name);
  if (channel.sensor.empty()) return name + " (" + role + ")";
  return name + " \u2014 " + QString::fromStdString(channel.sensor) + " (" + role + ")";
}

}  // namespace

RecordView::RecordView(QWidget* parent) : QWidget(parent) {
  readout_ = new QLabel(this);
  readout_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  readout_->setContentsMargins(6, 2, 6, 2);
  QFont readout_font = readout_->font();
  readout_font.setStyleHint(QFont::TypeWriter);
  readout_font.setFamily("DejaVu Sans Mono");
  readout_->setFont(readout_font);

  plot_ = new QCustomPlot(this);
  plot_->setInteractions(QCP::iRangeDrag | QCP::iRangeZoom);
  plot_->setProperty(PlotHoverReadouts::kOwnReadoutProperty, true);  // the readout line above
  plot_->setAutoAddPlottableToLegend(false);
  plot_->setNoAntialiasingOnDrag(true);
  plot_->setPlottingHint(QCP::phFastPolylines, true);
  plot_->setMouseTracking(true);
  plot_->addLayer("cursor", plot_->layer("main"), QCustomPlot::limAbove);
  cursor_layer_ = plot_->layer("cursor");
  cursor_layer_->setMode(QCPLayer::lmBuffered);
  margin_group_ = new QCPMarginGroup(plot_);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addWidget(readout_);
  layout->addWidget(plot_, 1);

  connect(plot_, &QCustomPlot::mouseMove, this, &RecordView::on_mouse_move);
  connect(plot_, &QCustomPlot::mousePress, this,
          [this](QMouseEvent* event) { press_position_ = event->position(); });
  connect(plot_, &QCustomPlot::mouseRelease, this, &RecordView::on_mouse_release);
  connect(plot_, &QCustomPlot::mouseDoubleClick, this, [this](QMouseEvent*) { fit(); });
  rebuild_plots();
}

RecordView::~RecordView() = default;

void RecordView::set_recording(std::shared_ptr<const daq::OpenedRecording> recording) {
  recording_ = std::move(recording);
  units_ = recording_ ? choose_display_units(*recording_) : std::vector<DisplayUnit>{};
  rebuild_plots();
  fit();
}

QCPAxisRect* RecordView::channel_rect(int channel) const {
  return channel >= 0 && std::size_t(channel) < rects_.size() ? rects_[std::size_t(channel)]
                                                              : nullptr;
}

QCPGraph* RecordView::channel_graph(int channel) const {
  return channel >= 0 && std::size_t(channel) < graphs_.size() ? graphs_[std::size_t(channel)]
                                                               : nullptr;
}

void RecordView::rebuild_plots() {
  plot_->clearItems();
  plot_->clearPlottables();
  plot_->plotLayout()->clear();
  rects_.clear();
  graphs_.clear();
  cursor_lines_.clear();
  cursor_tracers_.clear();
  mark_items_.clear();
  cursor_text_.clear();
  cursor_t_s_.reset();
  readout_->setText(tr("Move the mouse over the plots to read the values."));

  loaded_ = {};
  const bool showable =
      recording_ && recording_->samples && recording_->overview &&
      !recording_->sidecar.channels.empty() && recording_->sidecar.sample_rate_hz > 0.0 &&
      recording_->samples->channel_count() >= Eigen::Index(recording_->sidecar.channels.size());
  readout_->setVisible(showable);
  if (!showable) {
    auto* hint = new QCPTextElement(plot_, tr("No recording. File \u25b8 Open\u2026 (Ctrl+O)"));
    hint->setTextColor(Qt::gray);
    plot_->plotLayout()->addElement(0, 0, hint);
    plot_->replot();
    Q_EMIT cursor_text_changed(cursor_text_);
    return;
  }

  const auto& channels = recording_->sidecar.channels;
  const int channel_count = int(channels.size());
  plot_->plotLayout()->setRowSpacing(0);
  QFont title_font = font();
  title_font.setBold(true);

  for (int c = 0; c < channel_count; ++c) {
    const daq::ChannelInfo& channel = channels[std::size_t(c)];
    const DisplayUnit& unit = units_[std::size_t(c)];
    const bool bottom = c == channel_count - 1;
    const QColor colour(kChannelColours[std::size_t(c) % kChannelColours.size()]);

    // A title row above each plot names the channel and its sensor, where a legend would hide
    // the data (a long record fills its plot).
    auto* title = new QCPTextElement(plot_, title_text(channel), title_font);
    title->setTextColor(colour.darker(120));
    title->setTextFlags(Qt::AlignLeft | Qt::AlignVCenter);
    title->setMargins(QMargins(0, c == 0 ? 4 : 10, 0, 0));
    title->setAutoMargins(QCP::msLeft | QCP::msRight);
    title->setMarginGroup(QCP::msLeft | QCP::msRight, margin_group_);
    plot_->plotLayout()->addElement(2 * c, 0, title);

    auto* rect = new QCPAxisRect(plot_);
    plot_->plotLayout()->addElement(2 * c + 1, 0, rect);
    rect->setMarginGroup(QCP::msLeft | QCP::msRight, margin_group_);
    rect->setRangeDrag(Qt::Horizontal);
    rect->setRangeZoom(Qt::Horizontal);
    QCPAxis* time_axis = rect->axis(QCPAxis::atBottom);
    QCPAxis* value_axis = rect->axis(QCPAxis::atLeft);
    rect->setRangeDragAxes(time_axis, nullptr);
    rect->setRangeZoomAxes(time_axis, nullptr);
    time_axis->setTickLabels(bottom);
    if (bottom) time_axis->setLabel(tr("time [s]"));
    value_axis->setLabel(QString::fromStdString(channel.name + " [" + unit.symbol + "]"));
    value_axis->setNumberFormat("gb");
    // A frame around each plot: top and right axes as lines without ticks.
    for (QCPAxis::AxisType side : {QCPAxis::atTop, QCPAxis::atRight}) {
      rect->axis(side)->setVisible(true);
      rect->axis(side)->setTicks(false);
      rect->axis(side)->setTickLabels(false);
    }

    QCPGraph* graph = plot_->addGraph(time_axis, value_axis);
    graph->setName(title_text(channel));
    graph->setPen(QPen(colour, 1.0));
    graph->setAdaptiveSampling(true);

    auto* line = new QCPItemStraightLine(plot_);
    line->setLayer(cursor_layer_);
    line->setClipAxisRect(rect);
    line->setPen(QPen(QColor(60, 60, 60), 1.0, Qt::DashLine));
    draw_in_palette_colours(*line);
    for (QCPItemPosition* point : {line->point1, line->point2})
      point->setAxes(time_axis, value_axis);
    line->setVisible(false);

    auto* tracer = new QCPItemTracer(plot_);
    tracer->setLayer(cursor_layer_);
    tracer->setClipAxisRect(rect);
    tracer->position->setAxes(time_axis, value_axis);  // at the sample read, not a curve point
    tracer->setStyle(QCPItemTracer::tsCircle);
    tracer->setSize(9);
    tracer->setPen(QPen(QColor(30, 30, 30), 1.5));
    tracer->setBrush(QColor(255, 255, 255, 200));
    draw_in_palette_colours(*tracer);
    tracer->setVisible(false);

    connect(time_axis, qOverload<const QCPRange&>(&QCPAxis::rangeChanged), this,
            &RecordView::on_time_range_changed);
    rects_.push_back(rect);
    graphs_.push_back(graph);
    cursor_lines_.push_back(line);
    cursor_tracers_.push_back(tracer);
  }
  draw_marks();
  Q_EMIT cursor_text_changed(cursor_text_);
}

void RecordView::set_marks(std::vector<Mark> marks) {
  marks_ = std::move(marks);
  draw_marks();
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

void RecordView::draw_marks() {
  for (QCPAbstractItem* item : mark_items_) plot_->removeItem(item);
  mark_items_.clear();
  for (const Mark& mark : marks_) {
    for (std::size_t c = 0; c < rects_.size(); ++c) {
      add_time_mark(plot_, rects_[c], mark.t_s, c == 0 ? mark.text : QString(), mark_items_);
    }
  }
}

TimeWindow RecordView::full_window() const {
  if (!recording_ || !(recording_->sidecar.sample_rate_hz > 0.0)) return {0.0, 1.0};
  const double period_s = 1.0 / recording_->sidecar.sample_rate_hz;
  const double last_s = double(std::max<Eigen::Index>(recording_->sample_count() - 1, 0));
  return {0.0, std::max(last_s * period_s, period_s)};
}

void RecordView::fit() {
  if (rects_.empty()) return;
  const TimeWindow full = full_window();
  set_time_window(full.start_s, full.end_s);
  fit_value_axes(full);
  plot_->replot();
}

void RecordView::set_auto_value_range(bool on) {
  auto_value_range_ = on;
  if (rects_.empty()) return;
  fit_value_axes(on ? time_window() : full_window());
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

RecordView::SampleSpan RecordView::samples_in(TimeWindow window) const {
  const double rate_hz = recording_->sidecar.sample_rate_hz;
  const Eigen::Index n = recording_->sample_count();
  const Eigen::Index first =
      std::clamp<Eigen::Index>(Eigen::Index(std::floor(window.start_s * rate_hz)), 0, n);
  const Eigen::Index end =
      std::clamp<Eigen::Index>(Eigen::Index(std::ceil(window.end_s * rate_hz)) + 1, first, n);
  return {first, end};
}

void RecordView::fit_value_axes(TimeWindow window) {
  if (!recording_) return;
  // From the curves when they hold the whole window; else (the whole record's range asked for
  // while zoomed in) from the overview's buckets over it, which reach at most a bucket beyond.
  const SampleSpan span = samples_in(window);
  const bool drawn = loaded_.first <= span.first && span.end <= loaded_.end;
  const Eigen::Index bucket_samples =
      drawn ? 0 : recording_->overview->bucket_samples_for(span.first, span.end, 4096);
  for (std::size_t c = 0; c < graphs_.size(); ++c) {
    QCPGraph* graph = graphs_[c];
    bool found = false;
    QCPRange range;
    if (drawn) {
      range = graph->data()->valueRange(found, QCP::sdBoth, QCPRange(window.start_s, window.end_s));
    } else {
      const daq::SampleOverview::Envelope e =
          recording_->overview->envelope(Eigen::Index(c), span.first, span.end, bucket_samples);
      for (std::size_t k = 0; k < e.min.size(); ++k) {
        if (!std::isfinite(e.min[k]) || !std::isfinite(e.max[k])) continue;
        const double lo = units_[c].to_display(e.min[k]), hi = units_[c].to_display(e.max[k]);
        range = found ? QCPRange(std::min(range.lower, lo), std::max(range.upper, hi))
                      : QCPRange(lo, hi);
        found = true;
      }
    }
    if (!found) continue;
    if (range.size() <= 0.0) {
      const double half = range.upper == 0.0 ? 1.0 : 0.1 * std::abs(range.upper);
      range = QCPRange(range.upper - half, range.upper + half);
    }
    const double pad = kValueMargin * range.size();
    graph->valueAxis()->setRange(range.lower - pad, range.upper + pad);
  }
}

void RecordView::load_window(TimeWindow window) {
  if (!recording_ || graphs_.empty()) return;
  const double rate_hz = recording_->sidecar.sample_rate_hz;
  const Eigen::Index n = recording_->sample_count();
  const auto [first, end] = samples_in(window);
  const Eigen::Index shown = std::max<Eigen::Index>(end - first, 1);
  const int width_px = std::max(rects_.front()->width(), 800);
  const Eigen::Index max_buckets = Eigen::Index(kBucketsPerPixel) * width_px;
  // The points each sample range wants: the samples, or the overview's level for the window.
  Eigen::Index bucket_samples = 1;
  if (shown > kRawSamples) {
    bucket_samples = recording_->overview->bucket_samples_for(first, end, max_buckets);
  }
  if (loaded_.bucket_samples == bucket_samples && loaded_.first <= first && end <= loaded_.end) {
    return;  // what was read covers the window at the resolution it wants
  }
  // Around the window: on a pan (the window overlaps what was read at its resolution), what a
  // pan of a few widths reaches, up to 4 windows on either side of the samples (kRawSamples in
  // all at most); on a jump (a zoom, a click elsewhere), one window on either side, so that the
  // frame that lands reads a third as much; one of the overview's buckets.
  const bool pan =
      loaded_.bucket_samples == bucket_samples && first < loaded_.end && end > loaded_.first;
  const Eigen::Index around =
      bucket_samples == 1
          ? std::clamp<Eigen::Index>((kRawSamples - shown) / 2, 0, (pan ? 4 : 1) * shown)
          : shown;
  const Eigen::Index read_first = std::max<Eigen::Index>(first - around, 0);
  const Eigen::Index read_end = std::min(end + around, n);
  std::vector<QVector<QCPGraphData>> data(graphs_.size());
  if (bucket_samples == 1) {
    Eigen::MatrixXd rows;
    try {
      rows = recording_->samples->read(read_first, read_end - read_first);
    } catch (const InputError&) {  // the file went away or changed: keep what is drawn
      return;
    }
    for (std::size_t c = 0; c < graphs_.size(); ++c) {
      data[c].resize(qsizetype(rows.rows()));
      for (Eigen::Index i = 0; i < rows.rows(); ++i) {
        data[c][qsizetype(i)] = QCPGraphData(double(read_first + i) / rate_hz,
                                             units_[c].to_display(rows(i, Eigen::Index(c))));
      }
    }
  } else {
    for (std::size_t c = 0; c < graphs_.size(); ++c) {
      const daq::SampleOverview::Envelope wide =
          recording_->overview->envelope(Eigen::Index(c), read_first, read_end, bucket_samples);
      // Each bucket a stroke from its least value at its first sample to its greatest at its
      // last: a band as wide as the samples' spread, drawn from two points.
      data[c].resize(qsizetype(2 * wide.min.size()));
      for (std::size_t k = 0; k < wide.min.size(); ++k) {
        const Eigen::Index b0 = wide.first_sample + Eigen::Index(k) * wide.bucket_samples;
        const Eigen::Index b1 = std::min(b0 + wide.bucket_samples, n) - 1;
        data[c][qsizetype(2 * k)] =
            QCPGraphData(double(b0) / rate_hz, units_[c].to_display(wide.min[k]));
        data[c][qsizetype(2 * k + 1)] =
            QCPGraphData(double(b1) / rate_hz, units_[c].to_display(wide.max[k]));
      }
    }
  }
  for (std::size_t c = 0; c < graphs_.size(); ++c) {
    graphs_[c]->data()->set(data[c], true);
    // The buckets' strokes make a solid band: smoothing its edges costs more than the band.
    graphs_[c]->setAntialiased(bucket_samples == 1);
  }
  loaded_ = {read_first, read_end, bucket_samples};
}

void RecordView::set_time_window(double start_s, double end_s) {
  on_time_range_changed(QCPRange(start_s, end_s));
}

TimeWindow RecordView::time_window() const {
  if (rects_.empty()) return {};
  const QCPRange range = rects_.front()->axis(QCPAxis::atBottom)->range();
  return {range.lower, range.upper};
}

void RecordView::on_time_range_changed(const QCPRange& range) {
  if (syncing_time_axes_ || rects_.empty()) return;
  syncing_time_axes_ = true;
  const double min_width_s = kMinWindowSamples / recording_->sidecar.sample_rate_hz;
  const TimeWindow window =
      clamp_time_window({range.lower, range.upper}, full_window(), min_width_s);
  for (QCPAxisRect* rect : rects_) {
    rect->axis(QCPAxis::atBottom)->setRange(window.start_s, window.end_s);
  }
  syncing_time_axes_ = false;
  load_window(window);
  if (auto_value_range_) fit_value_axes(window);
  plot_->replot(QCustomPlot::rpQueuedReplot);
  Q_EMIT time_window_changed(window.start_s, window.end_s);
}

void RecordView::on_mouse_release(QMouseEvent* event) {
  if (rects_.empty() || event->button() != Qt::LeftButton) return;
  const QPointF position = event->position();
  if ((position - press_position_).manhattanLength() > kClickTolerancePx) return;  // a drag
  if (plot_->axisRectAt(position) == nullptr) return;
  set_cursor_follows_mouse(false);
  set_cursor_time(rects_.front()->axis(QCPAxis::atBottom)->pixelToCoord(position.x()));
  if (cursor_t_s_) Q_EMIT clicked(*cursor_t_s_);
}

void RecordView::set_cursor_follows_mouse(bool on) {
  if (on == cursor_follows_mouse_) return;
  cursor_follows_mouse_ = on;
  Q_EMIT cursor_follows_mouse_changed(on);
}

void RecordView::on_mouse_move(QMouseEvent* event) {
  if (rects_.empty() || !cursor_follows_mouse_) return;
  const QPointF position = event->position();
  if (plot_->axisRectAt(position) == nullptr) return;
  set_cursor_time(rects_.front()->axis(QCPAxis::atBottom)->pixelToCoord(position.x()));
}

void RecordView::set_cursor_time(double t_s) {
  if (!recording_ || rects_.empty()) return;
  const CursorReadout readout = read_cursor(*recording_, t_s);
  if (readout.sample < 0) return;
  for (std::size_t c = 0; c < rects_.size(); ++c) {
    cursor_lines_[c]->point1->setCoords(readout.t_s, 0.0);
    cursor_lines_[c]->point2->setCoords(readout.t_s, 1.0);
    cursor_lines_[c]->setVisible(true);
    const bool has_value = c < readout.values_si.size() && c < units_.size();
    if (has_value) {
      cursor_tracers_[c]->position->setCoords(readout.t_s,
                                              units_[c].to_display(readout.values_si[c]));
    }
    cursor_tracers_[c]->setVisible(has_value);
  }
  cursor_text_ = QString::fromStdString(format_readout(readout, *recording_, units_));
  cursor_t_s_ = readout.t_s;
  readout_->setText(cursor_text_);
  cursor_layer_->replot();
  Q_EMIT cursor_text_changed(cursor_text_);
  Q_EMIT cursor_moved(readout.t_s);
}

}  // namespace oscilab::ui
