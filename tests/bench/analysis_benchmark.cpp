// Speed of the measurement analysis (target: offline analysis of the 262.5 s stepped-sine record
// at ≥ 5000× real time on one core, i.e. ≤ 52 ms; the live pipeline at 512 Hz under 1 % of one
// core). Records come from the virtual rig once, outside the timed loops.
#include <cstdio>
#include <ctime>
#include <mutex>
#include <optional>

#include <benchmark/benchmark.h>

#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"
#include "analysis/signal/fftw_planner.h"
#include "analysis/signal/real_fft.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace {

using namespace oscilab;
using namespace oscilab::analysis;

const MeasurementChannels& default_record() {
  static const MeasurementChannels channels = [] {
    SteppedSineSchedule schedule;
    for (int i = 0; i < 26; ++i) schedule.levels_n.push_back(0.2 + 0.1 * i);
    daq::RigSpec spec;
    spec.seed = 1;
    return daq::measurement_channels(
        daq::record_stepped_sine(paper_model(), schedule, spec).recording);
  }();
  return channels;
}

double record_seconds() {
  return static_cast<double>(default_record().base.size()) / default_record().sample_rate_hz;
}

// The EDC path alone: per-cycle fits, levels, steady-state test (what `analyze --edc` needs).
void BM_OfflineEdc(benchmark::State& state) {
  const MeasurementChannels& channels = default_record();
  const StreamSetup setup = stream_setup(channels);
  SampleBlock block;
  block.samples.resize(channels.base.size(), 2);
  block.samples.col(0) = channels.base;
  block.samples.col(1) = channels.mass;
  std::size_t levels = 0;
  for (auto _ : state) {
    MeasurementPipeline pipeline(PipelineSettings{}, setup);
    pipeline.push(block);
    pipeline.finish();
    levels = pipeline.levels().size();
  }
  state.counters["x_realtime"] = benchmark::Counter(
      record_seconds() * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(std::to_string(levels) + " levels");
}
BENCHMARK(BM_OfflineEdc)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole offline analysis of one record: EDC plus z, ż, z̈, f, R by spectral calculus.
void BM_OfflineAnalyzeRecord(benchmark::State& state) {
  const MeasurementChannels& channels = default_record();
  for (auto _ : state) {
    const RecordAnalysis analysis = analyze_record(channels, PipelineSettings{});
    benchmark::DoNotOptimize(analysis.levels.data());
  }
  state.counters["x_realtime"] = benchmark::Counter(
      record_seconds() * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_OfflineAnalyzeRecord)->Unit(benchmark::kMillisecond)->UseRealTime();

// The restoring-force slices of a campaign (the stiffness slice and its fit, a damping slice
// per stable zero) over two records' motion signals: the serial step after the records'
// analyses.
void BM_OfflineSlices(benchmark::State& state) {
  const RecordAnalysis record = analyze_record(default_record(), PipelineSettings{});
  const std::vector<const MotionSignals*> signals = {&record.motion, &record.motion};
  const PipelineSettings settings;
  for (auto _ : state) {
    const StiffnessSlice stiffness = stiffness_slice(signals, settings);
    const DampingSlice damping =
        damping_slice(signals, stiffness, 0.5 * (stiffness.z_min_m + stiffness.z_max_m), settings);
    benchmark::DoNotOptimize(damping.bins.data());
  }
}
BENCHMARK(BM_OfflineSlices)->Unit(benchmark::kMillisecond)->UseRealTime();

// Live: the same record pushed in 64-sample blocks (8 blocks a second at 512 Hz). The counter
// `core_pct_at_512hz` is the share of one core the pipeline needs to keep up in real time.
void BM_LivePipeline(benchmark::State& state) {
  const MeasurementChannels& channels = default_record();
  const StreamSetup setup = stream_setup(channels);
  constexpr Eigen::Index kBlock = 64;
  std::vector<SampleBlock> blocks;
  for (Eigen::Index i = 0; i < channels.base.size(); i += kBlock) {
    SampleBlock block;
    const Eigen::Index count = std::min(kBlock, channels.base.size() - i);
    block.t0_s = static_cast<double>(i) / channels.sample_rate_hz;
    block.samples.resize(count, 2);
    block.samples.col(0) = channels.base.segment(i, count);
    block.samples.col(1) = channels.mass.segment(i, count);
    blocks.push_back(std::move(block));
  }
  double busy_s = 0.0;  // CPU time of this thread: the share of a core, whatever the load
  for (auto _ : state) {
    const std::clock_t start = std::clock();
    MeasurementPipeline pipeline(PipelineSettings{}, setup);
    for (const SampleBlock& block : blocks) pipeline.push(block);
    pipeline.finish();
    benchmark::DoNotOptimize(pipeline.levels().data());
    busy_s += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  }
  // Google Benchmark prints counters with SI prefixes (0.01 → "10m"): the share of one core
  // goes in the label as a plain percentage instead.
  char label[64];
  std::snprintf(label, sizeof label, "%.4f %% of one core at 512 Hz",
                100.0 * busy_s / (static_cast<double>(state.iterations()) * record_seconds()));
  state.SetLabel(label);
}
BENCHMARK(BM_LivePipeline)->Unit(benchmark::kMillisecond)->UseRealTime();

// What a fresh process pays at the first real transform of a record's length: plans made, then
// one forward and one inverse transform. RealFft (a complex plan of half the length and a
// twiddle table) against FFTW's own r2c and c2r plans (FFTW_ESTIMATE), in the same process, at
// the length of the offline analysis's even extension of a 262.5 s record at 512 Hz. FFTW keeps
// what its planner learnt for the rest of a process (a later plan of the same problem is found
// at once), so each iteration forgets it.
constexpr int kRecordTransformLength = 268800;

void BM_RealFftFirstUse(benchmark::State& state) {
  FftwVector<double> x(kRecordTransformLength, 1.0), back(kRecordTransformLength);
  FftwVector<std::complex<double>> spectrum(kRecordTransformLength / 2 + 1);
  for (auto _ : state) {
    std::optional<RealFft> fft;
    {
      const std::lock_guard lock(fftw_planner_mutex());
      fftw_forget_wisdom();  // as in a fresh process
      fft.emplace(kRecordTransformLength);
    }
    fft->forward(x.data(), spectrum.data());
    fft->inverse(spectrum.data(), back.data());
    const std::lock_guard lock(fftw_planner_mutex());
    fft.reset();
  }
}
BENCHMARK(BM_RealFftFirstUse)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FftwRealPlansFirstUse(benchmark::State& state) {
  FftwVector<double> x(kRecordTransformLength, 1.0), back(kRecordTransformLength);
  FftwVector<std::complex<double>> spectrum(kRecordTransformLength / 2 + 1);
  auto* bins = reinterpret_cast<fftw_complex*>(spectrum.data());
  for (auto _ : state) {
    fftw_plan r2c = nullptr, c2r = nullptr;
    {
      const std::lock_guard lock(fftw_planner_mutex());
      fftw_forget_wisdom();  // as in a fresh process
      r2c = fftw_plan_dft_r2c_1d(kRecordTransformLength, x.data(), bins, FFTW_ESTIMATE);
      c2r = fftw_plan_dft_c2r_1d(kRecordTransformLength, bins, back.data(), FFTW_ESTIMATE);
    }
    fftw_execute(r2c);
    fftw_execute(c2r);
    const std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(r2c);
    fftw_destroy_plan(c2r);
  }
}
BENCHMARK(BM_FftwRealPlansFirstUse)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
