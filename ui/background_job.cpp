#include "ui/background_job.h"

#include <QMetaObject>
#include <QPointer>

namespace oscilab::ui {

BackgroundJob::BackgroundJob(QObject* parent) : QObject(parent) {}

BackgroundJob::~BackgroundJob() {
  cancel_.cancel();
  join();
}

void BackgroundJob::join() {
  if (thread_.joinable()) thread_.join();
}

bool BackgroundJob::start(Work work) {
  if (running_) return false;
  join();  // a finished job's thread
  cancel_ = CancelToken{};
  running_ = true;
  last_permille_->store(-1);
  const CancelToken cancel = cancel_;
  QPointer<BackgroundJob> self(this);
  auto last = last_permille_;
  thread_ = std::thread([self, work = std::move(work), cancel, last] {
    const ProgressFn report = [self, last](double fraction) {
      const int permille = static_cast<int>(fraction * 1000.0);
      if (permille < last->load() + 5 && permille != 1000) return;
      last->store(permille);
      QMetaObject::invokeMethod(
          self.data(),
          [self, fraction] {
            if (self) Q_EMIT self->progress(fraction);
          },
          Qt::QueuedConnection);
    };
    work(report, cancel);
    QMetaObject::invokeMethod(
        self.data(),
        [self, cancel] {
          if (!self) return;
          self->running_ = false;
          Q_EMIT self->finished(cancel.cancelled());
        },
        Qt::QueuedConnection);
  });
  return true;
}

void BackgroundJob::cancel() { cancel_.cancel(); }

}  // namespace oscilab::ui
