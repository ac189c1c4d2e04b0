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

}  // namespace oscilab::ui
