#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QObject>

#include "analysis/common/job.h"
#include "analysis/hbm/branch.h"
#include "analysis/hbm/continuation.h"
#include "analysis/model/model.h"
#include "ui/outcome_job.h"

namespace oscilab::ui {

/// What a continuation of branches hands back when it ends (finished, cancelled or failed).
struct BranchOutcome {
  bool cancelled = false;
  std::string error;                       // InputError text: options the core rejects
  std::vector<analysis::Branch> branches;  // one per continuation, in the order given
};

/// The harmonic-balance branches of a model, one continuation after the other
/// (analysis::continue_branch), with `progress` over all of them; stops at `cancel`. For the
/// workers of BranchJob and BifurcationMapJob; throws InputError as continue_branch does.
std::vector<analysis::Branch> continue_branches(
    const analysis::Model& model, const std::vector<analysis::ContinuationOptions>& continuations,
    const ProgressFn& progress, const CancelToken& cancel);

/// The HBM branches of a model (one per well, as `oscilab-cli hbm`) on a worker thread
/// (ui/outcome_job.h), with progress and cancel. Thread-safety: UI thread only.
class BranchJob : public QObject {
  Q_OBJECT

 public:
  explicit BranchJob(QObject* parent = nullptr);

  /// Returns false (and does nothing) while one runs.
  bool start(std::shared_ptr<const analysis::Model> model,
             std::vector<analysis::ContinuationOptions> continuations);
  void cancel() { work_.cancel(); }
  bool running() const { return work_.running(); }

 Q_SIGNALS:
  void progress(double fraction_done);
  /// The branches ended (UI thread).
  void finished(std::shared_ptr<const oscilab::ui::BranchOutcome> outcome);

 private:
  OutcomeJob<BranchOutcome> work_{this, &BranchJob::finished, &BranchJob::progress};
};

}  // namespace oscilab::ui
