// The PNG figure writer the program sees: it checks the figure, lays it out as the module's C
// interface takes it (png_module_api.h) and has oscilab_png_module draw it with cairo
// (figure_cairo.cpp). The module is loaded on the first figure.
#include "analysis/figures/figure_png.h"

#include <algorithm>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/common/module_loader.h"
#include "analysis/figures/png_module_api.h"

namespace oscilab::figures {
namespace {

constexpr int kMaxSidePx = 20000;  // a figure larger than this is a mistake, not a figure
constexpr std::size_t kProblemBytes = 512;

}  // namespace

int figure_height_px(const Figure& figure) {
  return figure.panel_height_px * static_cast<int>(figure.panels.size()) +
         (figure.title.empty() ? 0 : kFigureTitleRowPx);
}

void write_figure_png(const Figure& figure, const std::string& path) {
  if (figure.panels.empty()) throw InputError(path + ": the figure has no panels");
  const int width = figure.width_px;
  const int height = figure_height_px(figure);
  if (width < 100 || width > kMaxSidePx || figure.panel_height_px < 100 || height > kMaxSidePx) {
    throw InputError(path + ": figure size " + std::to_string(width) + " x " +
                     std::to_string(height) + " px is outside 100.." + std::to_string(kMaxSidePx) +
                     " px");
  }
  const auto write = reinterpret_cast<OscilabWriteFigurePngV1>(
      module_entry(kPngModuleFile, kPngModuleEntry, "writing " + path));
  // The figure's C form points into `figure`, which outlives the call.
  std::vector<std::vector<OscilabFigureSeriesV1>> series(figure.panels.size());
  std::vector<OscilabFigurePanelV1> panels;
  for (std::size_t p = 0; p < figure.panels.size(); ++p) {
    const FigurePanel& panel = figure.panels[p];
    for (const FigureSeries& s : panel.series) {
      series[p].push_back({s.name.c_str(), static_cast<int>(s.style), s.color, s.x.data(),
                           s.y.data(), std::min(s.x.size(), s.y.size()), s.width_px});
    }
    panels.push_back({panel.title.c_str(), panel.x_label.c_str(), panel.y_label.c_str(),
                      series[p].data(), series[p].size(), panel.legend ? 1 : 0,
                      static_cast<int>(panel.legend_corner)});
  }
  const OscilabFigureV1 c_figure{figure.title.c_str(),   panels.data(), panels.size(), width,
                                 figure.panel_height_px, height};
  char problem[kProblemBytes] = {};
  if (write(&c_figure, path.c_str(), problem, sizeof problem) == 0) {
    throw InputError(path + ": " + problem);
  }
}

}  // namespace oscilab::figures
