#include "ui/identification/branch_job.h"

#include <exception>

#include "ui/background_job.h"

namespace oscilab::ui {

std::vector<analysis::Branch> continue_branches(
    const analysis::Model& model, const std::vector<analysis::ContinuationOptions>& continuations,
    const ProgressFn& progress, const CancelToken& cancel) {
  std::vector<analysis::Branch> branches;
  const double n = static_cast<double>(continuations.size());
  for (std::size_t i = 0; i < continuations.size() && !cancel.cancelled(); ++i) {
    branches.push_back(analysis::continue_branch(
        model, continuations[i],
        [&](double f) {
          if (progress) progress((static_cast<double>(i) + f) / n);
        },
        cancel));
  }
  return branches;
}

BranchJob::BranchJob(QObject* parent) : QObject(parent) {
  job_ = new BackgroundJob(this);
  connect(job_, &BackgroundJob::progress, this, &BranchJob::progress);
  connect(job_, &BackgroundJob::finished, this, [this](bool cancelled) {
    outcome_->cancelled = cancelled;
    Q_EMIT finished(outcome_);
  });
}

// The worker writes outcome_ and must end before the job goes.
BranchJob::~BranchJob() { delete job_; }

bool BranchJob::running() const { return job_->running(); }

void BranchJob::cancel() { job_->cancel(); }

bool BranchJob::start(std::shared_ptr<const analysis::Model> model,
                      std::vector<analysis::ContinuationOptions> continuations) {
  if (job_->running() || !model) return false;
  auto outcome = std::make_shared<BranchOutcome>();
  outcome_ = outcome;
  return job_->start([outcome, model = std::move(model), continuations = std::move(continuations)](
                         const ProgressFn& progress, const CancelToken& cancel) {
    try {
      outcome->branches = continue_branches(*model, continuations, progress, cancel);
    } catch (const std::exception& error) {  // InputError: options the core rejects
      outcome->error = error.what();
    }
  });
}

}  // namespace oscilab::ui
