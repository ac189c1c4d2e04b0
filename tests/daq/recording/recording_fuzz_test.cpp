// Mutated sidecars, CSV and sound files: the readers either read them or throw InputError; they
// never crash, hang or throw anything else. Fixed seeds, so a failure reproduces.
#include <gtest/gtest.h>

#include <cstdint>
#include <exception>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/recording.h"
#include "daq/recording/sidecar.h"
#include "tests/daq/recording/fuzz_mutation.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using nlohmann::json;
using testing::channel;
using testing::TempDir;

// Text that tends to break parsers: separators, signs, exponents, huge and special numbers.
const std::vector<std::string> kGarbage = {",",
                                           ";",
                                           "\n",
                                           "\r\n",
                                           "\"",
                                           "-",
                                           "+",
                                           "e",
                                           ".",
                                           "{",
                                           "}",
                                           "[",
                                           "]",
                                           ":",
                                           "null",
                                           "nan",
                                           "inf",
                                           "-inf",
                                           "1e999",
                                           "-1e999",
                                           "1e-999",
                                           "18446744073709551616",
                                           "-9223372036854775809",
                                           "0x10",
                                           "\xEF\xBB\xBF",
                                           "\xff\xfe",
                                           std::string(1, '\0'),
                                           "\t",
                                           "  ",
                                           "t_s",
                                           "\"mps\"",
                                           "99999999999999999999999999999999999999"};

// One random mutation of `bytes`: truncation, byte flips, inserted garbage, a deleted or a
// repeated range.
std::string mutate_bytes(std::string bytes, std::mt19937_64& rng) {
  const int kind = std::uniform_int_distribution<int>(0, 5)(rng);
  switch (kind) {
    case 0:
      testing::truncate_anywhere(bytes, rng);
      break;
    case 1:
      testing::flip_bits(bytes, std::uniform_int_distribution<int>(1, 8)(rng), rng);
      break;
    case 2:
      testing::overwrite_bytes(bytes, std::uniform_int_distribution<int>(1, 6)(rng), rng);
      break;
    case 3:  // inserted garbage
      bytes.insert(testing::random_position(bytes.size(), rng), kGarbage[rng() % kGarbage.size()]);
      break;
    case 4: {  // deleted range
      const std::size_t start = testing::random_position(bytes.size(), rng);
      bytes.erase(start, std::uniform_int_distribution<std::size_t>(1, 64)(rng));
      break;
    }
    default: {  // repeated range
      const std::size_t start = testing::random_position(bytes.size(), rng);
      testing::repeat_range(bytes, start, rng() % 128, rng);
      break;
    }
  }
  return bytes;
}

// A value of a random JSON type, including ones no field accepts.
json random_value(std::mt19937_64& rng) {
  switch (rng() % 12) {
    case 0:
      return nullptr;
    case 1:
      return static_cast<bool>(rng() % 2);
    case 2:
      return "mps";
    case 3:
      return -1;
    case 4:
      return 0;
    case 5:
      return 1e308;
    case 6:
      return std::numeric_limits<std::uint64_t>::max();
    case 7:
      return json::array();
    case 8:
      return json::object();
    case 9:
      return std::numeric_limits<double>::infinity();  // out of range: stored as infinity
    case 10:
      return json::array({1, "two", nullptr});
    default:
      return -5e-324;
  }
}

// Replaces, adds or erases one value somewhere in the JSON tree.
void mutate_json(json& value, std::mt19937_64& rng) {
  json* node = &value;
  for (int depth = 0; depth < 4; ++depth) {
    if (!(node->is_object() || node->is_array()) || node->empty() || rng() % 3 == 0) break;
    auto it = node->begin();
    std::advance(it, static_cast<long>(rng() % node->size()));
    if (rng() % 4 == 0 && node->is_object() && depth > 0) {
      node->erase(it.key());
      return;
    }
    node = &*it;
  }
  if (node->is_object() && rng() % 2 == 0) {
    static const std::vector<std::string> kKeys = {
        "format", "sample_rate_hz", "mass_kg", "channels",  "csv",   "excitation",
        "column", "unit",           "levels",  "delimiter", "header"};
    (*node)[kKeys[rng() % kKeys.size()]] = random_value(rng);
  } else {
    *node = random_value(rng);
  }
}

enum class Outcome { Read, Rejected, Failed };

// Reads `path`: a trustworthy recording or an InputError naming the file; anything else is a
// failure, described in `failure`.
Outcome read_or_reject(const std::string& path, std::string& failure) {
  try {
    const Recording recording = read_recording(path);
    if (recording.samples_si.rows() == 0 || !recording.samples_si.allFinite()) {
      failure = "accepted a recording without samples or with non-finite samples";
      return Outcome::Failed;
    }
    return Outcome::Read;
  } catch (const InputError& error) {
    // The message names the recording or its sidecar: both share the stem.
    const std::string stem = path.substr(0, path.rfind('.'));
    if (std::string(error.what()).rfind(stem, 0) != 0) {
      failure = std::string("message does not name the file: ") + error.what();
      return Outcome::Failed;
    }
    return Outcome::Rejected;
  } catch (const std::exception& error) {
    failure = std::string("unexpected exception: ") + error.what();
  } catch (...) {
    failure = "unexpected non-standard exception";
  }
  return Outcome::Failed;
}

