#pragma once

#include <string>

#include "analysis/figures/figure.h"

namespace oscilab::figures {

/// The height a figure is drawn at: panel_height_px per panel and 30 px for the title.
int figure_height_px(const Figure& figure);

/// Writes `figure` as a PNG image of figure.width_px × figure_height_px(figure) pixels, drawn
/// with cairo into memory: no display, no GUI library, safe on any thread (each call owns its
/// surface). The layout follows the app's interactive figures: the title, then per panel its
/// title, framed axes with "nice" ticks and a grid, the series autoscaled with a margin (4 % of
/// the x span, 6 % of the y span), and the legend in the panel's corner. Lines are drawn as
/// parametric curves in data order (a branch that turns back at a fold is drawn as followed) and
/// break at NaN.
///
/// Throws InputError naming `path` when the figure has no panels or the file cannot be written.
void write_figure_png(const Figure& figure, const std::string& path);

}  // namespace oscilab::figures
