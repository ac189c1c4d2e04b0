#include "ui/live/adaptive_test_job.h"

#include <chrono>
#include <cmath>
#include <utility>

#include <QMetaObject>

#include "daq/recording/adaptive_test_folder.h"

namespace oscilab::ui {

AdaptiveTestStep adaptive_test_step(const analysis::AdaptiveDecision& decision,
                                    const std::vector<analysis::ModelHypothesis>& hypotheses) {
  AdaptiveTestStep step;
  step.index = decision.index;
  step.shaker_time_s = decision.shaker_time_s;
  step.levels = decision.levels;
  for (const analysis::ModelHypothesis& h : hypotheses) {
    step.labels.push_back(h.label());
    step.weights.push_back(h.weight);
    step.reduced_chi2.push_back(h.solved ? h.reduced_edc_chi2() : std::nan(""));
  }
  step.decision = decision.decision;
  step.proposed = !decision.decision.stop && decision.next.found;
  if (step.proposed) {
    step.proposal = decision.next.best;
    step.proposal_reason = decision.next.reason;
  }
  step.update_s = decision.refit_s + decision.proposal_s;
  return step;
}

AdaptiveTestJob::AdaptiveTestJob(QObject* parent) : QObject(parent) {}

// The worker may wait for an answer: release it; work_, destroyed next, joins it.
AdaptiveTestJob::~AdaptiveTestJob() { cancel(); }

bool AdaptiveTestJob::awaiting_answer() const {
  const std::lock_guard lock(mutex_);
  return awaiting_;
}

void AdaptiveTestJob::cancel() {
  work_.cancel();
  answered_.notify_all();
}

void AdaptiveTestJob::answer(analysis::ProposalAnswer answer) {
  {
    const std::lock_guard lock(mutex_);
    if (!awaiting_) return;
    answer_ = answer;
  }
  answered_.notify_all();
}

void AdaptiveTestJob::set_auto(bool on) {
  {
    const std::lock_guard lock(mutex_);
    auto_mode_ = on;
    if (on && awaiting_) answer_ = analysis::ProposalAnswer::Run;
  }
  answered_.notify_all();
}

// The gate of run_adaptive_test, on the worker: Run at once in auto mode, else the operator's
// answer; a cancel releases it (the loop then sees the token).
analysis::ProposalAnswer AdaptiveTestJob::wait_for_answer(const CancelToken& cancel) {
  std::unique_lock lock(mutex_);
  if (auto_mode_) return analysis::ProposalAnswer::Run;
  awaiting_ = true;
  answer_.reset();
  const auto tell = [this](bool waiting) {
    QMetaObject::invokeMethod(
        this, [this, waiting] { Q_EMIT awaiting_changed(waiting); }, Qt::QueuedConnection);
  };
  tell(true);
  // cancel() notifies, but the token is set outside the mutex: a bounded wait closes that race.
  while (!answer_ && !cancel.cancelled()) {
    answered_.wait_for(lock, std::chrono::milliseconds(100));
  }
  awaiting_ = false;
  tell(false);
  return answer_.value_or(analysis::ProposalAnswer::Stop);
}

bool AdaptiveTestJob::start(Request request) {
  if (work_.running()) return false;
  {
    const std::lock_guard lock(mutex_);
    auto_mode_ = request.auto_mode;
    awaiting_ = false;
    answer_.reset();
  }
  auto outcome = std::make_shared<AdaptiveTestOutcome>();
  outcome->folder = request.folder;
  return work_.start(
      std::move(outcome),
      [this, request = std::move(request)](AdaptiveTestOutcome& outcome, const ProgressFn& progress,
                                           const CancelToken& cancel) {
        daq::AdaptiveTestFolder folder(request.folder);
        daq::RigLevelRunner rig(request.rig_truth, folder.recordings_dir(), request.schedule,
                                request.seed);
        // Each decision reaches the UI thread queued; the job is joined before this object goes,
        // and a queued call to a destroyed object is dropped.
        const auto on_decision = [&](const analysis::AdaptiveDecision& d,
                                     const std::vector<analysis::ModelHypothesis>& hypotheses) {
          folder.log(d, hypotheses);
          QMetaObject::invokeMethod(
              this, [this, step = adaptive_test_step(d, hypotheses)] { Q_EMIT decided(step); },
              Qt::QueuedConnection);
        };
        outcome.result = analysis::run_adaptive_test(
            rig, request.options, on_decision, progress, cancel,
            [&](const analysis::AdaptiveDecision&) { return wait_for_answer(cancel); });
        outcome.recordings = rig.paths();
        folder.write_results(outcome.result, outcome.recordings);  // a cancelled one's too
      });
}

}  // namespace oscilab::ui
