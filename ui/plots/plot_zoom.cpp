#include "ui/plots/plot_zoom.h"

#include <utility>
#include <vector>

#include <QObject>
#include <QPointer>

#include <qcustomplot.h>

namespace oscilab::ui {
namespace {

// The ranges of every axis of a plot at one moment.
using AxisRanges = std::vector<std::pair<QPointer<QCPAxis>, QCPRange>>;

// The ranges before each keyboard zoom of one plot, newest last: a child of the plot, found by
// its name, so that it goes with the plot.
class ZoomHistory : public QObject {
 public:
  static constexpr int kDepth = 50;  // zooms remembered; older ones are forgotten

  static ZoomHistory* of(QCustomPlot& plot) {
    auto* history = plot.findChild<ZoomHistory*>("zoom_history", Qt::FindDirectChildrenOnly);
    if (!history) {
      history = new ZoomHistory(&plot);
      history->setObjectName("zoom_history");
    }
    return history;
  }

  void remember(QCustomPlot& plot) {
    AxisRanges ranges;
    for (QCPAxisRect* rect : plot.axisRects()) {
      for (QCPAxis* axis : rect->axes()) ranges.emplace_back(axis, axis->range());
    }
    states_.push_back(std::move(ranges));
    if (states_.size() > kDepth) states_.erase(states_.begin());
  }

  bool restore() {
    if (states_.empty()) return false;
    for (const auto& [axis, range] : states_.back()) {
      if (axis) axis->setRange(range);
    }
    states_.pop_back();
    return true;
  }

 private:
  using QObject::QObject;
  std::vector<AxisRanges> states_;
};

}  // namespace

void zoom_plot(QCustomPlot& plot, double factor) {
  ZoomHistory::of(plot)->remember(plot);
  // Each axis from its range before the zoom: axes kept in step with each other (the record
  // view's time axes) change together and must not be scaled twice.
  AxisRanges before;
  for (QCPAxisRect* rect : plot.axisRects()) {
    for (const Qt::Orientation orientation : {Qt::Horizontal, Qt::Vertical}) {
      if (!rect->rangeZoom().testFlag(orientation)) continue;
      for (QCPAxis* axis : rect->rangeZoomAxes(orientation))
        before.emplace_back(axis, axis->range());
    }
  }
  for (const auto& [axis, range] : before) {
    axis->setRange(range);  // back to where it was, then scaled (a log axis about its centre's log)
    axis->scaleRange(factor);
  }
  plot.replot();
}

void reset_plot_zoom(QCustomPlot& plot) {
  ZoomHistory::of(plot)->remember(plot);
  plot.rescaleAxes();
  plot.replot();
}

bool undo_plot_zoom(QCustomPlot& plot) {
  if (!ZoomHistory::of(plot)->restore()) return false;
  plot.replot();
  return true;
}

}  // namespace oscilab::ui
