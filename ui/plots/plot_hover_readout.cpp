#include "ui/plots/plot_hover_readout.h"

#include <QCoreApplication>
#include <QMouseEvent>
#include <QRegularExpression>
#include <QToolTip>

#include <qcustomplot.h>

namespace oscilab::ui {
namespace {

// "z = 1.25 mm" from an axis labelled "z [mm]" ("f = −m d²b/dt² [N]": "f = …", no label: the
// value alone).
QString axis_value_text(const QCPAxis& axis, double value) {
  static const QRegularExpression kNameAndUnit(QStringLiteral("^(.*?)\\s*\\[([^\\]]*)\\]\\s*$"));
  QString name = axis.label();
  QString unit;
  if (const QRegularExpressionMatch match = kNameAndUnit.match(name); match.hasMatch()) {
    name = match.captured(1);
    unit = match.captured(2);
  }
  name = name.section(QStringLiteral(" = "), 0, 0).trimmed();
  QString text = QString::number(value, 'g', 4);
  if (!unit.isEmpty()) text += QLatin1Char(' ') + unit;
  return name.isEmpty() ? text : name + QStringLiteral(" = ") + text;
}

}  // namespace

QString plot_hover_text(const QCustomPlot& plot, QPointF position) {
  QCPAxisRect* rect = plot.axisRectAt(position);
  if (rect == nullptr || !rect->rect().contains(position.toPoint())) return {};
  const QCPAxis* x = rect->axis(QCPAxis::atBottom);
  const QCPAxis* y = rect->axis(QCPAxis::atLeft);
  if (x == nullptr || y == nullptr) return {};
  return axis_value_text(*x, x->pixelToCoord(position.x())) + QStringLiteral("   ") +
         axis_value_text(*y, y->pixelToCoord(position.y()));
}

PlotHoverReadouts::PlotHoverReadouts(QObject* parent) : QObject(parent) {
  if (QCoreApplication* app = QCoreApplication::instance()) app->installEventFilter(this);
}

PlotHoverReadouts::~PlotHoverReadouts() {
  if (QCoreApplication* app = QCoreApplication::instance()) app->removeEventFilter(this);
}

bool PlotHoverReadouts::eventFilter(QObject* watched, QEvent* event) {
  // Three event types matter; everything else passes untouched (this sees every event).
  const QEvent::Type type = event->type();
  if (type != QEvent::Enter && type != QEvent::MouseMove && type != QEvent::ToolTip) return false;
  auto* plot = qobject_cast<QCustomPlot*>(watched);
  if (plot == nullptr || plot->property(kOwnReadoutProperty).toBool()) return false;
  if (type == QEvent::Enter) {
    plot->setMouseTracking(true);  // moves without a button pressed reach the filter
    return false;
  }
  QPointF position;
  QPoint global;
  if (type == QEvent::ToolTip) {  // the mouse rests: the readout, then the plot's own tooltip
    position = static_cast<QHelpEvent*>(event)->pos();
    global = static_cast<QHelpEvent*>(event)->globalPos();
  } else {
    const auto* move = static_cast<QMouseEvent*>(event);
    if (move->buttons() != Qt::NoButton) return false;  // a drag pans: no readout meanwhile
    position = move->position();
    global = move->globalPosition().toPoint();
  }
  QString text = plot_hover_text(*plot, position);
  if (text.isEmpty()) {
    if (type == QEvent::MouseMove) QToolTip::hideText();
    return false;  // outside the axes: the plot's own tooltip, if any
  }
  if (!plot->toolTip().isEmpty()) text += QStringLiteral("\n") + plot->toolTip();
  QToolTip::showText(global, text, plot);
  return type == QEvent::ToolTip;
}

}  // namespace oscilab::ui
