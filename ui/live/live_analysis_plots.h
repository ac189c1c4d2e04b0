#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <QString>
#include <QWidget>

#include "analysis/edc/level_tracker.h"
#include "analysis/edc/well.h"
#include "analysis/hbm/level_response.h"
#include "analysis/rfs/streaming_slices.h"
#include "daq/live/acquisition.h"

class QCPErrorBars;
class QCPGraph;
class QCustomPlot;

namespace oscilab::ui {

/// The live analysis plots, stacked: the EDC against f₀ of both wells, level by level with ±3σ
/// bars (Fig. 10), under the model's prediction (Fig. 15); the force–displacement loop of the
/// current cycle (Fig. 9) beside the spectrum of z with the excitation's harmonics; and the
/// restoring-force surface growing live (stiffness and damping slices, §3.1–3.2, Fig. 7b, 7c),
/// coloured by well. The numbers come from the acquisition and analysis/; these plots only
/// draw them. Used from the UI thread only.
class LiveAnalysisPlots : public QWidget {
  Q_OBJECT

 public:
  explicit LiveAnalysisPlots(QWidget* parent = nullptr);

  /// A new stream at `frequency_hz` (ν; 0: not known yet): empty slices, loop and spectrum.
  void reset(double frequency_hz);
  /// Takes the acquisition's samples the slices have not taken yet and redraws the slices.
  void refresh_slices(const daq::Acquisition& acquisition, double frequency_hz);
  /// Redraws the loop of the newest whole cycle and the spectrum of the last seconds of z.
  void refresh_cycle(const daq::Acquisition& acquisition, double frequency_hz);
  /// Redraws the measured EDC when the levels or the level being filled changed.
  void show_edc(const std::vector<analysis::LevelResult>& levels,
                const std::optional<analysis::LevelResult>& current);

  /// Names the model's curves after `label` and empties them until show_model_edc().
  void set_model_label(const QString& label);
  /// Draws the model's EDC of the positive (0) and negative (1) well; the next show_edc redraws.
  void show_model_edc(const analysis::LevelResponse& positive,
                      const analysis::LevelResponse& negative);

  QCustomPlot* edc_plot() const { return edc_plot_; }
  /// EDC graphs: measured positive / negative / other wells, the level being filled, and the
  /// model's prediction per well (empty until computed).
  QCPGraph* edc_graph(analysis::Well well) const;
  QCPGraph* current_level_graph() const { return current_graph_; }
  QCPGraph* model_graph(bool positive_well) const { return model_graphs_[positive_well ? 0 : 1]; }

 private:
  analysis::StreamingSlices slices_;
  daq::TraceHistory raw_;  // reused buffer
  std::size_t levels_shown_ = static_cast<std::size_t>(-1);
  std::optional<analysis::LevelResult> current_shown_;

  QCustomPlot* edc_plot_ = nullptr;
  QCPGraph* edc_graphs_[3] = {nullptr, nullptr, nullptr};  // positive, negative, other
  QCPGraph* current_graph_ = nullptr;
  QCPErrorBars* edc_bars_[4] = {nullptr, nullptr, nullptr, nullptr};  // wells, then current
  QCPGraph* model_graphs_[2] = {nullptr, nullptr};
  QCustomPlot* stiffness_plot_ = nullptr;
  QCustomPlot* damping_plot_ = nullptr;
  QCustomPlot* loop_plot_ = nullptr;
  QCustomPlot* spectrum_plot_ = nullptr;
};

}  // namespace oscilab::ui
