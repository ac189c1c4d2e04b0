#pragma once

#include <string>

#include "ui/figure.h"

class QCustomPlot;

namespace oscilab::ui {

/// Lays `figure` out in `plot` (replacing what it showed): the title, then each panel's title and
/// axes with their labels, grid, legend and series, autoscaled with a margin. For a widget in a
/// window as for the offscreen PNG below.
void render_figure(QCustomPlot& plot, const Figure& figure);
/// The height the figure is drawn at: panel_height_px per panel and 30 px for the title.
int figure_height_px(const Figure& figure);

/// Renders a Figure offscreen with QCustomPlot and saves it as PNG. Needs a QApplication (the
/// plot is a QWidget; the "offscreen" platform is enough, no display). Branch curves are drawn
/// as parametric curves in data order, so a branch that turns back at a fold is drawn as it is
/// followed, not re-sorted by x.
///
/// Returns an empty string on success, otherwise why it failed (naming the file).
std::string render_figure_png(const Figure& figure, const std::string& path);

}  // namespace oscilab::ui
