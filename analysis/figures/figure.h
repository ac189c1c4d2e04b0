#pragma once

#include <array>
#include <cstdlib>
#include <string>
#include <vector>

namespace oscilab::figures {

/// A colour of the figures' palette, 8 bits per channel.
struct Rgb {
  int red, green, blue;
};

/// Okabe & Ito (2008), the colour-blind-safe palette, black first; `index` wraps around. Both
/// renderers (the PNG writer and the app's interactive plots) draw with it.
inline Rgb palette_color(int index) {
  static constexpr std::array<Rgb, 8> colors = {{{0, 0, 0},
                                                 {0, 114, 178},
                                                 {213, 94, 0},
                                                 {0, 158, 115},
                                                 {204, 121, 167},
                                                 {230, 159, 0},
                                                 {86, 180, 233},
                                                 {240, 228, 66}}};
  return colors[static_cast<std::size_t>(std::abs(index)) % colors.size()];
}

/// A static figure as data (Qt-free, so the CLI and tests build it without widgets): panels
/// stacked vertically, each with labelled axes and series. Values are in the units the axis
/// labels name; NaN in x or y breaks a line (a gap), so one series can hold several segments.
struct FigureSeries {
  enum class Style { Line, DashedLine, Dots, Markers };
  std::string name;  // legend entry; empty: not in the legend
  Style style = Style::Line;
  int color = 0;  // index into a fixed colour-blind-safe palette
  std::vector<double> x, y;
  double width_px = 1.8;  // line width, or dot/marker size
};

struct FigurePanel {
  std::string title;    // drawn above the panel
  std::string x_label;  // with unit, e.g. "forcing amplitude f0 [N]"
  std::string y_label;
  std::vector<FigureSeries> series;
  bool legend = true;
  enum class Corner { TopLeft, TopRight, BottomLeft, BottomRight };
  Corner legend_corner = Corner::TopLeft;  // where the legend sits inside the axes
};

/// The height of a figure's title row (figure_height_px).
inline constexpr int kFigureTitleRowPx = 30;

struct Figure {
  std::string title;
  std::vector<FigurePanel> panels;
  int width_px = 1000;
  int panel_height_px = 380;
};

}  // namespace oscilab::figures
