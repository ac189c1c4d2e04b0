#include "ui/live/live_trace_view.h"
#include "ui/qt_text.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <QDoubleSpinBox>
#include <QFontMetrics>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QScrollBar>
#include <QSignalBlocker>
#include <QVBoxLayout>

#include <qcustomplot.h>

namespace oscilab::ui {
namespace {

enum Trace { kBaseTrace, kBTrace, kMassTrace, kZTrace, kForceTrace, kTraceCount };
const QColor kTraceColours[kTraceCount] = {QColor(0, 114, 178), QColor(0, 158, 115),
                                           QColor(204, 121, 167), QColor(20, 20, 20),
                                           QColor(213, 94, 0)};

// Range of the finite values of `v` (lo > hi when there are none).
void finite_range(const std::vector<double>& v, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (double x : v) {
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  }
}

QString trace_name(int trace, const std::optional<daq::Sidecar>& layout) {
  daq::Quantity base = daq::Quantity::Acceleration, mass = daq::Quantity::Displacement;
  bool relative = false;
  if (layout) {
    for (const daq::ChannelInfo& c : layout->channels) {
      if (c.role == daq::ChannelRole::Base) base = c.quantity;
      if (c.role == daq::ChannelRole::Mass) mass = c.quantity;
      if (c.role == daq::ChannelRole::Relative) relative = true, mass = c.quantity;
    }
  }
  switch (trace) {
    case kBaseTrace:
      return base == daq::Quantity::Acceleration ? QObject::tr("b\u0308 table acceleration")
             : base == daq::Quantity::Velocity   ? QObject::tr("b\u0307 table velocity")
                                                 : QObject::tr("b table (measured)");
    case kBTrace:
      return QObject::tr("b table displacement (integrated, 2 s behind)");
    case kMassTrace:
      return relative ? QObject::tr("z relative displacement (measured)")
             : mass == daq::Quantity::Displacement ? QObject::tr("y mass position (vibrometer)")
                                                   : QObject::tr("mass channel");
    case kZTrace:
      return QObject::tr("z = y \u2212 b (2 s behind)");
    default:
      return QObject::tr("f = \u2212m b\u0308");
  }
}

QString trace_symbol(int trace) {
  static const char* symbols[kTraceCount] = {"b\u0308", "b", "y", "z", "f"};
  return QString::fromUtf8(symbols[trace]);
}

std::string trace_si_unit(int trace, const std::optional<daq::Sidecar>& layout) {
  if (trace == kBTrace || trace == kZTrace) return "m";
  if (trace == kForceTrace) return "N";
  if (layout) {
    for (const daq::ChannelInfo& c : layout->channels) {
      if (trace == kBaseTrace && c.role == daq::ChannelRole::Base) return si_unit_of(c.quantity);
      if (trace == kMassTrace &&
          (c.role == daq::ChannelRole::Mass || c.role == daq::ChannelRole::Relative)) {
        return si_unit_of(c.quantity);
      }
    }
  }
  return trace == kBaseTrace ? "m/s^2" : "m";
}

}  // namespace

LiveTraceView::LiveTraceView(QWidget* parent) : QWidget(parent) {
  setObjectName("live_trace_view");
  units_.resize(kTraceCount);
  ranges_.resize(kTraceCount);

  // One axis rect per trace, stacked over a shared time axis.
  plot_ = new QCustomPlot;
  plot_->setObjectName("trace_plot");
  plot_->setMinimumSize(220, 300);  // four traces stay readable on a 768-high screen
  plot_->plotLayout()->clear();
  plot_->plotLayout()->setRowSpacing(2);
  auto* margins = new QCPMarginGroup(plot_);
  for (int k = 0; k < kTraceCount; ++k) {
    auto* rect = new QCPAxisRect(plot_);
    plot_->plotLayout()->addElement(k, 0, rect);
    rect->setMarginGroup(QCP::msLeft | QCP::msRight, margins);
    QCPAxis* time_axis = rect->axis(QCPAxis::atBottom);
    QCPAxis* value_axis = rect->axis(QCPAxis::atLeft);
    const bool bottom = k == kTraceCount - 1;
    time_axis->setTickLabels(bottom);
    if (bottom) time_axis->setLabel(tr("stream time [s]"));
    value_axis->setNumberFormat("gb");
    value_axis->setLabel(trace_symbol(k));
    for (QCPAxis::AxisType side : {QCPAxis::atTop, QCPAxis::atRight}) {
      rect->axis(side)->setVisible(true);
      rect->axis(side)->setTicks(false);
      rect->axis(side)->setTickLabels(false);
    }
    QCPGraph* graph = plot_->addGraph(time_axis, value_axis);
    graph->setPen(QPen(kTraceColours[k], 1.0));
    graph->setAntialiased(false);
    auto* name = new QCPItemText(plot_);
    name->setObjectName("trace_name");
    name->setClipAxisRect(rect);
    name->position->setAxisRect(rect);
    name->position->setType(QCPItemPosition::ptAxisRectRatio);
    name->position->setCoords(0.01, 0.03);
    name->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
    name->setColor(kTraceColours[k].darker(130));
    name->setBrush(QColor(255, 255, 255, 200));
    name->setText(trace_name(k, std::nullopt));
    names_.push_back(name);
    rects_.push_back(rect);
    graphs_.push_back(graph);
  }
  connect(plot_, &QCustomPlot::afterReplot, this, [this] { ++frames_; });

  // The window's controls.
  window_box_ = new QDoubleSpinBox;
  window_box_->setObjectName("window_s");
  window_box_->setRange(1.0, 600.0);
  window_box_->setDecimals(0);
  window_box_->setValue(10.0);
  window_box_->setSuffix(tr(" s"));
  window_box_->setToolTip(tr("Time shown by the traces (up to the 10 minutes kept)"));
  connect(window_box_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
    timeline_.set_window_s(v);
    sync_scroll_bar();
    refresh();
    Q_EMIT window_changed(v);
  });
  pause_button_ = new QPushButton(tr("Pause view"));
  pause_button_->setObjectName("pause_view");
  pause_button_->setCheckable(true);
  pause_button_->setToolTip(
      tr("Freeze the traces and scroll back over the last 10 minutes; the acquisition goes on"));
  connect(pause_button_, &QPushButton::toggled, this, &LiveTraceView::set_paused);
  scroll_bar_ = new QScrollBar(Qt::Horizontal);
  scroll_bar_->setObjectName("view_scroll");
  scroll_bar_->setToolTip(tr("Scroll back over the history (pauses the view)"));
  connect(scroll_bar_, &QScrollBar::valueChanged, this,
          [this](int value) { scroll_to(0.1 * value); });
  auto* controls = new QHBoxLayout;
  controls->addWidget(new QLabel(tr("Window")));
  controls->addWidget(window_box_);
  controls->addWidget(pause_button_);
  controls->addWidget(scroll_bar_, 1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(plot_, 1);
  layout->addLayout(controls);
}

void LiveTraceView::show_stream(const daq::Acquisition* acquisition,
                                const std::optional<daq::Sidecar>& layout) {
  acquisition_ = acquisition;
  timeline_ = LiveTimeline(window_box_->value(), daq::AcquisitionOptions{}.history_s);
  pause_button_->setChecked(false);
  std::fill(units_.begin(), units_.end(), std::nullopt);
  std::fill(ranges_.begin(), ranges_.end(), std::nullopt);
  set_layout(layout);
}

void LiveTraceView::set_layout(const std::optional<daq::Sidecar>& layout) {
  layout_ = layout;
  elide_names();
}

void LiveTraceView::elide_names() {
  // Each trace's name within its axes: elided ("…") on a narrow plot rather than cut.
  for (int k = 0; k < kTraceCount; ++k) {
    QCPItemText* name = names_[std::size_t(k)];
    const int width = rects_[std::size_t(k)]->width() - 12;
    const QString text = trace_name(k, layout_);
    name->setText(width > 0 ? QFontMetrics(name->font()).elidedText(text, Qt::ElideRight, width)
                            : text);
  }
}

void LiveTraceView::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  plot_->plotLayout()->update(QCPLayoutElement::upLayout);  // the axes' new sizes
  elide_names();
  // About 30 px per value tick label up each trace, so that they never run into each other.
  constexpr int kTickHeightPx = 30;
  for (QCPAxisRect* rect : rects_) {
    rect->axis(QCPAxis::atLeft)
        ->ticker()
        ->setTickCount(std::clamp(rect->height() / kTickHeightPx, 3, 5));
  }
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

void LiveTraceView::set_window_s(double window_s) { window_box_->setValue(window_s); }

double LiveTraceView::window_s() const { return window_box_->value(); }

void LiveTraceView::set_paused(bool paused) {
  if (paused) {
    timeline_.pause();
  } else {
    timeline_.resume();
  }
  {
    const QSignalBlocker block(pause_button_);
    pause_button_->setChecked(paused);
  }
  sync_scroll_bar();
  refresh();
}

void LiveTraceView::scroll_to(double end_s) {
  timeline_.scroll_to(end_s);
  {
    const QSignalBlocker block(pause_button_);
    pause_button_->setChecked(true);
  }
  sync_scroll_bar();
  refresh();
}

void LiveTraceView::sync_scroll_bar() {
  const TimeWindow range = timeline_.scroll_range();
  const TimeWindow view = timeline_.view();
  const QSignalBlocker block(scroll_bar_);
  scroll_bar_->setRange(static_cast<int>(std::floor(10 * range.start_s)),
                        static_cast<int>(std::ceil(10 * range.end_s)));
  scroll_bar_->setPageStep(std::max(1, static_cast<int>(10 * timeline_.window_s())));
  scroll_bar_->setSingleStep(std::max(1, static_cast<int>(timeline_.window_s())));
  scroll_bar_->setValue(static_cast<int>(std::lround(10 * view.end_s)));
}

void LiveTraceView::refresh() {
  if (!acquisition_) return;
  const daq::AcquisitionStatus status = acquisition_->status();
  timeline_.advance(status.stream_time_s);
  const TimeWindow window = timeline_.view();
  const int buckets = std::max(200, plot_->width());  // a min–max pair per pixel column
  acquisition_->history(window.start_s, window.end_s, buckets, traces_);
  const std::vector<double>* series[kTraceCount] = {&traces_.base, &traces_.b_m, &traces_.mass,
                                                    &traces_.z_m, &traces_.force_n};
  QVector<QCPGraphData> data;
  for (int k = 0; k < kTraceCount; ++k) {
    const std::vector<double>& v = *series[k];
    double lo = 0.0, hi = 0.0;
    finite_range(v, lo, hi);
    const double max_abs = lo <= hi ? std::max(std::abs(lo), std::abs(hi)) : 0.0;
    const DisplayUnit unit =
        sticky_display_unit(units_[std::size_t(k)], trace_si_unit(k, layout_), max_abs);
    if (!units_[std::size_t(k)] || units_[std::size_t(k)]->symbol != unit.symbol) {
      units_[std::size_t(k)] = unit;
      ranges_[std::size_t(k)].reset();
      rects_[std::size_t(k)]
          ->axis(QCPAxis::atLeft)
          ->setLabel(trace_symbol(k) + " [" + qtext(unit.symbol) + "]");
    }
    data.resize(static_cast<qsizetype>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
      data[qsizetype(i)] = QCPGraphData(traces_.t_s[i], unit.to_display(v[i]));
    }
    graphs_[std::size_t(k)]->data()->set(data, true);
    if (lo <= hi) {
      const AxisRange range =
          follow_range(ranges_[std::size_t(k)], unit.to_display(lo), unit.to_display(hi));
      ranges_[std::size_t(k)] = range;
      rects_[std::size_t(k)]->axis(QCPAxis::atLeft)->setRange(range.lo, range.hi);
    }
    rects_[std::size_t(k)]->axis(QCPAxis::atBottom)->setRange(window.start_s, window.end_s);
  }
  if (!timeline_.following()) sync_scroll_bar();
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

}  // namespace oscilab::ui
