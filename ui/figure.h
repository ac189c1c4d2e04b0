#pragma once

#include <string>
#include <vector>

namespace oscilab::ui {

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

struct Figure {
  std::string title;
  std::vector<FigurePanel> panels;
  int width_px = 1000;
  int panel_height_px = 380;
};

}  // namespace oscilab::ui
