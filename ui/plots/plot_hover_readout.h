#pragma once

#include <QObject>
#include <QPointF>
#include <QString>

class QCustomPlot;

namespace oscilab::ui {

/// The value under the mouse on every QCustomPlot of the application, in a tooltip: an event
/// filter on the application object reads the axis rect under the mouse and shows its bottom and
/// left axes' values with their units, taken from the axes' labels ("z [mm]": "z = 1.25 mm"). A
/// plot with a readout of its own (the record view's cursor line) sets the property
/// kOwnReadoutProperty and is left alone. One per application; the filter goes with the object.
/// UI thread only.
class PlotHoverReadouts : public QObject {
  Q_OBJECT

 public:
  static constexpr const char* kOwnReadoutProperty = "oscilab_own_readout";

  explicit PlotHoverReadouts(QObject* parent = nullptr);
  ~PlotHoverReadouts() override;

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
};

/// "x-name = value unit   y-name = value unit" at `position` (widget pixels) of `plot`, four
/// significant digits; empty outside every axis rect.
QString plot_hover_text(const QCustomPlot& plot, QPointF position);

}  // namespace oscilab::ui
