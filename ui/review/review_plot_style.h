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

}  // namespace oscilab::ui
