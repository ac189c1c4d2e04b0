// Speed of the NI TDMS reader:
//   - 10 minutes of 2 channels at 512 Hz (307 200 float64 samples each), logged in 1 s segments,
//     read into a recording through a sidecar;
//   - describe() of a ~1 GB file (1000 segments of 1 MiB of raw data, 4 channels): it reads the
//     lead-ins and the metadata and seeks over the data, so it takes milliseconds, not the
//     second or more that reading 1 GB would.
// Both files are written byte by byte here (NI's "TDMS File Format Internal Structure") into
// the temporary directory and removed at exit.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include <benchmark/benchmark.h>

#include "daq/recording/formats/formats.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/tdms_test_bytes.h"

namespace {

using namespace oscilab::daq;
using namespace oscilab::daq::testing;
namespace fs = std::filesystem;

class TempFile {
 public:
  explicit TempFile(const std::string& name)
      : path_((fs::temp_directory_path() /
               ("oscilab_bench_" + name + "_" + std::to_string(::getpid()) + ".tdms"))
                  .string()) {}
  ~TempFile() {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Metadata naming `channels` float64 channels of group "rig" with `values` values per chunk
// (a new raw data index), or reusing the previous segment's index (`reuse`).
std::string metadata(int channels, std::uint64_t values, bool reuse) {
  TdmsBytes m;
  m.u32(static_cast<std::uint32_t>(channels));  // number of objects
  for (int c = 0; c < channels; ++c) {
    m.str("/'rig'/'ch" + std::to_string(c) + "'");  // channel path
    if (reuse) {
      m.u32(kIndexSameAsPrevious);  // raw data index as before
      m.u32(0);                     // no properties
    } else {
      m.u32(kIndexPlain).u32(kTdsF64).u32(1).u64(values);   // float64, dimension 1, values
      m.u32(2);                                             // 2 properties
      m.str("wf_increment").u32(kTdsF64).f64(1.0 / 512.0);  // s
      m.str("unit_string").u32(kTdsString).str("m/s^2");
    }
  }
  return m.bytes();
}

// 10 minutes at 512 Hz, 2 channels: 600 segments of 1 s.
const std::string& ten_minute_file() {
  static const TempFile file("tdms_10min");
  static const bool written = [] {
    std::ofstream out(file.path(), std::ios::binary | std::ios::trunc);
    for (int s = 0; s < 600; ++s) {
      TdmsBytes raw;
      for (int c = 0; c < 2; ++c) {
        for (int i = 0; i < 512; ++i) {
          const double t_s = s + i / 512.0;
          raw.f64(std::sin(2.0 * M_PI * (10.0 + c) * t_s));
        }
      }
      const bool first = s == 0;
      out << tdms_segment(first ? kTocMetaData | kTocNewObjList | kTocRawData : kTocRawData,
                          first ? metadata(2, 512, false) : "", raw.bytes());
    }
    return true;
  }();
  (void)written;
  return file.path();
}

void BM_TdmsRead10Minutes2Channels512Hz(benchmark::State& state) {
  const std::string& path = ten_minute_file();
  Sidecar sidecar;
  sidecar.sample_rate_hz = 512.0;
  for (int c = 0; c < 2; ++c) {
    ChannelInfo channel;
    channel.name = "ch" + std::to_string(c);
    channel.role = c == 0 ? ChannelRole::Base : ChannelRole::Mass;
    channel.quantity = Quantity::Acceleration;
    channel.unit = "m/s^2";
    channel.source = "rig/ch" + std::to_string(c);
    sidecar.channels.push_back(channel);
  }
  for (auto _ : state) {
    const Recording recording = read_recording(path, sidecar);
    if (recording.sample_count() != 307200) state.SkipWithError("wrong sample count");
    benchmark::DoNotOptimize(recording.samples_si.data());
  }
}
BENCHMARK(BM_TdmsRead10Minutes2Channels512Hz)->Unit(benchmark::kMillisecond)->UseRealTime();

// ~1 GB: 1000 segments, each 4 channels × 32768 float64 values (1 MiB) of raw data, with
// metadata in every segment (the first a new index, then "same as previous").
const std::string& one_gigabyte_file() {
  static const TempFile file("tdms_1gb");
  static const bool written = [] {
    std::ofstream out(file.path(), std::ios::binary | std::ios::trunc);
    TdmsBytes raw;
    for (int i = 0; i < 4 * 32768; ++i) raw.f64(i * 1e-3);
    for (int s = 0; s < 1000; ++s) {
      const bool first = s == 0;
      out << tdms_segment(kTocMetaData | kTocRawData | (first ? kTocNewObjList : 0),
                          metadata(4, 32768, !first), raw.bytes());
    }
    return true;
  }();
  (void)written;
  return file.path();
}

void BM_TdmsDescribe1GB(benchmark::State& state) {
  const std::string& path = one_gigabyte_file();
  state.counters["file_MB"] = static_cast<double>(fs::file_size(path)) / 1e6;
  for (auto _ : state) {
    const FileContents contents = tdms_format().describe(path);
    if (contents.file_signals.size() != 4 || contents.file_signals[0].sample_count != 32768000) {
      state.SkipWithError("unexpected contents");
    }
    benchmark::DoNotOptimize(contents.file_signals.data());
  }
}
BENCHMARK(BM_TdmsDescribe1GB)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
