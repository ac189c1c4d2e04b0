#include "ui/identification/branch_job.h"

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

BranchJob::BranchJob(QObject* parent) : QObject(parent) {}

bool BranchJob::start(std::shared_ptr<const analysis::Model> model,
                      std::vector<analysis::ContinuationOptions> continuations) {
  if (!model) return false;
  return work_.start(
      std::make_shared<BranchOutcome>(),
      [model = std::move(model), continuations = std::move(continuations)](
          BranchOutcome& outcome, const ProgressFn& progress, const CancelToken& cancel) {
        outcome.branches = continue_branches(*model, continuations, progress, cancel);
      });
}

}  // namespace oscilab::ui
