#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <QWidget>

#include "analysis/diagnosis/diagnosis.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/identification/fit_setup.h"
#include "ui/identification/diagnosis_view.h"
#include "ui/identification/fit_job.h"

class QComboBox;
class QCustomPlot;
class QGroupBox;
class QLabel;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QSplitter;

class QTableWidget;
class QTabWidget;

namespace oscilab::figures {
struct FitFigureData;
}  // namespace oscilab::figures

namespace oscilab::ui {

struct DiagnosisOutcome;
struct FigureDataOutcome;
class DiagnosisJob;
class FigureDataJob;
class FigureDialog;
class FitSettingsForm;
class FlowLayout;
class ResponseDialog;

/// The fit and model-gap panel: recordings of a stepped-sine campaign, a fit of
/// the paper's θ (eq. (9)) by CMA-ES or the paper's GA, and a diagnosis that names the missing
/// effect; each runs on a worker thread with progress and cancel (ui/identification/fit_job,
/// ui/identification/diagnosis_job). Results: the identified parameters with standard errors and 95
/// % intervals (Table 3 style), the EDC per well measured against the model (Fig. 15), the
/// diagnosis's verdict and steps with the EDC residuals in σ before and after. The computing is the
/// analysis core's (fit_edc, diagnose); the panel shows.
///
/// While a fit runs, the EDC tab draws the model EDC of the best θ so far over the measured
/// points, at most 5 times a second (the worker computes it and sends a FitPreview). After a
/// fit: "Figures…" shows Figs. 13–16 (ui/fit_figures), "Export results…" writes the
/// FIT JSON of `oscilab-cli fit` and the figures as PNG + CSV into a folder, "HBM branch…" and
/// "Bifurcation map…" open the fitted model's branches and map (ResponseDialog). The data the
/// figures need beyond the fit (cost slices, sensitivity curves) is computed once, on demand, on
/// the worker with progress and cancel (ui/identification/figure_data_job).
///
/// Thread-safety: UI thread only; fit_preview is emitted from the worker thread (queued).
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

  /// The measured EDC of the opened recordings as a fit would use it (analysis::edc_dataset of
  /// their analysis), drawn in the EDC tab before any fit, with a hint that says what can be done
  /// with it. `error`: why there is nothing to fit (no usable stepped-sine level). Nothing changes
  /// while a job runs or once a job has drawn a model over the points.
  void show_measured(const analysis::EdcDataset& data, const QString& error = {});

  /// The last fit that finished (not cancelled), with its objective; null before.
  const analysis::FitResult* fit_result() const;
  std::shared_ptr<const analysis::EdcObjective> fit_objective() const;
  /// Opens the figures of the last fit (computing their data first when needed, on the worker).
  void show_figures();
  /// Writes the last fit's FIT JSON (fit.json), figures (PNG) and tables (CSV) into `dir`,
  /// computing the figure data first when needed; export_finished says how it went.
  void export_results(const QString& dir);
  /// The HBM branches (continuation in f0 at the test frequency, one per well) and the
  /// bifurcation map of the fitted model, each in its own dialog (computed when opened).
  ResponseDialog* open_branch_dialog();
  ResponseDialog* open_map_dialog();
  FigureDialog* figures_dialog() const { return figures_dialog_; }

  QPushButton* fit_button() const { return fit_button_; }
  QPushButton* diagnose_button() const { return diagnose_button_; }
  QPushButton* cancel_button() const { return cancel_button_; }
  QTableWidget* parameter_table() const { return parameter_table_; }
  QTableWidget* step_table() const { return diagnosis_view_->step_table(); }
  QTableWidget* budget_table() const { return diagnosis_view_->budget_table(); }
  QLabel* status_label() const { return status_label_; }
  QLabel* verdict_label() const { return diagnosis_view_->verdict_label(); }
  QCustomPlot* edc_plot() const { return edc_plot_; }
  QCustomPlot* residual_plot() const { return diagnosis_view_->residual_plot(); }
  /// The energy the baseline misses against |Z1| (figures::missing_energy_figure).
  QCustomPlot* missing_energy_plot() const { return diagnosis_view_->missing_energy_plot(); }
  /// Best χ² against model evaluations, growing while a fit runs (Fig. 14).
  QCustomPlot* convergence_plot() const { return convergence_plot_; }
  QTabWidget* tabs() const { return tabs_; }
  QPushButton* figures_button() const { return figures_button_; }
  QPushButton* export_button() const { return export_button_; }
  QPushButton* branch_button() const { return branch_button_; }
  QPushButton* map_button() const { return map_button_; }

