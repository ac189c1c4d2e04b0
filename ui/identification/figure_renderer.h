#pragma once

#include "analysis/figures/figure.h"

class QCustomPlot;

namespace oscilab::ui {

/// Lays `figure` out in `plot` (replacing what it showed): the title, then each panel's title and
/// axes with their labels, grid, legend and series, autoscaled with a margin. For a widget in a
/// window. PNG files are drawn by figures::write_figure_png, the same layout without Qt.
void render_figure(QCustomPlot& plot, const figures::Figure& figure);

}  // namespace oscilab::ui
