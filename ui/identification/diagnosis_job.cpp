#include "ui/identification/diagnosis_job.h"

#include <memory>
#include <string>

#include <QMetaObject>

#include "analysis/identification/edc_dataset.h"
#include "daq/recording/campaign_reader.h"

namespace oscilab::ui {

DiagnosisJob::DiagnosisJob(QObject* parent) : QObject(parent) {}

bool DiagnosisJob::start(std::vector<std::string> recordings, analysis::FitSetup setup,
                         analysis::DiagnosisOptions options) {
  return work_.start(
      std::make_shared<DiagnosisOutcome>(),
      [this, paths = std::move(recordings), setup, options](
          DiagnosisOutcome& outcome, const ProgressFn& progress, const CancelToken& cancel) {
        // The stage's words reach the UI thread queued, only when they change; the job is joined
        // before this object goes, and a queued call to a destroyed object is dropped.
        const auto say = [this, last = std::make_shared<std::string>()](const std::string& text) {
          if (text == *last) return;
          *last = text;
          QMetaObject::invokeMethod(
              this, [this, words = QString::fromStdString(text)] { Q_EMIT stage(words); },
              Qt::QueuedConnection);
        };
        say("analysing the recordings");
        const analysis::CampaignAnalysis campaign =
            daq::analyze_recordings(paths, {}, {}, {}, cancel);
        if (campaign.status == JobStatus::Cancelled) return;  // reported as cancelled, no error
        const analysis::ModelForm form = analysis::fit_form(campaign, setup, outcome.notes);
        outcome.result = analysis::diagnose(
            campaign, form, options,
            [&](const analysis::DiagnosisProgress& p) {
              progress(p.fraction);
              say(p.describe());
            },
            cancel);
        const analysis::DiagnosisResult& r = outcome.result;
        if (r.final_form) {
          outcome.objective = std::make_shared<const analysis::EdcObjective>(
              *r.final_form, analysis::edc_dataset(campaign), r.final_cost);
        }
      });
}

}  // namespace oscilab::ui
