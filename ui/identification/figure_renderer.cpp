#include "ui/identification/figure_renderer.h"

#include <algorithm>
#include <cmath>

#include <QColor>
#include <QFont>
#include <QPen>

#include <qcustomplot.h>

namespace oscilab::ui {
namespace {

QColor palette_qcolor(int index) {
  const figures::Rgb c = figures::palette_color(index);
  return {c.red, c.green, c.blue};
}

void add_series(QCPAxisRect* rect, QCPLegend* legend, const figures::FigureSeries& series) {
  const QColor color = palette_qcolor(series.color);
  // Split at NaN: each finite run becomes one curve; only the first goes in the legend.
  bool first_curve = true;
  std::size_t i = 0;
  const std::size_t n = std::min(series.x.size(), series.y.size());
  while (i < n) {
    while (i < n && !(std::isfinite(series.x[i]) && std::isfinite(series.y[i]))) ++i;
    QVector<double> keys, values;
    while (i < n && std::isfinite(series.x[i]) && std::isfinite(series.y[i])) {
      keys.push_back(series.x[i]);
      values.push_back(series.y[i]);
      ++i;
    }
    if (keys.isEmpty()) break;
    auto* curve = new QCPCurve(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    curve->setData(keys, values);
    QPen pen(color);
    pen.setWidthF(series.width_px);
    switch (series.style) {
      case figures::FigureSeries::Style::Line:
        curve->setPen(pen);
        break;
      case figures::FigureSeries::Style::DashedLine:
        pen.setStyle(Qt::DashLine);
        curve->setPen(pen);
        break;
      case figures::FigureSeries::Style::Dots:
        curve->setLineStyle(QCPCurve::lsNone);
        curve->setScatterStyle(
            QCPScatterStyle(QCPScatterStyle::ssDisc, color, color, series.width_px));
        break;
      case figures::FigureSeries::Style::Markers:
        curve->setLineStyle(QCPCurve::lsNone);
        pen.setWidthF(1.5);
        curve->setScatterStyle(
            QCPScatterStyle(QCPScatterStyle::ssCircle, pen, Qt::white, series.width_px));
        break;
    }
    if (!series.name.empty() && first_curve && legend != nullptr) {
      curve->setName(QString::fromStdString(series.name));
      curve->addToLegend(legend);
    }
    first_curve = false;
  }
}

}  // namespace

void render_figure(QCustomPlot& plot, const figures::Figure& figure) {
  plot.clearPlottables();
  plot.clearItems();
  plot.setAutoAddPlottableToLegend(false);
  plot.plotLayout()->clear();
  QFont font = plot.font();
  font.setPointSizeF(10.0);
  QFont title_font = font;
  title_font.setBold(true);
  title_font.setPointSizeF(11.0);

  int row = 0;
  if (!figure.title.empty()) {
    plot.plotLayout()->addElement(
        row++, 0, new QCPTextElement(&plot, QString::fromStdString(figure.title), title_font));
  }
  for (const figures::FigurePanel& panel : figure.panels) {
    if (!panel.title.empty()) {
      plot.plotLayout()->addElement(
          row++, 0, new QCPTextElement(&plot, QString::fromStdString(panel.title), font));
    }
    auto* rect = new QCPAxisRect(&plot);
    plot.plotLayout()->addElement(row++, 0, rect);
    QCPAxis* x = rect->axis(QCPAxis::atBottom);
    QCPAxis* y = rect->axis(QCPAxis::atLeft);
    x->setLabel(QString::fromStdString(panel.x_label));
    y->setLabel(QString::fromStdString(panel.y_label));
    x->setLabelFont(font);
    y->setLabelFont(font);
    x->setTickLabelFont(font);
    y->setTickLabelFont(font);
    x->grid()->setVisible(true);
    y->grid()->setVisible(true);
    QCPLegend* legend = nullptr;
    if (panel.legend) {
      legend = new QCPLegend;
      using Corner = figures::FigurePanel::Corner;
      const Corner c = panel.legend_corner;
      const Qt::Alignment vertical =
          c == Corner::TopLeft || c == Corner::TopRight ? Qt::AlignTop : Qt::AlignBottom;
      const Qt::Alignment horizontal =
          c == Corner::TopLeft || c == Corner::BottomLeft ? Qt::AlignLeft : Qt::AlignRight;
      rect->insetLayout()->addElement(legend, vertical | horizontal);
      legend->setLayer(QLatin1String("legend"));
      legend->setFont(font);
      legend->setBrush(QBrush(QColor(255, 255, 255, 220)));
    }
    for (const figures::FigureSeries& series : panel.series) add_series(rect, legend, series);
    if (legend != nullptr && legend->itemCount() == 0) legend->setVisible(false);
    // Autoscale with a margin of 4 % so that curves do not sit on the frame.
    bool found = false;
    QCPRange keys, values;
    for (QCPAbstractPlottable* p : rect->plottables()) {
      bool ok = false;
      const QCPRange k = p->getKeyRange(ok);
      if (!ok) continue;
      const QCPRange v = p->getValueRange(ok);
      if (!ok) continue;
      if (!found) {
        keys = k;
        values = v;
        found = true;
      } else {
        keys.expand(k);
        values.expand(v);
      }
    }
    if (found) {
      const double dk = std::max(keys.size(), 1e-12) * 0.04;
      const double dv = std::max(values.size(), 1e-12) * 0.06;
      x->setRange(keys.lower - dk, keys.upper + dk);
      y->setRange(values.lower - dv, values.upper + dv);
    }
  }
}

}  // namespace oscilab::ui
