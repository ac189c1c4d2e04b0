#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QMetaType>
#include <QObject>

#include "analysis/identification/edc_fit.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/identification/fit_setup.h"
#include "ui/outcome_job.h"

namespace oscilab::ui {

/// The best model of a running fit so far, made on the fit's worker thread and handed to the UI
/// thread by a queued signal: its EDC at every measured level (live progress).
struct FitPreview {
  long fit_number = 0;  // which fit of its job sent it (FitJob::is_current)
  long evaluations = 0;
  double best_weighted_cost = 0.0;  // χ² of the best θ so far
  Eigen::VectorXd theta;            // the best θ so far
  /// The measured levels (immutable; shared with the worker, which only evaluates it).
  std::shared_ptr<const analysis::EdcObjective> objective;
  /// S^mod at the best θ, per group and level of objective->data() (0: not solved), J.
  std::vector<std::vector<double>> edc_mod_j;
};

/// What a fit hands back when it ends (finished, cancelled or failed).
struct FitOutcome {
  bool cancelled = false;
  std::string error;                 // InputError text: bad recordings, a model that fails
  std::vector<std::string> records;  // the recordings fitted, as given
  std::vector<std::string> notes;    // how the base model was set up (campaign_model)
  std::shared_ptr<const analysis::EdcObjective> objective;  // null when it failed early
  analysis::FitResult fit;
};

/// A friction fit on a worker thread (ui/outcome_job.h): the recordings' analysis
/// (daq::analyze_recordings), the objective (analysis::prepare_fit) and the search
/// (analysis::fit_edc), with progress and cancel. While the search runs it reports the best χ² so
/// far (at most every 50 ms) and the model EDC of the best θ so far (at most 5 times a second);
/// at the end, its outcome. The computing is the analysis core's.
///
/// Thread-safety: UI thread only; preview() is emitted on the worker thread.
class FitJob : public QObject {
  Q_OBJECT

 public:
  explicit FitJob(QObject* parent = nullptr);

  /// Returns false (and does nothing) while a fit runs.
  bool start(std::vector<std::string> recordings, analysis::FitSetup setup,
             analysis::FitOptions options);
  void cancel() { work_.cancel(); }
  bool running() const { return work_.running(); }
  /// Whether `preview` is of the fit that runs (one queued before an older fit ended is not);
  /// reads nothing the worker writes.
  bool is_current(const FitPreview& preview) const;

 Q_SIGNALS:
  void progress(double fraction_done);
  /// The best χ² so far against the model evaluations (UI thread).
  void convergence_point(long evaluations, double best_weighted_cost);
  /// The model EDC of the best θ so far. Emitted on the worker thread.
  void preview(std::shared_ptr<const oscilab::ui::FitPreview> preview);
  /// The fit ended (UI thread).
  void finished(std::shared_ptr<const oscilab::ui::FitOutcome> outcome);

 private:
  long fits_started_ = 0;  // UI thread only: the number of the fit running or last run
  // The worker emits preview() on this object: it ends before the signal goes (work_ is
  // destroyed first, and its destructor cancels and joins).
  OutcomeJob<FitOutcome> work_{this, &FitJob::finished, &FitJob::progress};
};

}  // namespace oscilab::ui

Q_DECLARE_METATYPE(std::shared_ptr<const oscilab::ui::FitPreview>)
