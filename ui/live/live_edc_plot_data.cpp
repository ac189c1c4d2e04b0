#include "ui/live/live_edc_plot_data.h"

#include <algorithm>
#include <cmath>

namespace oscilab::ui {

EdcPlotData edc_plot_data(const std::vector<analysis::LevelResult>& levels,
                          const std::optional<analysis::LevelResult>& current) {
  EdcPlotData data;
  const auto point = [&](const analysis::LevelResult& level) {
    data.max_f0_n = std::max(data.max_f0_n, level.f0_n);
    return EdcPoint{level.f0_n, level.edc_mean_j, 3.0 * level.edc_std_j, level.cycles,
                    level.flags()};
  };
  for (const analysis::LevelResult& level : levels) {
    auto& series = level.well == analysis::Well::Positive   ? data.positive
                   : level.well == analysis::Well::Negative ? data.negative
                                                            : data.other;
    series.push_back(point(level));
  }
  if (current && current->cycles > 0) {
    data.current = point(*current);
    data.current_well = current->well;
  }
  return data;
}

std::vector<double> prediction_levels(double max_measured_f0_n) {
  constexpr double kFirst = 0.1, kStep = 0.05, kPaperTop = 2.7;  // §3.2: 0.2 → 2.7 N
  const double top =
      std::max(kPaperTop, std::isfinite(max_measured_f0_n) ? max_measured_f0_n + 0.1 : kPaperTop);
  const auto n = static_cast<int>(std::ceil((top - kFirst) / kStep - 1e-9)) + 1;
  std::vector<double> levels;
  for (int i = 0; i < n; ++i) levels.push_back(kFirst + kStep * i);
  return levels;
}

std::string level_warning(const std::optional<analysis::LevelResult>& current) {
  if (!current || current->cycles == 0) return {};
  std::string text;
  if (!current->period1) text = "not period-1 (sub-harmonic or non-periodic motion, Fig. 17)";
  if (current->cross_well) text += std::string(text.empty() ? "" : "; ") + "crosses wells";
  return text;
}

}  // namespace oscilab::ui
