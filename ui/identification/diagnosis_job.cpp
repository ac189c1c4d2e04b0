#include "ui/identification/diagnosis_job.h"

#include <exception>
#include <memory>
#include <string>

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
  return job_->start([this, outcome, paths = std::move(recordings), setup, options](
                         const ProgressFn& progress, const CancelToken& cancel) {
    // The stage's words reach the UI thread queued, only when they change; the job is joined
    // before this object goes, and a queued call to a destroyed object is dropped.
    const auto say = [this, last = std::make_shared<std::string>()](const std::string& text) {
      if (text == *last) return;
      *last = text;
      QMetaObject::invokeMethod(
          this, [this, words = QString::fromStdString(text)] { Q_EMIT stage(words); },
          Qt::QueuedConnection);
    };
    try {
      say("analysing the recordings");
      const analysis::CampaignAnalysis campaign =
          daq::analyze_recordings(paths, {}, {}, {}, cancel);
      if (campaign.status == JobStatus::Cancelled) return;  // reported as cancelled, no error
      const analysis::ModelForm form = analysis::fit_form(campaign, setup, outcome->notes);
      outcome->result = analysis::diagnose(
          campaign, form, options,
          [&](const analysis::DiagnosisProgress& p) {
            progress(p.fraction);
            say(p.describe());
          },
          cancel);
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
