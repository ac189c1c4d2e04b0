#pragma once

#include <initializer_list>
#include <vector>

#include <QString>

#include <qcustomplot.h>

namespace oscilab::ui {

/// The look the review's plots share: a plot with its axis labels, "gb" numbers and a frame
/// (frame_axes), listing its plottables in its legend, at least 260 × 200 pixels.
QCustomPlot* make_review_plot(const QString& x_label, const QString& y_label);

/// Largest finite |value| of a set of vectors, to choose a display unit.
double largest_abs(std::initializer_list<const std::vector<double>*> vectors);

/// An axis over [lo, hi] with 5 % of the span as margin on either side (10 % of |hi|, at least
/// 1, for a single value); [−1, 1] when there are no values (lo > hi).
void fit_axis_with_margin(QCPAxis* axis, double lo, double hi);

/// Space around fitted data ranges, as a fraction of their span.
constexpr double kRangeMargin = 0.05;

}  // namespace oscilab::ui
