#pragma once

class QCustomPlot;

namespace oscilab::ui {

/// Keyboard zoom of any QCustomPlot (View ▸ Zoom in, Zoom out, Undo zoom, Reset zoom). A zoom
/// scales the axes a mouse-wheel zoom would scale (each axis rect's range-zoom axes, in its
/// range-zoom orientations) about their centres, so a plot whose wheel zooms time only (the
/// record view) zooms time only here too. Each zoom and reset remembers the ranges before it, per
/// plot, for undo_plot_zoom. UI thread only.

/// Scales the zoom axes of `plot` by `factor` about their centres (< 1 zooms in) and replots.
void zoom_plot(QCustomPlot& plot, double factor);
/// Every axis of `plot` over its data (QCustomPlot::rescaleAxes), remembered for undo.
void reset_plot_zoom(QCustomPlot& plot);
/// Back to the ranges before the last zoom_plot or reset_plot_zoom of `plot`; false when there
/// is nothing to undo.
bool undo_plot_zoom(QCustomPlot& plot);

}  // namespace oscilab::ui
