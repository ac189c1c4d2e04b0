#pragma once

#include <QWidget>

#include "analysis/diagnosis/diagnosis.h"

class QCustomPlot;
class QLabel;
class QScrollArea;
class QTableWidget;

namespace oscilab::ui {

/// What a model-gap diagnosis found, for the fit panel: the verdict with the evidence that
/// supported it and the response fingerprints before and after; every candidate of every step
/// with its ΔBIC (EDC alone and joint), how each piece of evidence moved (Δχ²) and why it was
/// accepted or not; and, each on a page of its own, the EDC residuals in σ before and after
/// (residual_page()), the energy the baseline misses against the response amplitude, whose
/// log-log slope names the missing dissipation law (missing_energy_page()), and the final model's
/// σ budget per level (budget_page()). It displays; the numbers come from analysis::diagnose, the
/// figures from analysis/figures/diagnosis_figures.h (as `oscilab-cli diagnose` draws them).
class DiagnosisView : public QWidget {
 public:
  explicit DiagnosisView(QWidget* parent = nullptr);

  void show_result(const analysis::DiagnosisResult& result, double bic_threshold);

  QWidget* budget_page() const { return budget_page_; }
  QWidget* residual_page() const;
  QWidget* missing_energy_page() const;
  QLabel* verdict_label() const { return verdict_label_; }
  QTableWidget* step_table() const { return step_table_; }
  QCustomPlot* residual_plot() const { return residual_plot_; }
  QCustomPlot* missing_energy_plot() const { return missing_energy_plot_; }
  QTableWidget* budget_table() const { return budget_table_; }

 private:
  void show_steps(const analysis::DiagnosisResult& result, double bic_threshold);
  void show_residuals(const analysis::DiagnosisResult& result);
  void show_missing_energy(const analysis::DiagnosisResult& result);
  void show_budget(const analysis::DiagnosisResult& result);

  QLabel* verdict_label_ = nullptr;
  QTableWidget* step_table_ = nullptr;
  QCustomPlot* residual_plot_ = nullptr;
  QCustomPlot* missing_energy_plot_ = nullptr;
  QWidget* budget_page_ = nullptr;
  QScrollArea* residual_page_ = nullptr;  // the residual plot, scrolled on a short screen
  QLabel* budget_label_ = nullptr;
  QTableWidget* budget_table_ = nullptr;
};

}  // namespace oscilab::ui
