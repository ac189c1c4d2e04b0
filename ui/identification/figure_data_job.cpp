#include "ui/identification/figure_data_job.h"

#include <exception>

#include "daq/recording/fit_json.h"
#include "ui/background_job.h"

namespace oscilab::ui {

FigureDataJob::FigureDataJob(QObject* parent) : QObject(parent) {
  job_ = new BackgroundJob(this);
  connect(job_, &BackgroundJob::finished, this, [this](bool cancelled) {
    outcome_->cancelled = cancelled;
    Q_EMIT finished(outcome_);
  });
}

// The worker writes outcome_ and must end before the job goes.
FigureDataJob::~FigureDataJob() { delete job_; }

bool FigureDataJob::running() const { return job_->running(); }

void FigureDataJob::cancel() { job_->cancel(); }

bool FigureDataJob::start(std::shared_ptr<const FitOutcome> fit,
                          std::shared_ptr<const figures::FitFigureData> existing,
                          std::string export_dir) {
  if (job_->running() || !fit || !fit->objective) return false;
  auto outcome = std::make_shared<FigureDataOutcome>();
  outcome->export_dir = export_dir;
  outcome_ = outcome;
  return job_->start([outcome, fit = std::move(fit), existing = std::move(existing),
                      dir = std::move(export_dir)](const ProgressFn&, const CancelToken& cancel) {
    try {
      auto data = std::make_shared<figures::FitFigureData>(
          existing ? *existing
                   : figures::fit_figure_data(*fit->objective, fit->fit.theta, 0, cancel));
      if (!dir.empty() && !cancel.cancelled()) {
        daq::write_fit_json(dir + "/fit.json", fit->fit, *fit->objective, fit->records, fit->notes);
        figures::write_fit_figures(dir, fit->fit, *fit->objective, *data, true);
      }
      outcome->data = std::move(data);
    } catch (const std::exception& e) {  // InputError: a file that cannot be written
      outcome->error = e.what();
    }
  });
}

}  // namespace oscilab::ui
