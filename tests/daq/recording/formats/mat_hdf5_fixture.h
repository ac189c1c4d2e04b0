#pragma once

// MAT-file and HDF5 fixtures written at test time by SciPy (scipy.io.savemat) and h5py through
// write_mat_hdf5.py: the test gives the values, the script writes the file.

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "daq/recording/format_reader.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq::testing {

/// One variable or dataset: its values row-major in `shape`.
inline nlohmann::json fixture_variable(const std::string& name, const std::string& dtype,
                                       std::vector<std::size_t> shape,
                                       const std::vector<double>& values,
                                       nlohmann::json attrs = nlohmann::json::object(),
                                       const std::string& byteorder = "=") {
  return {{"name", name},     {"dtype", dtype}, {"shape", shape},
          {"values", values}, {"attrs", attrs}, {"byteorder", byteorder}};
}

/// Runs the script on `spec` (its "path" is the file written); fails the test when it fails.
inline void write_fixture(const TempDir& dir, const nlohmann::json& spec) {
  const std::string spec_path = dir.file("spec.json");
  write_file(spec_path, spec.dump());
  // The system interpreter: SciPy and h5py are Debian packages (python3-scipy, python3-h5py).
  const std::string command = "/usr/bin/python3 " OSCILAB_SOURCE_DIR
                              "/tests/daq/recording/formats/write_mat_hdf5.py " +
                              spec_path;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

/// `count` values of a seeded, varied signal: a sine plus noise, rounded to what `dtype` holds.
inline std::vector<double> varied_values(std::size_t count, unsigned seed, double amplitude) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.1 * amplitude);
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) {
    values[i] = amplitude * std::sin(0.05 * static_cast<double>(i) + seed) + noise(rng);
  }
  return values;
}

/// The signal of that name in a file's contents; throws when the file has none.
inline const FileSignal& signal_named(const FileContents& contents, const std::string& name) {
  for (const FileSignal& signal : contents.file_signals) {
    if (signal.name == name) return signal;
  }
  throw std::runtime_error("no signal " + name);
}

}  // namespace oscilab::daq::testing
