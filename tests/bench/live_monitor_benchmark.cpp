// Frame rate of the live monitor (target: ≥ 30 frames per second on a 2-core machine): the real
// widget replaying the bundled stepped sine at 1× with 10 minutes of history on screen. The
// history is filled first by replaying 600 s of stream as fast as possible (the file loops), then
// the replay runs at 1× and the frames the trace plot draws in 1.5 s of the application's event
// loop are counted (QCustomPlot replots; the monitor's frame timer asks for at most 62.5 a
// second). Arg: the window of the traces in s (600: all the history kept; 10: the default).
// Runs offscreen unless QT_QPA_PLATFORM says otherwise; the figures are counters of one run.
#include <algorithm>
#include <vector>

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QTimer>

#include <benchmark/benchmark.h>
#include <qcustomplot.h>

#include "daq/sources/replay_source.h"
#include "ui/live/live_monitor.h"
#include "ui/live/live_trace_view.h"

namespace {

using oscilab::ui::LiveMonitor;

const std::string kSample = std::string(OSCILAB_SOURCE_DIR) + "/samples/stepped_positive.flac";
constexpr double kHistoryS = 600.0;  // the acquisition keeps 10 minutes
constexpr int kMeasureMs = 1500;

// Runs the event loop until `done` holds or `timeout_ms` passed.
template <typename Predicate>
void run_event_loop_until(Predicate done, int timeout_ms) {
  QEventLoop loop;
  QTimer check;
  check.setInterval(20);
  QObject::connect(&check, &QTimer::timeout, &loop, [&] {
    if (done()) loop.quit();
  });
  QTimer::singleShot(timeout_ms, &loop, &QEventLoop::quit);
  check.start();
  loop.exec();
}

void run_event_loop_for(int ms) {
  QEventLoop loop;
  QTimer::singleShot(ms, &loop, &QEventLoop::quit);
  loop.exec();
}

void BM_LiveMonitorFramesPerSecondAt1x(benchmark::State& state) {
  const double window_s = static_cast<double>(state.range(0));
  LiveMonitor monitor;
  monitor.resize(1600, 950);
  monitor.show();
  oscilab::ui::LiveSettings settings;
  settings.source = oscilab::ui::LiveSourceKind::Replay;
  settings.replay_path = kSample;
  settings.replay_loop = true;
  settings.speed = 0.0;  // fill the history as fast as the acquisition goes
  settings.window_s = window_s;
  monitor.set_settings(settings);
  if (!monitor.start()) {
    state.SkipWithError(monitor.message().toStdString().c_str());
    return;
  }
  run_event_loop_until([&] { return monitor.acquisition()->status().stream_time_s >= kHistoryS; },
                       120000);
  monitor.replay()->set_speed(1.0);
  run_event_loop_for(500);  // the queue drained, the 1× pace settled

  long frames = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const long first = monitor.frames_drawn();
    QElapsedTimer clock;
    clock.start();
    run_event_loop_for(kMeasureMs);
    const double elapsed_s = 1e-9 * static_cast<double>(clock.nsecsElapsed());
    state.SetIterationTime(elapsed_s);
    frames += monitor.frames_drawn() - first;
    seconds += elapsed_s;
  }
  const oscilab::ui::TimeWindow shown = monitor.view_window();
  state.counters["frames_per_s"] = static_cast<double>(frames) / seconds;
  state.counters["target_frames_per_s"] = 30.0;
  state.counters["window_s"] = shown.end_s - shown.start_s;
  state.counters["stream_time_s"] = monitor.acquisition()->status().stream_time_s;
  state.counters["trace_replot_ms"] = monitor.trace_view()->plot()->replotTime(true);
  monitor.stop();
}
BENCHMARK(BM_LiveMonitorFramesPerSecondAt1x)
    ->Arg(600)
    ->Arg(10)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

// The gaps between ticks of a 5 ms timer in the UI thread while the monitor draws a 100× replay
// of the sample (51 200 samples/s): what a user's click waits for. Above ~50 ms a user sees the
// window stutter (three frames at 60 Hz). One run: the whole replay.
void BM_LiveMonitorEventLoopGapDuringA100xReplay(benchmark::State& state) {
  for (auto _ : state) {
    LiveMonitor monitor;
    monitor.resize(1600, 950);
    monitor.show();
    oscilab::ui::LiveSettings settings;
    settings.source = oscilab::ui::LiveSourceKind::Replay;
    settings.replay_path = kSample;
    settings.speed = 100.0;
    monitor.set_settings(settings);
    std::vector<double> gaps_ms;
    QElapsedTimer clock;
    QTimer probe;
    probe.setTimerType(Qt::PreciseTimer);
    probe.setInterval(5);
    qint64 last = -1;
    QObject::connect(&probe, &QTimer::timeout, [&] {
      const qint64 now = clock.nsecsElapsed();
      if (last >= 0) gaps_ms.push_back(1e-6 * static_cast<double>(now - last));
      last = now;
    });
    if (!monitor.start()) {
      state.SkipWithError(monitor.message().toStdString().c_str());
      return;
    }
    clock.start();
    probe.start();
    run_event_loop_until([&] { return monitor.acquisition()->finished(); }, 60000);
    probe.stop();
    state.SetIterationTime(1e-9 * static_cast<double>(clock.nsecsElapsed()));
    std::sort(gaps_ms.begin(), gaps_ms.end());
    state.counters["ticks"] = static_cast<double>(gaps_ms.size());
    state.counters["gap_median_ms"] = gaps_ms.empty() ? -1.0 : gaps_ms[gaps_ms.size() / 2];
    state.counters["gap_max_ms"] = gaps_ms.empty() ? -1.0 : gaps_ms.back();
    state.counters["frames"] = static_cast<double>(monitor.frames_drawn());
  }
}
BENCHMARK(BM_LiveMonitorEventLoopGapDuringA100xReplay)
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
