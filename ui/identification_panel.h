#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QWidget>

#include "analysis/diagnosis/diagnosis.h"
#include "analysis/identification/edc_fit.h"

class QComboBox;
class QCustomPlot;
class QLabel;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTableWidget;
class QTabWidget;

namespace oscilab::ui {

class BackgroundJob;

/// The fit and model-gap panel (issues 6 and 9): recordings of a stepped-sine campaign, a fit of
/// the paper's θ (eq. (9)) by CMA-ES or the paper's GA, and a diagnosis that names the missing
/// effect; both run on a worker thread with progress and cancel. Results: the identified
/// parameters with standard errors and 95 % intervals (Table 3 style), the EDC per well measured
/// against the model (Fig. 15), the diagnosis's verdict and steps with the EDC residuals in σ
/// before and after. The computing is the analysis core's (fit_edc, diagnose); the panel shows.
class IdentificationPanel : public QWidget {
  Q_OBJECT

 public:
  explicit IdentificationPanel(QWidget* parent = nullptr);
  ~IdentificationPanel() override;

  void set_recordings(const std::vector<std::string>& paths);
  void add_recording(const std::string& path);
  std::vector<std::string> recordings() const;
  /// Method "cmaes" or "ga"; evaluations of CMA-ES (GA: population × generations, 5 % elite).
  void set_fit_settings(const std::string& method, int evaluations, int population,
                        int generations);
  /// Budgets of a diagnosis (baseline fit, each candidate's refit).
  void set_diagnosis_budget(long baseline_evaluations, long candidate_evaluations);

  void start_fit();
  void start_diagnosis();
  void cancel();
  bool busy() const;

  QPushButton* fit_button() const { return fit_button_; }
  QPushButton* diagnose_button() const { return diagnose_button_; }
  QPushButton* cancel_button() const { return cancel_button_; }
  QTableWidget* parameter_table() const { return parameter_table_; }
  QTableWidget* step_table() const { return step_table_; }
  QLabel* status_label() const { return status_label_; }
  QLabel* verdict_label() const { return verdict_label_; }
  QCustomPlot* edc_plot() const { return edc_plot_; }
  QCustomPlot* residual_plot() const { return residual_plot_; }
  /// Best χ² against model evaluations, growing while a fit runs (Fig. 14).
  QCustomPlot* convergence_plot() const { return convergence_plot_; }
  QTabWidget* tabs() const { return tabs_; }

 Q_SIGNALS:
  /// A fit or a diagnosis ended (finished, cancelled or failed); `message` says which.
  void job_finished(const QString& message);

 private:
  struct Outcome;
  void start(bool diagnosis);
  void on_finished(bool cancelled);
  void set_busy(bool busy);
  /// A fit's best χ² so far (called on the UI thread, from the worker's queued reports).
  void add_convergence_point(long evaluations, double best_weighted_cost);
  void show_fit(const Outcome& outcome);
  void show_diagnosis(const Outcome& outcome);
  void plot_edc(const analysis::EdcObjective& objective, const analysis::EdcEvaluation& model,
                const QString& model_name);

  BackgroundJob* job_ = nullptr;
  std::shared_ptr<Outcome> outcome_;
  long baseline_evaluations_ = 2000;
  long candidate_evaluations_ = 800;

  QListWidget* record_list_ = nullptr;
  QComboBox* method_box_ = nullptr;
  QSpinBox* evaluations_box_ = nullptr;
  QSpinBox* population_box_ = nullptr;
  QSpinBox* generations_box_ = nullptr;
  QPushButton* add_button_ = nullptr;
  QPushButton* fit_button_ = nullptr;
  QPushButton* diagnose_button_ = nullptr;
  QPushButton* cancel_button_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel* status_label_ = nullptr;
  QLabel* verdict_label_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  QTableWidget* parameter_table_ = nullptr;
  QTableWidget* step_table_ = nullptr;
  QCustomPlot* edc_plot_ = nullptr;
  QCustomPlot* residual_plot_ = nullptr;
  QCustomPlot* convergence_plot_ = nullptr;
};

}  // namespace oscilab::ui
