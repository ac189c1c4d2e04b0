#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/edc/level_tracker.h"
#include "analysis/edc/well.h"

// The measured EDC points of the live monitor, level by level, and where the model is drawn.

namespace oscilab::ui {

/// A measured EDC point (Fig. 10): the level's mean over its steady cycles with ±3σ bars.
struct EdcPoint {
  double f0_n = 0.0;
  double edc_j = 0.0;
  double error_j = 0.0;  // 3 edc_std_j: the bars of Fig. 10
  int cycles = 0;
  std::string flags;  // LevelResult::flags()
};

/// The EDC against f₀ of each well, level by level: finished levels in their well's series
/// (positive, negative, or other: cross-well or unknown), the level being filled apart.
struct EdcPlotData {
  std::vector<EdcPoint> positive, negative, other;
  std::optional<EdcPoint> current;
  analysis::Well current_well = analysis::Well::Unclassified;
  double max_f0_n = 0.0;  // over all points
};
EdcPlotData edc_plot_data(const std::vector<analysis::LevelResult>& levels,
                          const std::optional<analysis::LevelResult>& current);

/// Levels at which the model's EDC is drawn: 0.1 N to at least 2.7 N (the paper's range, §3.2)
/// or just past the largest level measured, in steps of 0.05 N.
std::vector<double> prediction_levels(double max_measured_f0_n);

/// The warning shown for the level being filled: "" when it is period-1 in one well, else its
/// flags in words ("not period-1 (sub-harmonic or non-periodic, Fig. 17)", "crosses wells").
std::string level_warning(const std::optional<analysis::LevelResult>& current);

}  // namespace oscilab::ui
