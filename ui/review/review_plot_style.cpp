#include "ui/review/review_plot_style.h"

#include <algorithm>
#include <cmath>

#include "ui/plots/plot_helpers.h"

namespace oscilab::ui {

QCustomPlot* make_review_plot(const QString& x_label, const QString& y_label) {
  auto* plot = new QCustomPlot;
  plot->setAutoAddPlottableToLegend(true);
  frame_axes(plot, x_label, y_label);
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

}  // namespace oscilab::ui
