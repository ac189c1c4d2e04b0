#include "ui/identification/bifurcation_map_job.h"

#include <exception>

#include "ui/background_job.h"
#include "ui/identification/branch_job.h"

namespace oscilab::ui {
namespace {

// Share of the progress bar the branches take before a map (they take ~0.1 s, the map seconds).
constexpr double kBranchShareOfMap = 0.1;

}  // namespace

BifurcationMapJob::BifurcationMapJob(QObject* parent) : QObject(parent) {
  job_ = new BackgroundJob(this);
  connect(job_, &BackgroundJob::progress, this, &BifurcationMapJob::progress);
  connect(job_, &BackgroundJob::finished, this, [this](bool cancelled) {
    outcome_->cancelled = cancelled;
    Q_EMIT finished(outcome_);
  });
}

// The worker writes outcome_ and must end before the job goes.
BifurcationMapJob::~BifurcationMapJob() { delete job_; }

bool BifurcationMapJob::running() const { return job_->running(); }

void BifurcationMapJob::cancel() { job_->cancel(); }

bool BifurcationMapJob::start(std::shared_ptr<const analysis::Model> model,
                              std::vector<analysis::ContinuationOptions> continuations,
                              analysis::BifurcationMapOptions map) {
  if (job_->running() || !model) return false;
  auto outcome = std::make_shared<BifurcationMapOutcome>();
  outcome_ = outcome;
  return job_->start([outcome, model = std::move(model), continuations = std::move(continuations),
                      map](const ProgressFn& progress, const CancelToken& cancel) {
    try {
      outcome->branches = continue_branches(
          *model, continuations, [&](double f) { progress(kBranchShareOfMap * f); }, cancel);
      if (!cancel.cancelled()) {
        outcome->map = analysis::bifurcation_map(
            *model, map,
            [&](double f) { progress(kBranchShareOfMap + (1.0 - kBranchShareOfMap) * f); }, cancel);
      }
    } catch (const std::exception& error) {  // InputError: options the core rejects
      outcome->error = error.what();
    }
  });
}

}  // namespace oscilab::ui
