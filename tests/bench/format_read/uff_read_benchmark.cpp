// Reading 10 minutes of 2 channels at 512 Hz (307 200 samples each) from universal files: ASCII
// dataset 58 as Oscilab's UFF 58 export writes it (4E20.12), and binary 58b with float32 and
// float64 values. Each iteration is read_recording with an in-memory sidecar. main() comes from
// benchmark_main (the executable gathers one source per format).
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>

#include <benchmark/benchmark.h>

#include "daq/export/uff58_export.h"
#include "daq/recording/recording.h"

namespace {

using namespace oscilab::daq;
namespace fs = std::filesystem;

constexpr double kRateHz = 512.0;
constexpr Eigen::Index kSamples = 307200;  // 10 min at 512 Hz

ChannelInfo channel(const std::string& name, ChannelRole role, Quantity quantity,
                    const std::string& unit) {
  ChannelInfo info;
  info.name = name;
  info.role = role;
  info.quantity = quantity;
  info.unit = unit;
  return info;
}

Recording two_sines() {
  Recording recording;
  recording.sidecar.sample_rate_hz = kRateHz;
  recording.sidecar.channels = {
      channel("table", ChannelRole::Base, Quantity::Acceleration, "m/s^2"),
      channel("mass", ChannelRole::Mass, Quantity::Displacement, "m")};
  recording.samples_si.resize(kSamples, 2);
  for (Eigen::Index r = 0; r < kSamples; ++r) {
    const double t_s = static_cast<double>(r) / kRateHz;
    recording.samples_si(r, 0) = std::sin(2.0 * std::numbers::pi * 9.0 * t_s);
    recording.samples_si(r, 1) = 1e-3 * std::sin(2.0 * std::numbers::pi * 9.0 * t_s + 0.4);
  }
  return recording;
}

std::string padded(const std::string& text, std::size_t width) {
  return text + std::string(width > text.size() ? width - text.size() : 0, ' ');
}

// One 58b dataset: binary header, records 1-11 (fields as in the dataset 58 description), data.
std::string binary_dataset(const std::string& entity, int node, const Eigen::VectorXd& x,
                           bool float64) {
  char line[128];
  const std::size_t bytes = static_cast<std::size_t>(x.size()) * (float64 ? 8 : 4);
  std::string out = "    -1\n";
  std::snprintf(line, sizeof line, "%6d%c%6d%6d%12d%12zu%6d%6d%12d%12d\n", 58, 'b', 1, 2, 11, bytes,
                0, 0, 0, 0);
  out += line;
  for (int i = 0; i < 5; ++i) out += padded("NONE", 80) + "\n";
  std::snprintf(line, sizeof line, "%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d\n", 1, 0, 0, 0,
                entity.c_str(), node, 1, "NONE", 0, 0);
  out += line;
  std::snprintf(line, sizeof line, "%10d%10d%10d%13.5E%13.5E%13.5E\n", float64 ? 4 : 2,
                static_cast<int>(x.size()), 1, 0.0, 1.0 / kRateHz, 0.0);
  out += line;
  out += "        17    0    0    0 Time                 s                   \n";
  out += "        12    0    0    0 Acceleration         m/s^2               \n";
  out += "         0    0    0    0 NONE                 NONE                \n";
  out += "         0    0    0    0 NONE                 NONE                \n";
  const std::size_t start = out.size();
  out.resize(start + bytes);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (float64) {
      std::memcpy(out.data() + start + 8 * i, &x[i], 8);  // little-endian host
    } else {
      const float v = static_cast<float>(x[i]);
      std::memcpy(out.data() + start + 4 * i, &v, 4);
    }
  }
  return out + "    -1\n";
}

struct Files {
  std::string dir;
  std::string ascii;
  std::string float32;
  std::string float64;
  Sidecar sidecar;
  Files() {
    dir =
        (fs::temp_directory_path() / ("oscilab_bench_uff_" + std::to_string(::getpid()))).string();
    fs::create_directories(dir);
    const Recording recording = two_sines();
    ascii = dir + "/ascii.uff";
    write_recording_uff58(recording, ascii);
    for (const bool f64 : {false, true}) {
      std::ofstream out(dir + (f64 ? "/float64.uff" : "/float32.uff"), std::ios::binary);
      out << binary_dataset("table", 1, recording.samples_si.col(0), f64)
          << binary_dataset("mass", 2, recording.samples_si.col(1), f64);
    }
    float32 = dir + "/float32.uff";
    float64 = dir + "/float64.uff";
    sidecar = recording.sidecar;
    sidecar.channels[0].source = "table:1:+X";
    sidecar.channels[1].source = "mass:2:+X";
  }
  ~Files() {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
};

const Files& files() {
  static const Files instance;
  return instance;
}

void read(benchmark::State& state, const std::string& path) {
  for (auto _ : state) {
    const Recording recording = read_recording(path, files().sidecar);
    benchmark::DoNotOptimize(recording.samples_si.data());
  }
  state.counters["MB"] = static_cast<double>(fs::file_size(path)) / 1e6;
  state.SetItemsProcessed(state.iterations() * kSamples * 2);
}

void BM_ReadUff58Ascii(benchmark::State& state) { read(state, files().ascii); }
void BM_ReadUff58bFloat32(benchmark::State& state) { read(state, files().float32); }
void BM_ReadUff58bFloat64(benchmark::State& state) { read(state, files().float64); }

BENCHMARK(BM_ReadUff58Ascii)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadUff58bFloat32)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadUff58bFloat64)->Unit(benchmark::kMillisecond);

}  // namespace
