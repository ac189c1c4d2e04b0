#pragma once

#include <string>

#include "analysis/figures/figure.h"

// The PNG figure writer's drawing with cairo (figure_cairo.cpp), compiled into oscilab_png_module
// only: the program reaches it through write_figure_png (figure_png.h), which checks the figure
// and loads the module.
namespace oscilab::figures {

/// Draws `figure` (at least one panel, a sane size: write_figure_png checks) at figure.width_px ×
/// `height_px` pixels into memory and writes it to `path` as a PNG. Returns "" when written, else
/// the problem, e.g. "cannot write PNG (error while writing to output stream)". Throws nothing but
/// std::bad_alloc.
std::string draw_figure_png(const Figure& figure, int height_px, const std::string& path);

}  // namespace oscilab::figures
