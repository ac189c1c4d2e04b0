// Speed of the HDF5 reader: 10 minutes of 2 channels at 512 Hz (307 200 float64 samples each)
// written by h5py, as two datasets and as the two columns of one 307 200 x 2 dataset, read into
// a recording through a sidecar; and, for the cost of the child process (library_process.h),
// libhdf5 reading the same datasets in this process, and a child that sends 2 x 307 200 values
// without calling any library.
#include <cstring>

#include <benchmark/benchmark.h>
#include <hdf5.h>

#include "daq/recording/formats/library_process.h"
#include "daq/recording/recording.h"
#include "tests/bench/format_read/mat_hdf5_bench_util.h"

namespace {

using namespace oscilab::daq;
using namespace oscilab::daq::bench;

const ScriptFile& hdf5_file() {
  static const ScriptFile file(
      "run.h5",
      {{"format", "hdf5"},
       {"groups", {{{"path", "/rig"}, {"attrs", {{"sample_rate_hz", kRateHz}}}}}},
       {"variables",
        {sine_variable("/rig/a", {kSamples}, 2.0), sine_variable("/rig/z", {kSamples}, 3.0),
         sine_variable("/rig/both", {kSamples, 2}, 1.0)}}});
  return file;
}

void BM_Hdf5Read10Min(benchmark::State& state) {
  const Sidecar sidecar = state.range(0) == 0 ? two_channels({{"/rig/a", -1}, {"/rig/z", -1}})
                                              : two_channels({{"/rig/both", 0}, {"/rig/both", 1}});
  for (auto _ : state) {
    const Recording recording = read_recording(hdf5_file().path(), sidecar);
    benchmark::DoNotOptimize(recording.samples_si.data());
  }
  state.SetItemsProcessed(state.iterations() * 2 * static_cast<long>(kSamples));
}
BENCHMARK(BM_Hdf5Read10Min)->ArgName("matrix")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The baseline: libhdf5 in this process reading the two datasets (no fork, pipe, describe,
// calibration). Only a benchmark may do this: Oscilab itself never calls libhdf5 outside a child.
void BM_Hdf5InProcess10Min(benchmark::State& state) {
  std::vector<double> values(kSamples);
  for (auto _ : state) {
    const hid_t file = H5Fopen(hdf5_file().path().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    for (const char* name : {"/rig/a", "/rig/z"}) {
      const hid_t dataset = H5Dopen2(file, name, H5P_DEFAULT);
      H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
      H5Dclose(dataset);
      benchmark::DoNotOptimize(values.data());
    }
    H5Fclose(file);
  }
}
BENCHMARK(BM_Hdf5InProcess10Min)->Unit(benchmark::kMillisecond);

// The isolation alone: three children (a describe and two reads), two of which send 307 200
// doubles back, with no library call.
void BM_ChildProcessRoundTrips10Min(benchmark::State& state) {
  const std::string& path = hdf5_file().path();
  for (auto _ : state) {
    run_in_child(path, "none", child_limits_for(path, 4096), [] {
      return ChildReply{true, std::string(1000, 'x')};
    });
    for (int c = 0; c < 2; ++c) {
      const std::string bytes =
          run_in_child(path, "none", child_limits_for(path, kSamples * sizeof(double)), [] {
            return ChildReply{true, std::string(kSamples * sizeof(double), '\1')};
          });
      benchmark::DoNotOptimize(bytes.data());
    }
  }
}
BENCHMARK(BM_ChildProcessRoundTrips10Min)->Unit(benchmark::kMillisecond);

}  // namespace
