#include "ui/review/recording_opener.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <optional>
#include <thread>

#include <QEventLoop>
#include <QMetaObject>
#include <QProgressDialog>

namespace oscilab::ui {

std::shared_ptr<daq::OpenedRecording> open_off_the_ui_thread(
    QWidget* parent, const QString& label,
    const std::function<daq::OpenedRecording(const daq::OpeningControl&)>& open) {
  static constexpr int kSteps = 1000;
  QProgressDialog dialog(label, QObject::tr("Cancel"), 0, kSteps, parent);
  dialog.setObjectName("opening_progress");
  dialog.setWindowTitle(QObject::tr("Opening"));
  dialog.setWindowModality(Qt::WindowModal);
  dialog.setMinimumDuration(kProgressDelayMs);
  dialog.setAutoClose(false);
  dialog.setAutoReset(false);
  dialog.setValue(0);

  daq::OpeningControl control;
  const CancelToken cancel = control.cancel;
  QObject::connect(&dialog, &QProgressDialog::canceled, &dialog, [cancel, &dialog] {
    cancel.cancel();
    dialog.setLabelText(QObject::tr("Cancelling\u2026"));
  });
  // Progress reaches the dialog by queued calls, at most one per 0.5 % (the worker may report
  // per window of samples). The worker ends before the dialog is destroyed, so every call it
  // queues finds the dialog.
  auto last_step = std::make_shared<std::atomic<int>>(0);
  control.progress = [&dialog, last_step](double fraction) {
    const int step = std::clamp(static_cast<int>(fraction * kSteps), 0, kSteps);
    if (step < last_step->load() + kSteps / 200 && step != kSteps) return;
    last_step->store(step);
    QMetaObject::invokeMethod(
        &dialog, [&dialog, step] { dialog.setValue(step); }, Qt::QueuedConnection);
  };

  QEventLoop loop;
  std::optional<daq::OpenedRecording> opened;
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      opened.emplace(open(control));
    } catch (...) {
      failure = std::current_exception();
    }
    QMetaObject::invokeMethod(&loop, &QEventLoop::quit, Qt::QueuedConnection);
  });
  loop.exec();
  worker.join();
  dialog.reset();
  if (failure) std::rethrow_exception(failure);
  return std::make_shared<daq::OpenedRecording>(std::move(*opened));
}

}  // namespace oscilab::ui
