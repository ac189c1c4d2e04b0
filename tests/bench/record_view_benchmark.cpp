// The record view's frame time on a long record, offscreen at 1280x800: a replot of the whole
// record (drawn from the overview), a pan across it with an hour in view (overview buckets, read
// again as the window leaves what was read), a pan with 10 s in view (the samples, read from the
// file by seeking as the window leaves the 512 s read), and a zoom between the whole record and
// 10 s, which reads again at every step. A frame at 60 fps has 16.7 ms. The record is a 2 h
// two-channel W64 the benchmark writes (the samples in the file, as File > Open holds them), or
// the file OSCILAB_RECORD_VIEW_BENCH_FILE names (scripts/app_memory_study.sh's day-long one).
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>

#include <QApplication>

#include <benchmark/benchmark.h>
#include <qcustomplot.h>

#include "daq/recording/opened_recording.h"
#include "ui/review/record_view.h"

namespace {

using namespace oscilab;

double open_s = 0.0;  // how long opening the record took (File > Open, on the UI thread)

std::shared_ptr<const daq::OpenedRecording> bench_record() {
  static std::shared_ptr<const daq::OpenedRecording> opened;
  if (opened) return opened;
  std::string path;
  if (const char* given = std::getenv("OSCILAB_RECORD_VIEW_BENCH_FILE")) {
    path = given;
  } else {
    path = (std::filesystem::temp_directory_path() / "oscilab_record_view_bench.w64").string();
    daq::Recording made;
    made.sidecar.sample_rate_hz = 512.0;
    made.sidecar.channels.resize(2);
    made.sidecar.channels[0].name = "base_acc";
    made.sidecar.channels[0].role = daq::ChannelRole::Base;
    made.sidecar.channels[0].quantity = daq::Quantity::Acceleration;
    made.sidecar.channels[0].unit = "m/s^2";
    made.sidecar.channels[1].name = "y";
    made.sidecar.channels[1].role = daq::ChannelRole::Mass;
    made.sidecar.channels[1].quantity = daq::Quantity::Displacement;
    made.sidecar.channels[1].unit = "m";
    const Eigen::Index n = 2 * 3600 * 512;
    made.samples_si.resize(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = double(i) / 512.0, ramp = 1.0 + 2.0 * double(i) / double(n);
      made.samples_si(i, 0) = ramp * std::sin(2 * std::numbers::pi * 9.0 * t);
      made.samples_si(i, 1) = 1e-3 * ramp * std::sin(2 * std::numbers::pi * 9.0 * t + 0.5);
    }
    daq::write_recording(made, path);
  }
  const auto start = std::chrono::steady_clock::now();
  opened = std::make_shared<const daq::OpenedRecording>(daq::open_recording_for_review(path));
  open_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return opened;
}

// Arg 0: the whole record; 1: a pan with an hour in view; 2: a pan with 10 s in view; 3: a zoom
// between the whole record and 10 s.
void BM_RecordViewFrame(benchmark::State& state) {
  const auto record = bench_record();
  ui::RecordView view;
  view.resize(1280, 800);
  view.show();
  QApplication::processEvents();
  view.set_recording(record);
  const double duration_s = record->duration_s();
  const double width_s = state.range(0) == 1 ? 3600.0 : 10.0;
  double start_s = 0.0;
  long frames = 0;
  for (auto _ : state) {
    switch (state.range(0)) {
      case 0:
        break;
      case 1:
      case 2:
        start_s += width_s / 20.0;
        if (start_s + width_s > duration_s) start_s = 0.0;
        view.set_time_window(start_s, start_s + width_s);
        break;
      default:
        if (frames % 2 == 0) {
          view.fit();
        } else {
          start_s = std::fmod(start_s + 997.0, duration_s - 10.0);
          view.set_time_window(start_s, start_s + 10.0);
        }
    }
    view.plot()->replot(QCustomPlot::rpImmediateRefresh);
    ++frames;
  }
  state.counters["samples_per_point"] = double(view.samples_per_point());
  state.counters["record_h"] = duration_s / 3600.0;
  state.counters["open_s"] = open_s;
  static const char* const kLabels[] = {"whole record", "pan, 1 h in view", "pan, 10 s in view",
                                        "zoom whole <-> 10 s"};
  state.SetLabel(kLabels[state.range(0)]);
}
BENCHMARK(BM_RecordViewFrame)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
