// Speed of the MAT-file reader: 10 minutes of 2 channels at 512 Hz (307 200 float64 samples
// each) written by SciPy, read into a recording through a sidecar, uncompressed and compressed;
// and, for the cost of the child process (library_process.h), matio reading the same two
// variables in this process.
#include <benchmark/benchmark.h>
#include <matio.h>

#include "daq/recording/recording.h"
#include "tests/bench/format_read/mat_hdf5_bench_util.h"

namespace {

using namespace oscilab::daq;
using namespace oscilab::daq::bench;

const ScriptFile& mat_file(bool compress) {
  static const ScriptFile plain(
      "run.mat",
      {{"format", "mat5"},
       {"compress", false},
       {"variables",
        {sine_variable("a", {1, kSamples}, 2.0), sine_variable("z", {kSamples, 1}, 3.0)}}});
  static const ScriptFile compressed(
      "runz.mat",
      {{"format", "mat5"},
       {"compress", true},
       {"variables",
        {sine_variable("a", {1, kSamples}, 2.0), sine_variable("z", {kSamples, 1}, 3.0)}}});
  return compress ? compressed : plain;
}

void BM_MatRead10Min(benchmark::State& state) {
  const std::string& path = mat_file(state.range(0) != 0).path();
  const Sidecar sidecar = two_channels({{"a", -1}, {"z", -1}});
  for (auto _ : state) {
    const Recording recording = read_recording(path, sidecar);
    benchmark::DoNotOptimize(recording.samples_si.data());
  }
  state.SetItemsProcessed(state.iterations() * 2 * static_cast<long>(kSamples));
}
BENCHMARK(BM_MatRead10Min)->ArgName("compressed")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The baseline: matio in this process, the two variables read whole (what the children do,
// without fork, pipe, describe or calibration).
void BM_MatioInProcess10Min(benchmark::State& state) {
  const std::string& path = mat_file(state.range(0) != 0).path();
  for (auto _ : state) {
    mat_t* mat = Mat_Open(path.c_str(), MAT_ACC_RDONLY);
    for (const char* name : {"a", "z"}) {
      matvar_t* variable = Mat_VarRead(mat, name);
      benchmark::DoNotOptimize(variable->data);
      Mat_VarFree(variable);
    }
    Mat_Close(mat);
  }
}
BENCHMARK(BM_MatioInProcess10Min)
    ->ArgName("compressed")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
