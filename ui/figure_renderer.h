#pragma once

#include <string>

#include "ui/figure.h"

namespace oscilab::ui {

/// Renders a Figure offscreen with QCustomPlot and saves it as PNG. Needs a QApplication (the
/// plot is a QWidget; the "offscreen" platform is enough, no display). Branch curves are drawn
/// as parametric curves in data order, so a branch that turns back at a fold is drawn as it is
/// followed, not re-sorted by x.
///
/// Returns an empty string on success, otherwise why it failed (naming the file).
std::string render_figure_png(const Figure& figure, const std::string& path);

}  // namespace oscilab::ui
