#pragma once

#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <utility>

#include <QObject>

#include "analysis/common/input_error.h"
#include "analysis/common/job.h"
#include "ui/background_job.h"

namespace oscilab::ui {

/// What every job of the app shares (a fit, a diagnosis, branches, a map, figures, an adaptive
/// test, a live prediction): a BackgroundJob whose work fills an `Outcome`, a struct with at
/// least `bool cancelled` and `std::string error`. start() hands the work a fresh outcome; an
/// InputError the work throws becomes `error` (its text), any other exception `error` "internal
/// error: …", so that the work never throws past the thread; when the work has returned, the
/// owner's `finished` signal (or slot) gets the outcome on the UI thread with `cancelled` set.
///
/// A member of the job class that owns it (the QObject with the typed signals, which moc cannot
/// generate for a template). Its destructor cancels and joins the worker: declare it after every
/// member the work uses, so that it goes first. Thread-safety: UI thread only.
template <class Outcome>
class OutcomeJob {
 public:
  using Work =
      std::function<void(Outcome& outcome, const ProgressFn& progress, const CancelToken& cancel)>;

  /// `finished` is the owner's member receiving the outcome; `progress`, when given, the owner's
  /// signal the worker's progress (0 … 1) is forwarded to.
  template <class Owner>
  OutcomeJob(Owner* owner, void (Owner::*finished)(std::shared_ptr<const Outcome>),
             void (Owner::*progress)(double) = nullptr)
      : job_(new BackgroundJob(owner)) {
    if (progress) QObject::connect(job_, &BackgroundJob::progress, owner, progress);
    QObject::connect(job_, &BackgroundJob::finished, owner, [this, owner, finished](bool cancel) {
      outcome_->cancelled = cancel;
      (owner->*finished)(outcome_);
    });
  }
  ~OutcomeJob() { delete job_; }  // cancels and joins
  OutcomeJob(const OutcomeJob&) = delete;
  OutcomeJob& operator=(const OutcomeJob&) = delete;

  /// Runs `work` on `outcome` on the worker thread; false (and nothing) while a job runs.
  bool start(std::shared_ptr<Outcome> outcome, Work work) {
    if (job_->running() || !outcome) return false;
    outcome_ = outcome;
    return job_->start([outcome = std::move(outcome), work = std::move(work)](
                           const ProgressFn& progress, const CancelToken& cancel) {
      try {
        work(*outcome, progress, cancel);
      } catch (const InputError& error) {  // what the core refuses: bad files, options, models
        outcome->error = error.what();
      } catch (const std::exception& error) {
        outcome->error = std::string("internal error: ") + error.what();
      }
    });
  }
  void cancel() { job_->cancel(); }
  bool running() const { return job_->running(); }
  /// The outcome of the job started last (written by its worker while it runs); null before one.
  const std::shared_ptr<Outcome>& current() const { return outcome_; }

 private:
  BackgroundJob* job_;                // a child of the owner, deleted first by the destructor
  std::shared_ptr<Outcome> outcome_;  // of the last job started
};

}  // namespace oscilab::ui
