#pragma once

#include <string>

#include "ui/figure.h"

namespace oscilab::cli {

/// Writes `figure` as a PNG (ui::render_figure_png), creating the QApplication on first use with
/// the "offscreen" platform when no display is set. Throws InputError when the CLI was built
/// without the GUI (OSCILAB_BUILD_GUI=OFF) or the file cannot be written.
void write_figure_png(const ui::Figure& figure, const std::string& path);

/// Whether this build can write PNG figures.
bool png_output_available();

}  // namespace oscilab::cli
