// The fit panel's responsiveness on the bundled samples, offscreen: how long a click on Cancel
// takes to come back as job_finished (during the analysis of the recordings and during the
// CMA-ES search), and the largest gap between ticks of a 5 ms timer while a real fit runs (above
// ~50 ms a user sees the window stutter: three frames at 60 Hz). Counters of one run each; the
// tests check the behaviour (a cancelled fit says so), these figures are what it costs.
#include <algorithm>
#include <vector>

#include <QApplication>
#include <QElapsedTimer>
#include <QPushButton>
#include <QSignalSpy>
#include <QTest>
#include <QTimer>

#include <benchmark/benchmark.h>
#include <qcustomplot.h>

#include "ui/identification/identification_panel.h"

namespace {

using oscilab::ui::IdentificationPanel;

const std::string kSamples = std::string(OSCILAB_SOURCE_DIR) + "/samples/";

void set_samples(IdentificationPanel& panel) {
  panel.set_recordings({kSamples + "stepped_positive.flac", kSamples + "stepped_negative.flac"});
}

// Arg 0: cancel as soon as the fit starts (the recordings are being analysed); arg 1: cancel once
// the search has drawn its first point.
void BM_FitPanelCancelLatency(benchmark::State& state) {
  const bool in_search = state.range(0) == 1;
  for (auto _ : state) {
    IdentificationPanel panel;
    set_samples(panel);
    panel.set_fit_settings("cmaes", 100000, 100, 20);
    QElapsedTimer clock;
    double latency_ms = -1.0;
    QObject::connect(&panel, &IdentificationPanel::job_finished, &panel,
                     [&] { latency_ms = 1e-6 * static_cast<double>(clock.nsecsElapsed()); });
    panel.start_fit();
    if (in_search &&
        !QTest::qWaitFor([&] { return !panel.convergence_plot()->graph(0)->data()->isEmpty(); },
                         60000)) {
      state.SkipWithError("the search drew no point in 60 s");
      return;
    }
    clock.start();
    QTest::mouseClick(panel.cancel_button(), Qt::LeftButton);
    if (!QTest::qWaitFor([&] { return latency_ms >= 0.0; }, 20000)) {
      state.SkipWithError("the cancelled fit did not finish in 20 s");
      return;
    }
    state.SetIterationTime(1e-3 * latency_ms);
    state.counters["cancel_latency_ms"] = latency_ms;
  }
  state.SetLabel(in_search ? "during the search" : "during the analysis of the recordings");
}
BENCHMARK(BM_FitPanelCancelLatency)
    ->Arg(0)
    ->Arg(1)
    ->Iterations(1)
    ->Repetitions(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_FitPanelEventLoopGapDuringAFit(benchmark::State& state) {
  for (auto _ : state) {
    IdentificationPanel panel;
    panel.resize(560, 900);
    panel.show();
    if (!QTest::qWaitForWindowExposed(&panel)) {
      state.SkipWithError("the window was not exposed");
      return;
    }
    set_samples(panel);
    panel.set_fit_settings("cmaes", 1000, 100, 20);  // a real fit: search, polish, uncertainty
    std::vector<qint64> gaps;
    QElapsedTimer clock;
    QTimer ticker;
    ticker.setTimerType(Qt::PreciseTimer);
    ticker.setInterval(5);
    QObject::connect(&ticker, &QTimer::timeout, &panel, [&] { gaps.push_back(clock.restart()); });
    QSignalSpy done(&panel, &IdentificationPanel::job_finished);
    clock.start();
    ticker.start();
    QElapsedTimer fit_clock;
    fit_clock.start();
    panel.start_fit();
    const bool finished = done.wait(120000);
    ticker.stop();
    if (!finished) {
      state.SkipWithError("the fit did not finish in 120 s");
      return;
    }
    state.SetIterationTime(1e-3 * static_cast<double>(fit_clock.elapsed()));
    std::sort(gaps.begin(), gaps.end());
    state.counters["ticks"] = static_cast<double>(gaps.size());
    state.counters["gap_median_ms"] =
        gaps.empty() ? -1.0 : static_cast<double>(gaps[gaps.size() / 2]);
    state.counters["gap_max_ms"] = gaps.empty() ? -1.0 : static_cast<double>(gaps.back());
  }
}
BENCHMARK(BM_FitPanelEventLoopGapDuringAFit)
    ->Iterations(1)
    ->Repetitions(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

}  // namespace

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
