#pragma once

// Shared helpers of the recording tests: a scratch directory, file bytes, and a recording whose
// samples are known in closed form.

#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "analysis/common/input_error.h"
#include "daq/recording/recording.h"
#include "tests/input_error_of.h"

namespace oscilab::daq::testing {

/// A fresh directory under the system temporary directory, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    static std::atomic<unsigned> counter{0};
    std::random_device entropy;
    path_ = std::filesystem::temp_directory_path() /
            ("oscilab_recording_test_" + std::to_string(::getpid()) + "_" +
             std::to_string(counter.fetch_add(1)) + "_" + std::to_string(entropy()));
    std::filesystem::create_directories(path_);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline void write_file(const std::string& path, const std::string& bytes) {
  // A new file rather than a truncated one: ext4 flushes a file truncated and rewritten
  // (auto_da_alloc) on close, which would make the fuzz tests wait on the disk.
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

using oscilab::testing::input_error_of;

inline ChannelInfo channel(const std::string& name, ChannelRole role, Quantity quantity,
                           const std::string& unit, double scale = 1.0, double offset = 0.0) {
  ChannelInfo info;
  info.name = name;
  info.role = role;
  info.quantity = quantity;
  info.unit = unit;
  info.scale = scale;
  info.offset = offset;
  return info;
}

/// A stepped-sine-like test recording at `rate_hz`: base acceleration, mass displacement and a
/// force, each a sine of its own frequency, amplitude and phase (SI values in closed form).
inline Recording sine_recording(double rate_hz, Eigen::Index samples,
                                std::vector<ChannelInfo> channels) {
  Recording recording;
  recording.sidecar.sample_rate_hz = rate_hz;
  recording.sidecar.mass_kg = 0.26;
  recording.sidecar.channels = std::move(channels);
  const auto count = static_cast<Eigen::Index>(recording.sidecar.channels.size());
  recording.samples_si.resize(samples, count);
  for (Eigen::Index c = 0; c < count; ++c) {
    const double amplitude = std::pow(10.0, -static_cast<double>(c));  // 1, 0.1, 0.01 ...
    const double freq_hz = 9.0 + static_cast<double>(c);
    for (Eigen::Index r = 0; r < samples; ++r) {
      const double t_s = static_cast<double>(r) / rate_hz;
      recording.samples_si(r, c) =
          amplitude * std::sin(2.0 * std::numbers::pi * freq_hz * t_s + 0.3 * c);
    }
  }
  return recording;
}

/// Little-endian bytes of an integer.
template <typename T>
void append_le(std::string& bytes, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    bytes.push_back(static_cast<char>((static_cast<std::uint64_t>(value) >> (8 * i)) & 0xff));
  }
}

/// A canonical 16-bit PCM WAV file (RIFF, "fmt " and "data" chunks), written by hand so that the
/// reader is checked against the format's specification rather than against libsndfile itself.
inline std::string pcm16_wav(int rate_hz, int channels, const std::vector<std::int16_t>& samples) {
  const auto data_bytes = static_cast<std::uint32_t>(samples.size() * 2);
  std::string bytes = "RIFF";
  append_le<std::uint32_t>(bytes, 36 + data_bytes);
  bytes += "WAVEfmt ";
  append_le<std::uint32_t>(bytes, 16);
  append_le<std::uint16_t>(bytes, 1);  // PCM
  append_le<std::uint16_t>(bytes, static_cast<std::uint16_t>(channels));
  append_le<std::uint32_t>(bytes, static_cast<std::uint32_t>(rate_hz));
  append_le<std::uint32_t>(bytes, static_cast<std::uint32_t>(rate_hz * channels * 2));
  append_le<std::uint16_t>(bytes, static_cast<std::uint16_t>(channels * 2));
  append_le<std::uint16_t>(bytes, 16);
  bytes += "data";
  append_le<std::uint32_t>(bytes, data_bytes);
  for (const std::int16_t sample : samples)
    append_le<std::uint16_t>(bytes, static_cast<std::uint16_t>(sample));
  return bytes;
}

}  // namespace oscilab::daq::testing