Recording base_recording() {
  Recording recording = testing::sine_recording(
      256.0, 48,
      {channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "g", 0.01),
       channel("y", ChannelRole::Mass, Quantity::Displacement, "mm", 1e-3, 0.5),
       channel("f", ChannelRole::Force, Quantity::Force, "N", 1e-4)});
  Excitation excitation;
  excitation.type = "stepped-sine";
  excitation.frequency_hz = 9.0;
  excitation.levels = {{0.2, 0.0, 0.05, {}}, {0.4, 0.06, 0.18, {}}};
  recording.sidecar.excitation = excitation;
  recording.sidecar.notes = "fuzz";
  return recording;
}

// Mutates the bytes of `mutated_name` (a recording or its sidecar in `dir`) `iterations` times
// from `seed` and reads the recording each time.
void fuzz_file_bytes(const TempDir& dir, const std::string& recording_name,
                     const std::string& mutated_name, std::uint64_t seed, int iterations) {
  const std::string original = testing::read_file(dir.file(mutated_name));
  std::mt19937_64 rng(seed);
  int rejected = 0;
  for (int i = 0; i < iterations; ++i) {
    std::string bytes = original;
    const int rounds = std::uniform_int_distribution<int>(1, 3)(rng);
    for (int r = 0; r < rounds; ++r) bytes = mutate_bytes(bytes, rng);
    testing::write_file(dir.file(mutated_name), bytes);
    std::string failure;
    const Outcome outcome = read_or_reject(dir.file(recording_name), failure);
    ASSERT_NE(outcome, Outcome::Failed)
        << "seed " << seed << ", iteration " << i << ": " << failure;
    if (outcome == Outcome::Rejected) ++rejected;
  }
  ::testing::Test::RecordProperty("rejected", rejected);
  // Most mutations must be caught; a few (a flipped mantissa bit) leave a valid file.
  EXPECT_GT(rejected, 0);
}

// A recording written by the code under test, with its sidecar.
void fuzz_written(const std::string& recording_name, const std::string& mutated_name,
                  std::uint64_t seed, int iterations) {
  const TempDir dir;
  write_recording(base_recording(), dir.file(recording_name));
  fuzz_file_bytes(dir, recording_name, mutated_name, seed, iterations);
}

// Another instrument's export: preamble, no header, semicolons, a time column, unused columns.
void write_instrument_csv(const TempDir& dir) {
  std::string text = "Scope export 2026-11-23\ntime;ch1;ch2;ch3\n";
  for (int i = 0; i < 40; ++i) {
    text += std::to_string(i / 2048.0) + ";" + std::to_string(0.01 * i) + ";" +
            std::to_string(-0.5 * i) + ";21.5\n";
  }
  testing::write_file(dir.file("scope.csv"), text);
  testing::write_file(dir.file("scope.json"), R"({"sample_rate_hz": 2048,
    "csv": {"header": false, "delimiter": ";", "skip_lines": 2, "time_column": 0},
    "channels": [
      {"name": "base_acc", "role": "base", "quantity": "acceleration", "unit": "g",
       "scale": 10, "offset": 0.02, "column": 1},
      {"name": "y_dot", "role": "mass", "quantity": "velocity", "unit": "mm/s", "scale": 1,
       "column": 2}]})");
}

TEST(RecordingFuzz, MutatedSidecarBytesGiveOnlyInputErrors) {
  fuzz_written("run.csv", "run.json", 20261123, 10000);
}

TEST(RecordingFuzz, MutatedCsvBytesGiveOnlyInputErrors) {
  fuzz_written("run.csv", "run.csv", 4242, 10000);
}

TEST(RecordingFuzz, MutatedHeaderlessCsvAndItsSidecarGiveOnlyInputErrors) {
  const TempDir dir;
  write_instrument_csv(dir);
  fuzz_file_bytes(dir, "scope.csv", "scope.csv", 2048, 10000);
  write_instrument_csv(dir);
  fuzz_file_bytes(dir, "scope.csv", "scope.json", 9, 10000);
}

TEST(RecordingFuzz, MutatedWavBytesGiveOnlyInputErrors) {
  fuzz_written("run.wav", "run.wav", 512, 10000);
}

TEST(RecordingFuzz, MutatedFlacBytesGiveOnlyInputErrors) {
  fuzz_written("run.flac", "run.flac", 24, 10000);
}

TEST(RecordingFuzz, SidecarsWithWrongTypesGiveOnlyInputErrors) {
  const json original = sidecar_to_json(base_recording().sidecar);
  std::mt19937_64 rng(1901);
  int accepted = 0;
  for (int i = 0; i < 10000; ++i) {
    json value = original;
    const int rounds = std::uniform_int_distribution<int>(1, 3)(rng);
    for (int r = 0; r < rounds; ++r) mutate_json(value, rng);
    try {
      const Sidecar sidecar = parse_sidecar(value, "fuzz.json");
      // What is accepted must survive its own round trip.
      ASSERT_EQ(sidecar_to_json(parse_sidecar(sidecar_to_json(sidecar), "fuzz.json")),
                sidecar_to_json(sidecar))
          << "iteration " << i << ": " << value.dump();
      ++accepted;
    } catch (const InputError& error) {
      ASSERT_EQ(std::string(error.what()).rfind("fuzz.json", 0), 0u) << error.what();
    } catch (const std::exception& error) {
      FAIL() << "iteration " << i << ": unexpected exception " << error.what() << " for "
             << value.dump();
    }
  }
  EXPECT_GT(accepted, 0);  // mutations of unknown or optional keys are valid
}

}  // namespace
}  // namespace oscilab::daq
