// The job template every job of the app is made of (ui/outcome_job.h): the outcome reaches the
// owner on the UI thread with the work's result, an InputError's text, "internal error: …" for
// any other exception, or `cancelled`; one job at a time; the owner's end cancels and joins.
#include "ui/outcome_job.h"

#include <atomic>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include <QObject>
#include <QThread>
#include <QtTest>

#include "analysis/common/input_error.h"

namespace oscilab::ui {

struct CountOutcome {
  bool cancelled = false;
  std::string error;
  int value = 0;
  bool on_worker_thread = false;
};

// An owner as the app's jobs are: a QObject with the typed signals, the template a member.
class CountJob : public QObject {
  Q_OBJECT

 public:
  bool start(OutcomeJob<CountOutcome>::Work work) {
    return work_.start(std::make_shared<CountOutcome>(), std::move(work));
  }
  void cancel() { work_.cancel(); }
  bool running() const { return work_.running(); }

 Q_SIGNALS:
  void progress(double fraction_done);
  void finished(std::shared_ptr<const oscilab::ui::CountOutcome> outcome);

 private:
  OutcomeJob<CountOutcome> work_{this, &CountJob::finished, &CountJob::progress};
};

}  // namespace oscilab::ui

using oscilab::CancelToken;
using oscilab::ProgressFn;
using oscilab::ui::CountJob;
using oscilab::ui::CountOutcome;

class OutcomeJobTest : public QObject {
  Q_OBJECT

 private:
  // Starts `work` on `job` and waits (event loop running) for its outcome.
  static std::shared_ptr<const CountOutcome> run(
      CountJob& job, const oscilab::ui::OutcomeJob<CountOutcome>::Work& work,
      QList<double>* progress = nullptr) {
    std::shared_ptr<const CountOutcome> outcome;
    const QMetaObject::Connection done = QObject::connect(
        &job, &CountJob::finished, [&](std::shared_ptr<const CountOutcome> o) { outcome = o; });
    const QMetaObject::Connection step = QObject::connect(&job, &CountJob::progress, [&](double f) {
      if (progress) progress->append(f);
    });
    if (!job.start(work)) return nullptr;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!outcome && std::chrono::steady_clock::now() < deadline) {
      QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    }
    QObject::disconnect(done);
    QObject::disconnect(step);
    return outcome;
  }

 private Q_SLOTS:
  void handsTheWorksResultAndProgressToTheUiThread() {
    CountJob job;
    QList<double> progress;
    const auto ui_thread = std::this_thread::get_id();
    const auto outcome = run(
        job,
        [ui_thread](CountOutcome& o, const ProgressFn& report, const CancelToken&) {
          o.value = 42;
          o.on_worker_thread = std::this_thread::get_id() != ui_thread;
          report(0.5);
          report(1.0);
        },
        &progress);
    QVERIFY(outcome);
    QCOMPARE(outcome->value, 42);
    QVERIFY(outcome->on_worker_thread);
    QVERIFY(!outcome->cancelled);
    QVERIFY(outcome->error.empty());
    QVERIFY(!job.running());
    // Progress arrives queued, in order; the last report (1.0) is never coalesced away.
    QVERIFY(!progress.isEmpty());
    QCOMPARE(progress.last(), 1.0);
  }

  void anInputErrorBecomesTheOutcomesErrorText() {
    CountJob job;
    const auto outcome = run(job, [](CountOutcome& o, const ProgressFn&, const CancelToken&) {
      o.value = 1;
      throw oscilab::InputError("run7.flac: field \"rate_hz\": -512 is not positive");
    });
    QVERIFY(outcome);
    QCOMPARE(outcome->error, std::string("run7.flac: field \"rate_hz\": -512 is not positive"));
    QCOMPARE(outcome->value, 1);  // what the work wrote before it threw stays
    QVERIFY(!outcome->cancelled);
  }

  void anyOtherExceptionIsAnInternalError() {
    CountJob job;
    const auto outcome = run(job, [](CountOutcome&, const ProgressFn&, const CancelToken&) {
      throw std::runtime_error("vector::reserve");
    });
    QVERIFY(outcome);
    QCOMPARE(outcome->error, std::string("internal error: vector::reserve"));
  }

  void oneJobAtATimeAndCancelReachesTheWork() {
    CountJob job;
    std::atomic<bool> started{false};
    std::shared_ptr<const CountOutcome> outcome;
    QObject::connect(&job, &CountJob::finished,
                     [&](std::shared_ptr<const CountOutcome> o) { outcome = o; });
    QVERIFY(job.start([&](CountOutcome& o, const ProgressFn&, const CancelToken& cancel) {
      started = true;
      while (!cancel.cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      o.value = 7;
    }));
    QVERIFY(job.running());
    QTRY_VERIFY(started.load());
    // A second start while the first runs is refused and changes nothing.
    QVERIFY(
        !job.start([](CountOutcome& o, const ProgressFn&, const CancelToken&) { o.value = 9; }));
    job.cancel();
    QTRY_VERIFY(outcome != nullptr);
    QVERIFY(outcome->cancelled);
    QCOMPARE(outcome->value, 7);
    QVERIFY(!job.running());
    // The next job gets a fresh outcome and a fresh token.
    const auto next = run(job, [](CountOutcome& o, const ProgressFn&, const CancelToken& cancel) {
      o.value = cancel.cancelled() ? -1 : 8;
    });
    QVERIFY(next);
    QCOMPARE(next->value, 8);
    QVERIFY(!next->cancelled);
  }

  void theOwnersEndCancelsAndJoinsTheWorker() {
    std::atomic<bool> started{false}, ended{false};
    {
      CountJob job;
      QVERIFY(job.start([&](CountOutcome&, const ProgressFn&, const CancelToken& cancel) {
        started = true;
        while (!cancel.cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        ended = true;
      }));
      QTRY_VERIFY(started.load());
    }  // the destructor: cancel, join
    QVERIFY(ended.load());
    // No outcome is delivered to the destroyed owner (the queued end is dropped).
    QCoreApplication::processEvents();
  }
};

QTEST_GUILESS_MAIN(OutcomeJobTest)
#include "outcome_job_test.moc"
