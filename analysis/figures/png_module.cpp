// oscilab_png_module's entry point (png_module_api.h): the figure rebuilt from its C form, drawn
// by figure_cairo.cpp; whatever that throws (std::bad_alloc) is caught, so that no exception
// leaves the module.
#include <algorithm>
#include <cstring>
#include <string>

#include "analysis/figures/figure_cairo.h"
#include "analysis/figures/png_module_api.h"

namespace oscilab::figures {
namespace {

Figure figure_of(const OscilabFigureV1& c_figure) {
  Figure figure;
  figure.title = c_figure.title;
  figure.width_px = c_figure.width_px;
  figure.panel_height_px = c_figure.panel_height_px;
  for (std::size_t p = 0; p < c_figure.panel_count; ++p) {
    const OscilabFigurePanelV1& c_panel = c_figure.panels[p];
    FigurePanel& panel = figure.panels.emplace_back();
    panel.title = c_panel.title;
    panel.x_label = c_panel.x_label;
    panel.y_label = c_panel.y_label;
    panel.legend = c_panel.legend != 0;
    panel.legend_corner = static_cast<FigurePanel::Corner>(c_panel.legend_corner);
    for (std::size_t s = 0; s < c_panel.series_count; ++s) {
      const OscilabFigureSeriesV1& c_series = c_panel.series[s];
      FigureSeries& series = panel.series.emplace_back();
      series.name = c_series.name;
      series.style = static_cast<FigureSeries::Style>(c_series.style);
      series.color = c_series.color;
      series.x.assign(c_series.x, c_series.x + c_series.point_count);
      series.y.assign(c_series.y, c_series.y + c_series.point_count);
      series.width_px = c_series.width_px;
    }
  }
  return figure;
}

void copy_problem(const std::string& text, char* problem, std::size_t problem_size) {
  if (problem == nullptr || problem_size == 0) return;
  const std::size_t size = std::min(text.size(), problem_size - 1);
  std::memcpy(problem, text.data(), size);
  problem[size] = '\0';
}

}  // namespace
}  // namespace oscilab::figures

extern "C" __attribute__((visibility("default"))) int oscilab_write_figure_png_v1(
    const OscilabFigureV1* figure, const char* path, char* problem, size_t problem_size) {
  using namespace oscilab::figures;
  try {
    const std::string failure = draw_figure_png(figure_of(*figure), figure->height_px, path);
    copy_problem(failure, problem, problem_size);
    return failure.empty() ? 1 : 0;
  } catch (...) {
    copy_problem("cannot draw the figure (out of memory)", problem, problem_size);
    return 0;
  }
}