 Q_SIGNALS:
  /// A fit or a diagnosis ended (finished, cancelled or failed); `message` says which.
  void job_finished(const QString& message);
  /// A fit finished (not cancelled, no error): the fitted model (the form built at θ̄), for the
  /// rest of the app (the live monitor draws its EDC). Emitted before job_finished.
  void model_fitted(std::shared_ptr<const oscilab::analysis::Model> model);
  /// The best model so far of a running fit. Emitted on the worker thread at most 5 times a
  /// second; the panel draws it through a queued connection.
  void fit_preview(std::shared_ptr<const oscilab::ui::FitPreview> preview);
  /// The figures dialog shows the figures of the last fit.
  void figures_shown();
  /// An export of results ended; `ok` false with the reason in `message`.
  void export_finished(const QString& message, bool ok);

 protected:
  void resizeEvent(QResizeEvent* event) override;

 private:
  void connect_jobs();
  QGroupBox* make_records_group();
  FlowLayout* make_buttons();
  void make_results();
  /// The recordings and the base model to fit or diagnose, or false with the reason shown.
  bool job_inputs(std::vector<std::string>& paths, analysis::FitSetup& setup);
  void set_busy(bool busy);
  void update_result_buttons();
  void on_fit_finished(std::shared_ptr<const FitOutcome> outcome);
  void on_diagnosis_finished(std::shared_ptr<const DiagnosisOutcome> outcome);
  /// The buttons and the progress bar after a fit or a diagnosis.
  void begin_job(const QString& status);  // a search starts: plots cleared, buttons busy
  void end_job(bool completed);           // completed: finished, not cancelled and without error
  /// "Error: …" or "Cancelled." for a job that ended so; empty when it finished.
  QString ended_text(const std::string& error, bool cancelled) const;
  /// Runs `then` once the figure data of the last fit exists (at once, or after the worker
  /// computed it; not at all when that is cancelled). With `export_dir`, the worker also writes
  /// the FIT JSON, the CSV tables and the PNG figures there.
  void with_figure_data(std::function<void()> then, const QString& export_dir = {});
  void on_figure_data_finished(std::shared_ptr<const FigureDataOutcome> outcome);
  void show_preview(std::shared_ptr<const oscilab::ui::FitPreview> preview);
  ResponseDialog* open_response_dialog(bool map);
  /// A fit's best χ² so far (called on the UI thread, from the worker's queued reports).
  void add_convergence_point(long evaluations, double best_weighted_cost);
  void show_fit(const FitOutcome& outcome);
  void show_diagnosis(const DiagnosisOutcome& outcome);
  void plot_edc(const analysis::EdcObjective& objective,
                const std::vector<std::vector<double>>& edc_mod_j, const QString& model_name);
  // The measured points (±3σ) of `groups` and, when `edc_mod_j` has them, the model's line.
  void plot_edc(const std::vector<analysis::EdcGroup>& groups,
                const std::vector<std::vector<double>>& edc_mod_j, const QString& model_name);

  FitJob* fit_job_ = nullptr;
  DiagnosisJob* diagnosis_job_ = nullptr;
  FigureDataJob* figure_data_job_ = nullptr;
  std::shared_ptr<const FitOutcome> fitted_;  // the last finished fit, for figures and dialogs
  bool model_drawn_ = false;  // a job drew a model's EDC: the measured-only view stays away
  std::shared_ptr<const figures::FitFigureData> figure_data_;  // of fitted_, once computed
  std::function<void()> after_figure_data_;
  FigureDialog* figures_dialog_ = nullptr;
  long baseline_evaluations_ = analysis::DiagnosisOptions{}.baseline_evaluations;
  long candidate_evaluations_ = analysis::DiagnosisOptions{}.candidate_evaluations;
  double bic_threshold_ = analysis::DiagnosisOptions{}.bic_threshold;

  QListWidget* record_list_ = nullptr;
  FitSettingsForm* settings_form_ = nullptr;
  QPushButton* add_button_ = nullptr;
  QPushButton* fit_button_ = nullptr;
  QPushButton* diagnose_button_ = nullptr;
  QPushButton* cancel_button_ = nullptr;
  QPushButton* figures_button_ = nullptr;
  QPushButton* export_button_ = nullptr;
  QPushButton* branch_button_ = nullptr;
  QPushButton* map_button_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel* status_label_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  QSplitter* splitter_ = nullptr;  // the set-up above the results
  QWidget* setup_ = nullptr;       // the recordings and settings, scrolled above the results
  bool splitter_placed_ = false;   // the user moved the divider: it stays where they put it
  QTableWidget* parameter_table_ = nullptr;
  DiagnosisView* diagnosis_view_ = nullptr;
  QCustomPlot* edc_plot_ = nullptr;
  QCustomPlot* convergence_plot_ = nullptr;
};

}  // namespace oscilab::ui
