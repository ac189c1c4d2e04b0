// Long C++ jobs from Python: the GIL released while they run, progress handed to a Python
// callback on the calling thread, Ctrl-C turned into the job's CancelToken (bindings.h).
#include <pthread.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "bindings.h"

namespace oscilab::python {
namespace {

// How long the calling thread waits between signal checks when the job reports nothing: the
// bound on Ctrl-C's latency on top of the job's own cancel polling.
constexpr auto kSignalPoll = std::chrono::milliseconds(20);

struct JobState {
  std::mutex mutex;
  std::condition_variable wake;
  bool done = false;
  bool has_report = false;
  ProgressReport report;
  std::exception_ptr error;
};

// A thread that runs one job at a time, kept for the next one: the core keeps per-thread
// scratch buffers (spectral_calculus.cpp's thread_local FFT buffers), which a fresh thread per
// call would allocate and fault in anew, a fifth of analyze()'s time on the samples. Workers are
// never destroyed (detached, idle on a condition variable at exit).
class Worker {
 public:
  Worker() {
    std::thread([this] { loop(); }).detach();
  }
  void post(std::function<void()> task) {
    {
      const std::lock_guard lock(mutex_);
      task_ = std::move(task);
    }
    wake_.notify_one();
  }

 private:
  void loop() {
    for (;;) {
      std::function<void()> task;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return static_cast<bool>(task_); });
        task = std::move(task_);
        task_ = nullptr;
      }
      task();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::function<void()> task_;
};

// Idle workers; one more is made when every worker is busy (jobs from several Python threads).
class WorkerPool {
 public:
  Worker* acquire() {
    const std::lock_guard lock(mutex_);
    if (idle_.empty()) return new Worker;  // owned by the pool for the process's life
    Worker* worker = idle_.back();
    idle_.pop_back();
    return worker;
  }
  void release(Worker* worker) {
    const std::lock_guard lock(mutex_);
    idle_.push_back(worker);
  }

 private:
  std::mutex mutex_;
  std::vector<Worker*> idle_;
};

// Never destroyed: workers outlive static destructors. A child made by fork() (multiprocessing)
// has none of the parent's threads, so it starts a pool of its own.
std::atomic<WorkerPool*> g_pool{nullptr};

WorkerPool& pool() {
  static const bool registered = [] {
    g_pool.store(new WorkerPool);
    pthread_atfork(nullptr, nullptr, [] { g_pool.store(new WorkerPool); });
    return true;
  }();
  static_cast<void>(registered);
  return *g_pool.load();
}

}  // namespace

ProgressFn fraction_reporter(const ReportFn& report) {
  return [report](double fraction) {
    ProgressReport r;
    r.fraction = fraction;
    report(r);
  };
}

void run_job(const std::function<void(const ReportFn&, const CancelToken&)>& work,
             const py::object& progress) {
  auto state = std::make_shared<JobState>();
  const CancelToken cancel;
  const bool has_callback = !progress.is_none();
  // Without a callback reports are dropped: the calling thread then wakes only to check signals.
  const ReportFn report = [state, has_callback](const ProgressReport& r) {
    if (!has_callback) return;
    {
      const std::lock_guard lock(state->mutex);
      state->report = r;
      state->has_report = true;
    }
    state->wake.notify_all();
  };
  Worker* worker = pool().acquire();
  worker->post([state, &work, report, cancel] {
    try {
      work(report, cancel);
    } catch (...) {
      state->error = std::current_exception();
    }
    {
      const std::lock_guard lock(state->mutex);
      state->done = true;
    }
    state->wake.notify_all();
  });

  std::optional<py::error_already_set> pending;  // the Python exception to raise once done
  for (;;) {
    ProgressReport latest;
    bool have_report = false;
    bool done = false;
    {
      py::gil_scoped_release release;
      std::unique_lock lock(state->mutex);
      state->wake.wait_for(lock, kSignalPoll, [&] { return state->done || state->has_report; });
      done = state->done;
      if (state->has_report) {
        latest = state->report;
        have_report = true;
        state->has_report = false;
      }
    }
    if (pending) {
      if (done) break;
      continue;  // cancelling: wait for the job to return
    }
    if (!done && PyErr_CheckSignals() != 0) {
      pending.emplace();  // fetches KeyboardInterrupt (or what a handler raised)
      cancel.cancel();
      continue;
    }
    // The last report of a finished job is delivered too (its answer no longer matters).
    if (have_report && has_callback) {
      try {
        py::dict info = to_python(latest.extra);
        info["fraction"] = latest.fraction;
        if (!latest.named_key.empty()) {
          py::dict named;
          for (const auto& [name, value] : latest.named) named[py::str(name)] = value;
          info[py::str(latest.named_key)] = named;
        }
        const py::object answer = progress(info);
        if (py::isinstance<py::bool_>(answer) && !answer.cast<bool>()) cancel.cancel();
      } catch (py::error_already_set& e) {
        pending.emplace(std::move(e));
        cancel.cancel();
      }
    }
    if (done) break;
  }
  pool().release(worker);  // done: the worker only returns to its loop now
  if (pending) throw std::move(*pending);
  if (state->error) std::rethrow_exception(state->error);
}

}  // namespace oscilab::python
