#pragma once

#include <atomic>
#include <functional>
#include <memory>

namespace oscilab {

/// Cancellation shared between the thread that asks and the worker that polls. Copies share the
/// same flag, so a token handed to a job can be cancelled from the UI thread.
class CancelToken {
 public:
  CancelToken() : flag_(std::make_shared<std::atomic<bool>>(false)) {}
  void cancel() const { flag_->store(true, std::memory_order_relaxed); }
  bool cancelled() const { return flag_->load(std::memory_order_relaxed); }

 private:
  std::shared_ptr<std::atomic<bool>> flag_;
};

/// Progress report of long work: fraction done in [0, 1]. Called from the worker thread.
using ProgressFn = std::function<void(double fraction_done)>;

/// How long work ended: the status of a job, never an exception across threads.
enum class JobStatus { Ok, Cancelled, NoConvergence, NumericalIssue, InvalidInput };

}  // namespace oscilab
