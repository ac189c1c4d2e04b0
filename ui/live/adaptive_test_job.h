#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <QObject>

#include "analysis/design/adaptive_test.h"
#include "analysis/model/model.h"
#include "analysis/model/reference_models.h"
#include "daq/rig/rig_level_runner.h"
#include "ui/outcome_job.h"

namespace oscilab::ui {

/// One decision of a running adaptive test as the app shows it (copied off the worker).
struct AdaptiveTestStep {
  int index = 0;
  double shaker_time_s = 0.0;
  int levels = 0;
  std::vector<std::string> labels;   // ModelHypothesis::label(), the baseline first
  std::vector<double> weights;       // of each hypothesis
  std::vector<double> reduced_chi2;  // ModelHypothesis::reduced_edc_chi2() of each (NaN: ν ≤ 0)
  analysis::StopDecision decision;
  bool proposed = false;  // the test goes on: `proposal` is what it would run next
  analysis::SettingScore proposal;
  std::string proposal_reason;  // NextPoint::reason
  double update_s = 0.0;        // refits after the last level plus this proposal
};

/// How an adaptive test ended.
struct AdaptiveTestOutcome {
  bool cancelled = false;
  std::string error;  // InputError text (a refused option, an unwritable folder)
  analysis::AdaptiveTestResult result;
  std::vector<std::string> recordings;  // written under the folder's recordings/
  std::string folder;
};

/// An adaptive test on the virtual rig (daq::RigLevelRunner, as fast as it computes) on a worker
/// thread: analysis::run_adaptive_test with its decisions, progress and end reaching the UI
/// thread by queued signals, and the folder the CLI's `adaptive-test` writes
/// (daq::AdaptiveTestFolder). In auto mode every proposal runs; otherwise the worker waits at
/// each proposal for answer() (Run, Skip, Stop). Thread-safety: UI thread only.
class AdaptiveTestJob : public QObject {
  Q_OBJECT

 public:
  struct Request {
    analysis::Model rig_truth = analysis::paper_model();  // what the virtual rig simulates
    daq::RigLevelRunner::Schedule schedule;
    unsigned long long seed = 1;
    analysis::AdaptiveTestOptions options;
    std::string folder;  // recordings/, decisions.jsonl, report.json
    bool auto_mode = true;
  };

  explicit AdaptiveTestJob(QObject* parent = nullptr);
  ~AdaptiveTestJob() override;  // cancels, releases a waiting proposal and joins

  /// Returns false (and does nothing) while a test runs.
  bool start(Request request);
  void cancel();
  bool running() const { return work_.running(); }
  /// Whether the worker waits for an answer to the last proposal.
  bool awaiting_answer() const;
  /// The operator's answer to the proposal waited on (ignored when none is).
  void answer(analysis::ProposalAnswer answer);
  /// Auto mode on: a proposal waited on runs, and so does every later one.
  void set_auto(bool on);

 Q_SIGNALS:
  void progress(double fraction_done);
  /// A decision was made (UI thread).
  void decided(const oscilab::ui::AdaptiveTestStep& step);
  /// The worker began (true) or ended (false) waiting for answer() to the last decision's
  /// proposal (UI thread, after its decided()).
  void awaiting_changed(bool awaiting);
  void finished(std::shared_ptr<const oscilab::ui::AdaptiveTestOutcome> outcome);

 private:
  analysis::ProposalAnswer wait_for_answer(const CancelToken& cancel);

  mutable std::mutex mutex_;  // guards the three below
  std::condition_variable answered_;
  bool auto_mode_ = true;
  bool awaiting_ = false;
  std::optional<analysis::ProposalAnswer> answer_;
  // Last, so that it goes first: its destructor joins the worker, which waits on the above.
  OutcomeJob<AdaptiveTestOutcome> work_{this, &AdaptiveTestJob::finished,
                                        &AdaptiveTestJob::progress};
};

/// The step the app shows of a decision and the hypotheses as weighed for it.
AdaptiveTestStep adaptive_test_step(const analysis::AdaptiveDecision& decision,
                                    const std::vector<analysis::ModelHypothesis>& hypotheses);

}  // namespace oscilab::ui
