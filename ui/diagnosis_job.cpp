#include "ui/diagnosis_job.h"

#include <exception>

#include "analysis/common/input_error.h"
#include "analysis/identification/edc_dataset.h"
#include "daq/recording/campaign_reader.h"
#include "ui/background_job.h"

namespace oscilab::ui {

DiagnosisJob::DiagnosisJob(QObject* parent) : QObject(parent) {
  job_ = new BackgroundJob(this);
  connect(job_, &BackgroundJob::progress, this, &DiagnosisJob::progress);
  connect(job_, &BackgroundJob::finished, this, [this](bool cancelled) {
    outcome_->cancelled = cancelled;
    Q_EMIT finished(outcome_);
  });
}

// The worker writes outcome_ and must end before the job goes.
DiagnosisJob::~DiagnosisJob() { delete job_; }

bool DiagnosisJob::running() const { return job_->running(); }

void DiagnosisJob::cancel() { job_->cancel(); }

bool DiagnosisJob::start(std::vector<std::string> recordings, analysis::FitSetup setup,
                         analysis::DiagnosisOptions options) {
  if (job_->running()) return false;
  auto outcome = std::make_shared<DiagnosisOutcome>();
  outcome_ = outcome;
  return job_->start([outcome, paths = std::move(recordings), setup, options](
                         const ProgressFn& progress, const CancelToken& cancel) {
    try {
      const analysis::CampaignAnalysis campaign =
          daq::analyze_recordings(paths, {}, {}, {}, cancel);
      if (campaign.status == JobStatus::Cancelled) return;  // reported as cancelled, no error
      const analysis::ModelForm form = analysis::fit_form(campaign, setup, outcome->notes);
      outcome->result = analysis::diagnose(campaign, form, options, progress, cancel);
      const analysis::DiagnosisResult& r = outcome->result;
      if (r.final_form) {
        outcome->objective = std::make_shared<const analysis::EdcObjective>(
            *r.final_form, analysis::edc_dataset(campaign), r.final_cost);
      }
    } catch (const InputError& error) {
      outcome->error = error.what();
    } catch (const std::exception& error) {
      outcome->error = std::string("internal error: ") + error.what();
    }
  });
}

}  // namespace oscilab::ui
