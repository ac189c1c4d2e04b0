#pragma once

// The C interface of oscilab_png_module.so, the module that draws figures with cairo
// (figure_cairo.h). write_figure_png (figure_png.h) loads it on first use, so that a process that
// writes no PNG figure does not map cairo and the X11, fontconfig, freetype, pixman and libpng
// libraries it pulls in.
//
// Only plain data crosses: C strings, numbers and arrays the caller owns, and the problem as text
// in the caller's buffer. No C++ exception leaves the module and no C++ object crosses. Changing a
// type or a function here means a new version of the entry point.
#include <stddef.h>

extern "C" {

/// A figures::FigureSeries: `x` and `y` hold `point_count` values each.
struct OscilabFigureSeriesV1 {
  const char* name;
  int style;  // FigureSeries::Style as an int: Line, DashedLine, Dots, Markers
  int color;
  const double* x;
  const double* y;
  size_t point_count;
  double width_px;
};

/// A figures::FigurePanel.
struct OscilabFigurePanelV1 {
  const char* title;
  const char* x_label;
  const char* y_label;
  const OscilabFigureSeriesV1* series;
  size_t series_count;
  int legend;         // 0 or 1
  int legend_corner;  // FigurePanel::Corner as an int: TopLeft, TopRight, BottomLeft, BottomRight
};

/// A figures::Figure, drawn at width_px × height_px (figure_height_px).
struct OscilabFigureV1 {
  const char* title;
  const OscilabFigurePanelV1* panels;
  size_t panel_count;
  int width_px;
  int panel_height_px;
  int height_px;
};

/// Draws `figure` and writes it to `path` as a PNG. Returns 1 when written; else 0 with the
/// problem ("cannot write PNG (...)") in `problem`, null-terminated and cut to `problem_size`.
typedef int (*OscilabWriteFigurePngV1)(const OscilabFigureV1* figure, const char* path,
                                       char* problem, size_t problem_size);
}

namespace oscilab::figures {
inline constexpr const char* kPngModuleFile = "oscilab_png_module.so";
/// The entry point, an OscilabWriteFigurePngV1.
inline constexpr const char* kPngModuleEntry = "oscilab_write_figure_png_v1";
}  // namespace oscilab::figures
