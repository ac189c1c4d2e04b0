#pragma once

// Shared by the MAT-file and HDF5 read benchmarks: 10 minutes of 2 channels at 512 Hz written by
// SciPy or h5py (tests/daq/recording/formats/write_mat_hdf5.py), and the sidecar that maps them.

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "daq/recording/sidecar.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq::bench {

inline constexpr std::size_t kSamples = 307200;  // 10 min at 512 Hz
inline constexpr double kRateHz = 512.0;

/// A file written by the fixture script from `spec` (its "path" is set here), removed at exit.
class ScriptFile {
 public:
  ScriptFile(const std::string& name, nlohmann::json spec) {
    spec["path"] = dir_.file(name);
    testing::write_file(dir_.file("spec.json"), spec.dump());
    const std::string command = "/usr/bin/python3 " OSCILAB_SOURCE_DIR
                                "/tests/daq/recording/formats/write_mat_hdf5.py " +
                                dir_.file("spec.json");
    if (std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command);
    path_ = spec["path"];
  }
  const std::string& path() const { return path_; }

 private:
  testing::TempDir dir_;
  std::string path_;
};

/// A sine of `amplitude` over `shape` (the script computes it).
inline nlohmann::json sine_variable(const std::string& name, std::vector<std::size_t> shape,
                                    double amplitude,
                                    nlohmann::json attrs = nlohmann::json::object()) {
  return {{"name", name},
          {"dtype", "float64"},
          {"shape", shape},
          {"amplitude", amplitude},
          {"attrs", attrs}};
}

inline Sidecar two_channels(const std::vector<std::pair<std::string, int>>& sources) {
  Sidecar sidecar;
  sidecar.sample_rate_hz = kRateHz;
  sidecar.channels.push_back(
      testing::channel("base", ChannelRole::Base, Quantity::Acceleration, "m/s^2"));
  sidecar.channels.push_back(
      testing::channel("z", ChannelRole::Mass, Quantity::Displacement, "mm"));
  for (std::size_t c = 0; c < 2; ++c) {
    sidecar.channels[c].source = sources[c].first;
    sidecar.channels[c].column = sources[c].second;
  }
  return sidecar;
}

}  // namespace oscilab::daq::bench
