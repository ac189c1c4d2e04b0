#pragma once

#include <QColor>
#include <QString>

#include <qcustomplot.h>

namespace oscilab::ui {

/// A grey message in the middle of a plot's axes (why there is nothing to show yet); an empty
/// message hides it. The text item is created on first use and found again by its name.
void set_plot_hint(QCustomPlot* plot, const QString& message);

/// Filled round markers of `colour` and `size` pixels, for scatter graphs.
QCPScatterStyle disc_markers(const QColor& colour, double size);

/// A bold title row above the axes of `plot`, elided to the plot's width (the full title on
/// hover).
QCPTextElement* add_plot_title(QCustomPlot* plot, const QString& title);

/// The bottom and left axes labelled, with "gb" numbers, and the axes framed: the top and right
/// axes drawn as plain lines. Their tick count follows the plot's size, so that tick labels never
/// run into each other on a small plot.
void frame_axes(QCustomPlot* plot, const QString& x_label, const QString& y_label);

/// Space around fitted data ranges, as a fraction of their span.
constexpr double kRangeMargin = 0.05;

/// What an axis shows when there are no values to fit it to (lo > hi).
enum class WhenEmpty { Keep, Unit };  // its range unchanged, or [−1, 1]

/// An axis over [lo, hi] with `margin` × the span on either side; a single value gets ±10 % of
/// itself (±1 at 0).
void fit_axis(QCPAxis* axis, double lo, double hi, WhenEmpty when_empty = WhenEmpty::Unit,
              double margin = kRangeMargin);

}  // namespace oscilab::ui
