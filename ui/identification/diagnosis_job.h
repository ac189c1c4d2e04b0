#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QObject>

#include "analysis/diagnosis/diagnosis.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/identification/fit_setup.h"
#include "ui/outcome_job.h"

namespace oscilab::ui {

/// What a diagnosis hands back when it ends (finished, cancelled or failed).
struct DiagnosisOutcome {
  bool cancelled = false;
  std::string error;               // InputError text: bad recordings
  std::vector<std::string> notes;  // how the base model was set up (campaign_model)
  analysis::DiagnosisResult result;
  /// The final model's objective over the measured levels, when there is a final model.
  std::shared_ptr<const analysis::EdcObjective> objective;
};

/// A model-gap diagnosis on a worker thread (ui/outcome_job.h): the recordings' analysis
/// (daq::analyze_recordings), the paper's form of the base model (analysis::fit_form) and the
/// diagnosis (analysis::diagnose), with progress and cancel. The computing is the analysis
/// core's. Thread-safety: UI thread only.
class DiagnosisJob : public QObject {
  Q_OBJECT

 public:
  explicit DiagnosisJob(QObject* parent = nullptr);

  /// Returns false (and does nothing) while a diagnosis runs.
  bool start(std::vector<std::string> recordings, analysis::FitSetup setup,
             analysis::DiagnosisOptions options);
  void cancel() { work_.cancel(); }
  bool running() const { return work_.running(); }

 Q_SIGNALS:
  void progress(double fraction_done);
  /// What the diagnosis is doing, in words (analysis::DiagnosisProgress::describe), when it
  /// changes (UI thread).
  void stage(const QString& text);
  /// The diagnosis ended (UI thread).
  void finished(std::shared_ptr<const oscilab::ui::DiagnosisOutcome> outcome);

 private:
  OutcomeJob<DiagnosisOutcome> work_{this, &DiagnosisJob::finished, &DiagnosisJob::progress};
};

}  // namespace oscilab::ui
