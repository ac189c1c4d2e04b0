#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <thread>

#include <QObject>

#include "analysis/common/job.h"

namespace oscilab::ui {

/// Long work (a fit, a diagnosis) on its own thread, with progress and cancellation, never on the
/// UI thread: start() runs `work(progress, cancel)` on a std::thread; progress reaches the UI
/// thread by queued signals, coalesced to changes of at least 0.5 %; finished() is emitted on the
/// UI thread after the work returned. `work` must not throw (jobs report a status) and must poll
/// the token. The destructor cancels and joins.
///
/// Thread-safety: start(), cancel() and running() are for the UI thread.
class BackgroundJob : public QObject {
  Q_OBJECT

 public:
  using Work = std::function<void(const ProgressFn& progress, const CancelToken& cancel)>;

  explicit BackgroundJob(QObject* parent = nullptr);
  ~BackgroundJob() override;

  /// Returns false (and does nothing) while a job is running.
  bool start(Work work);
  void cancel();
  bool running() const { return running_; }

 Q_SIGNALS:
  void progress(double fraction_done);
  void finished(bool cancelled);

 private:
  void join();

  std::thread thread_;
  CancelToken cancel_;
  bool running_ = false;
  std::shared_ptr<std::atomic<int>> last_permille_ = std::make_shared<std::atomic<int>>(-1);
};

}  // namespace oscilab::ui
