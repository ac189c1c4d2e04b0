#pragma once

#include <memory>
#include <string>

#include <QObject>

#include "analysis/figures/fit_figures.h"
#include "ui/identification/fit_job.h"
#include "ui/outcome_job.h"

namespace oscilab::ui {

/// What the figure data of a fit hands back when it ends (finished, cancelled or failed).
struct FigureDataOutcome {
  bool cancelled = false;
  std::string error;                                   // InputError text: a file not written
  std::shared_ptr<const figures::FitFigureData> data;  // complete unless cancelled or failed
  std::string export_dir;                              // where the results went ("": nowhere)
};

/// The data of a fit's figures beyond the fit itself (cost slices, sensitivity curves:
/// figures::fit_figure_data) on a worker thread (ui/outcome_job.h), with cancel; and, when
/// asked, the results written into a folder: the FIT JSON (daq::write_fit_json, as `oscilab-cli
/// fit`), the figures as PNG and their tables as CSV (figures::write_fit_figures). The slices and
/// curves report no fraction done. Thread-safety: UI thread only.
class FigureDataJob : public QObject {
  Q_OBJECT

 public:
  explicit FigureDataJob(QObject* parent = nullptr);

  /// Computes the figure data of `fit` (or takes `existing`, when given) and, with a non-empty
  /// `export_dir`, writes the results there. Returns false (and does nothing) while one runs.
  bool start(std::shared_ptr<const FitOutcome> fit,
             std::shared_ptr<const figures::FitFigureData> existing, std::string export_dir);
  void cancel() { work_.cancel(); }
  bool running() const { return work_.running(); }

 Q_SIGNALS:
  /// The data (and the export) ended (UI thread).
  void finished(std::shared_ptr<const oscilab::ui::FigureDataOutcome> outcome);

 private:
  OutcomeJob<FigureDataOutcome> work_{this, &FigureDataJob::finished};
};

}  // namespace oscilab::ui
