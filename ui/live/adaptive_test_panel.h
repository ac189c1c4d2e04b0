#pragma once

#include <memory>
#include <vector>

#include <QWidget>

#include "ui/live/adaptive_test_job.h"

class QCheckBox;
class QComboBox;
class QCustomPlot;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QTableWidget;

namespace oscilab::ui {

/// The adaptive test in the Live tab: a stepped-sine test on the virtual rig that chooses its own
/// levels (analysis::run_adaptive_test through AdaptiveTestJob, the same loop as `oscilab-cli
/// adaptive-test --source rig`). Its settings (the rig's truth, wells, f₀ range, frequency, shaker
/// time budget, effects weighed, the output folder); a strip chart of every hypothesis's weight
/// against the shaker time spent and a table of the weights and misfits now; the leader and the
/// stop rule's state; the proposed next level with its reason, and Run / Skip / Stop for it unless
/// Auto runs every proposal; at the end the final diagnosis's verdict and the folder written.
/// UI thread only; the test runs on a worker thread and never blocks the UI.
class AdaptiveTestPanel : public QWidget {
  Q_OBJECT

 public:
  explicit AdaptiveTestPanel(QWidget* parent = nullptr);
  ~AdaptiveTestPanel() override;

  /// The test the settings describe, or InputError naming the setting.
  AdaptiveTestJob::Request request() const;
  /// Starts the test the settings describe; false (with the reason in the verdict line) when a
  /// setting is refused or a test runs.
  bool start();
  /// Starts `request` (a script's or a test's, past the settings' fields).
  bool start(AdaptiveTestJob::Request request);
  void cancel();
  bool running() const;
  AdaptiveTestJob* job() const { return job_; }

  // The settings, for tests and sessions.
  QLineEdit* rig_truth_edit() const { return rig_truth_; }
  QLineEdit* folder_edit() const { return folder_; }
  QLineEdit* effects_edit() const { return effects_; }
  QComboBox* wells_box() const { return wells_; }
  QDoubleSpinBox* budget_box() const { return budget_; }
  QCheckBox* auto_box() const { return auto_; }
  QPushButton* run_button() const { return run_; }
  QPushButton* skip_button() const { return skip_; }
  QPushButton* stop_button() const { return stop_; }
  QCustomPlot* weights_plot() const { return plot_; }
  QTableWidget* weights_table() const { return table_; }
  QLabel* leader_label() const { return leader_; }
  QLabel* proposal_label() const { return proposal_; }
  QLabel* verdict_label() const { return verdict_; }
  /// The steps shown so far (one per decision).
  const std::vector<AdaptiveTestStep>& steps() const { return steps_; }

 Q_SIGNALS:
  void test_finished();

 private:
  QWidget* make_settings();
  QWidget* make_state();
  void show_step(const AdaptiveTestStep& step);
  void redraw_weights();
  void show_outcome(const AdaptiveTestOutcome& outcome);
  void set_awaiting(bool awaiting);
  void update_buttons();

  AdaptiveTestJob* job_ = nullptr;
  std::vector<AdaptiveTestStep> steps_;
  bool awaiting_ = false;
  double budget_s_ = 0.0;  // of the test running
  QLineEdit* rig_truth_ = nullptr;
  QComboBox* wells_ = nullptr;
  QDoubleSpinBox* f0_min_ = nullptr;
  QDoubleSpinBox* f0_max_ = nullptr;
  QDoubleSpinBox* freq_ = nullptr;
  QDoubleSpinBox* budget_ = nullptr;
  QLineEdit* effects_ = nullptr;
  QLineEdit* folder_ = nullptr;
  QCheckBox* auto_ = nullptr;
  QPushButton* start_ = nullptr;
  QPushButton* cancel_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QCustomPlot* plot_ = nullptr;
  QTableWidget* table_ = nullptr;
  QLabel* leader_ = nullptr;
  QLabel* stop_rule_ = nullptr;
  QLabel* proposal_ = nullptr;
  QLabel* verdict_ = nullptr;
  QPushButton* run_ = nullptr;
  QPushButton* skip_ = nullptr;
  QPushButton* stop_ = nullptr;
};

}  // namespace oscilab::ui
