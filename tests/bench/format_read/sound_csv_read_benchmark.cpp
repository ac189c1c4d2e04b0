// The reference for the other formats' read benchmarks: 10 minutes of 2 channels at 512 Hz
// (307 200 samples each) read from Oscilab's own containers, written by write_recording: 64-bit
// float WAV, 24-bit FLAC and CSV at full precision. Each iteration is read_recording with the
// sidecar beside the file. main() comes from benchmark_main.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numbers>
#include <string>

#include <unistd.h>

#include <benchmark/benchmark.h>

#include "daq/recording/recording.h"

namespace {

using namespace oscilab::daq;
namespace fs = std::filesystem;

constexpr double kRateHz = 512.0;
constexpr Eigen::Index kSamples = 307200;  // 10 min at 512 Hz

// A table acceleration and a mass position, quantised as a 24-bit container stores them (scales
// 3e-5 m/s² and 1e-7 m per count, the virtual rig's), so that every container holds the values.
Recording two_sines() {
  Recording recording;
  recording.sidecar.sample_rate_hz = kRateHz;
  ChannelInfo table;
  table.name = "table";
  table.role = ChannelRole::Base;
  table.quantity = Quantity::Acceleration;
  table.unit = "m/s^2";
  table.scale = 3e-5;
  ChannelInfo mass = table;
  mass.name = "mass";
  mass.role = ChannelRole::Mass;
  mass.quantity = Quantity::Displacement;
  mass.unit = "m";
  mass.scale = 1e-7;
  recording.sidecar.channels = {table, mass};
  recording.samples_si.resize(kSamples, 2);
  for (Eigen::Index r = 0; r < kSamples; ++r) {
    const double t_s = static_cast<double>(r) / kRateHz;
    recording.samples_si(r, 0) = 3e-5 * std::round(std::sin(2 * std::numbers::pi * 9 * t_s) / 3e-5);
    recording.samples_si(r, 1) =
        1e-7 * std::round(1e-3 * std::sin(2 * std::numbers::pi * 9 * t_s + 0.4) / 1e-7);
  }
  return recording;
}

// The recording written once per container, in a directory removed at exit.
const std::string& file_for(const std::string& extension) {
  static const fs::path dir = [] {
    fs::path path =
        fs::temp_directory_path() / ("oscilab_read_benchmark_" + std::to_string(::getpid()));
    fs::create_directories(path);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(
          fs::temp_directory_path() / ("oscilab_read_benchmark_" + std::to_string(::getpid())),
          ignored);
    });
    return path;
  }();
  static std::map<std::string, std::string> paths;
  auto it = paths.find(extension);
  if (it == paths.end()) {
    const std::string path = (dir / ("ten_minutes" + extension)).string();
    write_recording(two_sines(), path);
    it = paths.emplace(extension, path).first;
  }
  return it->second;
}

void read_container(benchmark::State& state, const std::string& extension) {
  const std::string& path = file_for(extension);
  for (auto _ : state) {
    const Recording recording = read_recording(path);
    benchmark::DoNotOptimize(recording.samples_si.data());
  }
  state.counters["MB"] = static_cast<double>(fs::file_size(path)) / 1e6;
}

void BM_ReadWavFloat64(benchmark::State& state) { read_container(state, ".wav"); }
void BM_ReadFlac24(benchmark::State& state) { read_container(state, ".flac"); }
void BM_ReadCsv(benchmark::State& state) { read_container(state, ".csv"); }

BENCHMARK(BM_ReadWavFloat64)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadFlac24)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadCsv)->Unit(benchmark::kMillisecond);

}  // namespace
