// Speed of the live chain: source → queue → acquisition (fault checks, calibration,
// derived traces, per-cycle EDC) → recorder, measured end to end in one process.
//   - at 512 Hz, real time: CPU used by the whole process / wall time, target < 5 % of one core;
//     latency from the arrival of a cycle's first sample to its EDC, target < 1 cycle + 100 ms;
//   - replay at 100× (51.2 kHz of samples): no drop, no gap;
//   - as fast as possible: samples per second, the headroom.
// Each figure is a counter of one run; repetitions give the medians.
#include <chrono>
#include <ctime>
#include <filesystem>
#include <thread>

#include <unistd.h>

#include <benchmark/benchmark.h>

#include "analysis/model/reference_models.h"
#include "daq/live/acquisition.h"
#include "daq/sources/replay_source.h"
#include "daq/sources/rig_source.h"

namespace {

using namespace oscilab;
using namespace oscilab::daq;
namespace fs = std::filesystem;

double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string temp_recording(const char* name) {
  return (fs::temp_directory_path() /
          (std::string("oscilab_bench_") + name + "_" + std::to_string(::getpid()) + ".wav"))
      .string();
}

void remove_recording(const std::string& path) {
  for (const char* suffix : {".wav", ".json", ".events.jsonl"}) {
    fs::remove(fs::path(path).replace_extension("").string() + suffix);
  }
}

// Runs `acquisition` with a recording until its source ends; returns the wall time in s.
double run_recorded(Acquisition& acquisition, const std::string& path) {
  acquisition.start_recording(path);
  const auto start = std::chrono::steady_clock::now();
  acquisition.start();
  while (!acquisition.finished()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  acquisition.stop();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

RigSource::Options stepped(double speed, double duration_s) {
  RigSource::Options o;
  o.speed = speed;
  o.duration_s = duration_s;
  for (int i = 0; i * 4.0 + 0.5 < duration_s; ++i)
    o.schedule.push_back({0.5 + 4.0 * i, 0.5 + 0.3 * i, 9.0});
  return o;
}

// 512 Hz in real time: the rig integrates the model and reads its sensors (the source), the
// acquisition does everything else. 5 s of stream per run.
void BM_LiveChainRealTime512Hz(benchmark::State& state) {
  const std::string path = temp_recording("realtime");
  for (auto _ : state) {
    Acquisition acquisition(std::make_unique<RigSource>(analysis::paper_model(), stepped(1.0, 5.0)),
                            {});
    const double cpu0 = process_cpu_s();
    const double wall_s = run_recorded(acquisition, path);
    const double cpu_s = process_cpu_s() - cpu0;
    const AcquisitionStatus s = acquisition.status();
    state.SetIterationTime(wall_s);
    state.counters["cpu_pct_of_one_core"] = 100.0 * cpu_s / wall_s;
    state.counters["edc_latency_median_ms"] = 1e3 * s.edc_latency_median_s;
    state.counters["edc_latency_max_ms"] = 1e3 * s.edc_latency_max_s;
    state.counters["latency_target_ms"] = 1e3 / 9.0 + 100.0;
    state.counters["dropped"] = static_cast<double>(s.overflowed_blocks + s.gaps);
  }
  remove_recording(path);
}
BENCHMARK(BM_LiveChainRealTime512Hz)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

// The bundled 262.5 s stepped sine replayed at 100× (51.2 kHz of samples for 2.6 s).
void BM_LiveChainReplay100x(benchmark::State& state) {
  const std::string sample = std::string(OSCILAB_SOURCE_DIR) + "/samples/stepped_positive.flac";
  const std::string path = temp_recording("replay100");
  for (auto _ : state) {
    ReplaySource::Options options;
    options.speed = 100.0;
    options.block_rows = 64;
    Acquisition acquisition(std::make_unique<ReplaySource>(sample, options), {});
    const double cpu0 = process_cpu_s();
    const double wall_s = run_recorded(acquisition, path);
    const double cpu_s = process_cpu_s() - cpu0;
    const AcquisitionStatus s = acquisition.status();
    state.SetIterationTime(wall_s);
    state.counters["samples_per_s"] = static_cast<double>(s.samples) / wall_s;
    state.counters["cpu_pct_of_one_core"] = 100.0 * cpu_s / wall_s;
    state.counters["dropped_blocks"] = static_cast<double>(s.overflowed_blocks);
    state.counters["gap_samples"] = static_cast<double>(s.gap_samples);
    state.counters["levels"] = static_cast<double>(s.levels);
  }
  remove_recording(path);
}
BENCHMARK(BM_LiveChainReplay100x)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

// As fast as the acquisition takes it (the replay waits for room): the headroom.
void BM_LiveChainMaxThroughput(benchmark::State& state) {
  const std::string sample = std::string(OSCILAB_SOURCE_DIR) + "/samples/stepped_positive.flac";
  const std::string path = temp_recording("max");
  for (auto _ : state) {
    ReplaySource::Options options;
    options.speed = 0.0;
    options.block_rows = 256;
    Acquisition acquisition(std::make_unique<ReplaySource>(sample, options), {});
    const double wall_s = run_recorded(acquisition, path);
    const AcquisitionStatus s = acquisition.status();
    state.SetIterationTime(wall_s);
    state.counters["samples_per_s"] = static_cast<double>(s.samples) / wall_s;
    state.counters["x_realtime_512Hz"] = static_cast<double>(s.samples) / wall_s / 512.0;
  }
  remove_recording(path);
}
BENCHMARK(BM_LiveChainMaxThroughput)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
