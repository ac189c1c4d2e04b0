#include "ui/identification/bifurcation_map_job.h"

#include "ui/identification/branch_job.h"

namespace oscilab::ui {
namespace {

// Share of the progress bar the branches take before a map (they take ~0.1 s, the map seconds).
constexpr double kBranchShareOfMap = 0.1;

}  // namespace

BifurcationMapJob::BifurcationMapJob(QObject* parent) : QObject(parent) {}

bool BifurcationMapJob::start(std::shared_ptr<const analysis::Model> model,
                              std::vector<analysis::ContinuationOptions> continuations,
                              analysis::BifurcationMapOptions map) {
  if (!model) return false;
  return work_.start(
      std::make_shared<BifurcationMapOutcome>(),
      [model = std::move(model), continuations = std::move(continuations), map](
          BifurcationMapOutcome& outcome, const ProgressFn& progress, const CancelToken& cancel) {
        outcome.branches = continue_branches(
            *model, continuations, [&](double f) { progress(kBranchShareOfMap * f); }, cancel);
        if (cancel.cancelled()) return;
        outcome.map = analysis::bifurcation_map(
            *model, map,
            [&](double f) { progress(kBranchShareOfMap + (1.0 - kBranchShareOfMap) * f); }, cancel);
      });
}

}  // namespace oscilab::ui
