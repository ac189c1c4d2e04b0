#include "ui/review_plot_style.h"

#include <algorithm>
#include <cmath>

namespace oscilab::ui {

QCPTextElement* add_plot_title(QCustomPlot* plot, const QString& title) {
  plot->plotLayout()->insertRow(0);
  QFont font = plot->font();
  font.setBold(true);
  auto* element = new QCPTextElement(plot, title, font);
  plot->plotLayout()->addElement(0, 0, element);
  return element;
}

QCustomPlot* make_review_plot(const QString& x_label, const QString& y_label) {
  auto* plot = new QCustomPlot;
  plot->setAutoAddPlottableToLegend(true);
  plot->xAxis->setLabel(x_label);
  plot->yAxis->setLabel(y_label);
  plot->xAxis->setNumberFormat("gb");
  plot->yAxis->setNumberFormat("gb");
  for (QCPAxis* axis : {plot->xAxis2, plot->yAxis2}) {  // a frame: top and right as lines
    axis->setVisible(true);
    axis->setTicks(false);
    axis->setTickLabels(false);
  }
  plot->setMinimumSize(260, 200);
  return plot;
}

double largest_abs(std::initializer_list<const std::vector<double>*> vectors) {
  double m = 0.0;
  for (const auto* v : vectors) {
    for (double x : *v) {
      if (std::isfinite(x)) m = std::max(m, std::abs(x));
    }
  }
  return m;
}

void fit_axis_with_margin(QCPAxis* axis, double lo, double hi) {
  if (!(lo <= hi)) {
    axis->setRange(-1.0, 1.0);
    return;
  }
  const double pad = hi > lo ? kRangeMargin * (hi - lo) : std::max(1.0, std::abs(hi)) * 0.1;
  axis->setRange(lo - pad, hi + pad);
}

}  // namespace oscilab::ui
