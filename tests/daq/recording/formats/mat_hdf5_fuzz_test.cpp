// Mutated MAT-files and HDF5 files: describe and read_recording either read them or throw
// InputError, never anything else, never a crash or a hang of the test process (matio and
// libhdf5 run in a child process; their crashes become InputErrors). Fixed seeds, so a failure
// reproduces. The seeds are small files SciPy and h5py write.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/mat_hdf5_fixture.h"
#include "tests/daq/recording/fuzz_mutation.h"
#include "tests/daq/recording/largest_allocation.h"
#include "tests/daq/recording/recording_test_util.h"

// The largest allocation tracked is the parent's, per thread: the bound on what a file makes the
// parent allocate (the children's allocations are limited by their address-space limit,
// library_process.cpp).

namespace oscilab::daq {
namespace {

using nlohmann::json;
using testing::bits_of;
using testing::FieldValue;
using testing::fixture_variable;
using testing::random_position;

// Mutated files per format: 10 000 in the `study` suite, 1 000 in the unit suite, 200 when that
// suite runs under the sanitizers (each file costs a few forked children, ~2 ms each; ~0.1 s
// under ASan).
#ifndef OSCILAB_FUZZ_ITERATIONS
#define OSCILAB_FUZZ_ITERATIONS 1000
#endif
constexpr int kIterations = OSCILAB_FUZZ_ITERATIONS;
using testing::TempDir;

template <typename T>
std::string bytes_of(T value) {
  std::string bytes(sizeof(T), '\0');
  std::memcpy(bytes.data(), &value, sizeof(T));
  return bytes;
}

// Values a header field or an attribute is set to: 0, -1, tiny, huge, NaN, Inf, the limits of
// counts.
std::vector<FieldValue> extremes() {
  std::vector<FieldValue> values;
  for (const double value :
       {0.0, -1.0, 1e-300, 5e-324, 1e300, std::numeric_limits<double>::quiet_NaN(),
        std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        1e9 /* a rate far beyond Nyquist */}) {
    values.push_back({bits_of(value), 8});
  }
  for (const float value : {0.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(), 3e38f}) {
    values.push_back({bits_of(value), 4});
  }
  for (const std::uint64_t value :
       {std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max(),
        std::uint64_t{std::numeric_limits<std::int64_t>::max()}, std::uint64_t{1} << 40}) {
    values.push_back({value, 8});
  }
  for (const std::uint32_t value : {std::uint32_t{0}, std::uint32_t{0xffffffff},
                                    std::uint32_t{0x7fffffff}, std::uint32_t{0x80000000}}) {
    values.push_back({value, 4});
  }
  for (const std::uint16_t value : {std::uint16_t{0}, std::uint16_t{0xffff}}) {
    values.push_back({value, 2});
  }
  values.push_back({0xff, 1});
  values.push_back({0, 1});
  return values;
}

// Where the seed stores values worth setting to extremes: its dimensions (64 as 32- and 64-bit
// integers), its rate attributes and its time values.
std::vector<std::size_t> targets_in(const std::string& bytes) {
  std::vector<std::size_t> targets;
  for (const std::string& pattern :
       {bytes_of<std::uint64_t>(64), bytes_of<std::uint32_t>(64), bytes_of<std::uint32_t>(3),
        bytes_of<std::uint32_t>(2), bytes_of(0.01), bytes_of(100.0), bytes_of(0.63)}) {
    for (std::size_t at = bytes.find(pattern); at != std::string::npos;
         at = bytes.find(pattern, at + 1)) {
      targets.push_back(at);
    }
  }
  return targets;
}

std::string mutate(std::string bytes, const std::vector<std::size_t>& targets,
                   std::mt19937_64& rng) {
  static const std::vector<FieldValue> kExtremes = extremes();
  const int mutations = std::uniform_int_distribution<int>(1, 3)(rng);
  for (int m = 0; m < mutations && !bytes.empty(); ++m) {
    switch (std::uniform_int_distribution<int>(0, 6)(rng)) {
      case 0:
        testing::truncate_anywhere(bytes, rng);
        break;
      case 1:
        testing::flip_bits(bytes, 4, rng);
        break;
      case 2:
        testing::overwrite_bytes(bytes, 4, rng);
        break;
      case 3: {  // inserted random range
        const std::string inserted =
            testing::random_bytes(std::uniform_int_distribution<std::size_t>(1, 64)(rng), rng);
        bytes.insert(random_position(bytes.size(), rng), inserted);
        break;
      }
      case 4: {  // deleted range
        const std::size_t at = random_position(bytes.size() - 1, rng);
        bytes.erase(at, std::uniform_int_distribution<std::size_t>(1, 64)(rng));
        break;
      }
      case 5:    // an extreme at a known field (dimensions, rates, times)
      case 6: {  // an extreme at any aligned place (header fields, sizes, addresses)
        const FieldValue& value = kExtremes[rng() % kExtremes.size()];
        std::size_t at = 0;
        if (m % 2 == 0 && !targets.empty()) {
          at = targets[rng() % targets.size()];
        } else {
          at = random_position(bytes.size() - 1, rng) & ~std::size_t{3};
        }
        if (at + value.width <= bytes.size()) {  // in the host's byte order, as the seed's values
          testing::put_field(bytes, at, value.value, value.width,
                             std::endian::native == std::endian::big);
        }
        break;
      }
    }
  }
  return bytes;
}

struct FuzzStats {
  int read = 0;
  int refused = 0;
  int library_failed = 0;  // the child crashed, aborted, was killed or timed out
  std::size_t largest_ratio = 0;
};

// `iterations` mutations of each seed, each described and read with `sidecar`.
FuzzStats fuzz(const FormatReader& format, const std::vector<std::string>& seeds,
               const std::string& extension, const Sidecar& sidecar, int iterations,
               std::uint64_t seed) {
  const TempDir dir;
  std::mt19937_64 rng(seed);
  FuzzStats stats;
  std::vector<std::vector<std::size_t>> targets;
  for (const std::string& bytes : seeds) targets.push_back(targets_in(bytes));
  for (int i = 0; i < iterations; ++i) {
    const std::size_t which = static_cast<std::size_t>(i) % seeds.size();
    const std::string bytes = mutate(seeds[which], targets[which], rng);
    const std::string path = dir.file("f" + std::to_string(i % 8) + extension);
    testing::write_file(path, bytes);
    testing::start_tracking_allocations();
    try {
      format.describe(path);
      read_recording(path, sidecar);
      ++stats.read;
    } catch (const InputError& error) {
      const std::string message = error.what();
      ++stats.refused;
      if (message.find("failed on this file") != std::string::npos) {
        if (++stats.library_failed <= 3) std::printf("%s\n", message.c_str());
      }
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    } catch (const std::exception& error) {
      ADD_FAILURE() << "seed " << seed << ", iteration " << i << ": " << error.what();
    } catch (...) {
      ADD_FAILURE() << "seed " << seed << ", iteration " << i << ": unknown exception";
    }
    const std::size_t largest = testing::stop_tracking_allocations();
    const std::size_t ratio = largest / std::max<std::size_t>(bytes.size(), 1);
    stats.largest_ratio = std::max(stats.largest_ratio, ratio);
    // 1 MiB for the description's text, then 8 bytes per value, at most 1032 values per byte
    // of a compressed file (deflate's ratio): the reply the parent holds.
    EXPECT_LE(largest, (std::size_t{1} << 20) + 8 * 1032 * bytes.size())
        << "seed " << seed << ", iteration " << i;
  }
  return stats;
}

// Half the iterations on each of two threads, as the CLI reads recordings: the children are
// forked from a multi-threaded process.
FuzzStats fuzz_on_two_threads(const FormatReader& format, const std::vector<std::string>& seeds,
                              const std::string& extension, const Sidecar& sidecar,
                              std::uint64_t seed) {
  FuzzStats stats[2];
  std::thread other(
      [&] { stats[1] = fuzz(format, seeds, extension, sidecar, kIterations / 2, seed + 1000); });
  stats[0] = fuzz(format, seeds, extension, sidecar, kIterations - kIterations / 2, seed);
  other.join();
  return {stats[0].read + stats[1].read, stats[0].refused + stats[1].refused,
          stats[0].library_failed + stats[1].library_failed,
          std::max(stats[0].largest_ratio, stats[1].largest_ratio)};
}

void report(const char* name, const FuzzStats& stats) {
  std::printf(
      "%s: %d read, %d refused, of which %d library failures (crash, abort, timeout); "
      "largest allocation %zu x the file size\n",
      name, stats.read, stats.refused, stats.library_failed, stats.largest_ratio);
}

std::vector<double> ramp(std::size_t count, double step, double start = 0.0) {
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) values[i] = start + step * static_cast<double>(i);
  return values;
}

std::vector<double> time_matrix() {  // 64 x 3: [t a b], t at 100 Hz
  std::vector<double> values;
  for (std::size_t i = 0; i < 64; ++i) {
    values.insert(values.end(), {static_cast<double>(i) / 100.0, 0.63 * i, -2.0 * i});
  }
  return values;
}

Sidecar sidecar_for(const std::vector<std::pair<std::string, int>>& sources,
                    const SignalTime& time) {
  Sidecar sidecar;
  sidecar.sample_rate_hz = 100.0;
  for (const auto& [source, column] : sources) {
    ChannelInfo channel = testing::channel("c" + std::to_string(sidecar.channels.size()),
                                           ChannelRole::Base, Quantity::Acceleration, "m/s^2");
    channel.source = source;
    channel.column = column;
    sidecar.channels.push_back(channel);
  }
  sidecar.time = time;
  return sidecar;
}

TEST(MatHdf5Fuzz, MutatedMatFilesOnlyThrowInputError) {
  const TempDir dir;
  std::vector<std::string> seeds;
  for (const std::string format : {"mat5", "mat5z", "mat73"}) {
    const std::string path = dir.file(format + ".mat");
    testing::write_fixture(dir, {{"format", format == "mat5z" ? "mat5" : format},
                                 {"path", path},
                                 {"compress", format == "mat5z"},
                                 {"variables",
                                  {fixture_variable("x", "float64", {1, 64}, ramp(64, 0.01)),
                                   fixture_variable("m", "float64", {64, 3}, time_matrix()),
                                   fixture_variable("c", "int16", {64, 1}, ramp(64, 3.0, -90))}}});
    seeds.push_back(testing::read_file(path));
  }
  const FuzzStats stats = fuzz_on_two_threads(
      mat_format(), seeds, ".mat", sidecar_for({{"x", -1}, {"m", 1}, {"c", -1}}, {"m", 0}), 58);
  report("MAT", stats);
  EXPECT_GT(stats.read, 0);  // some mutations leave the values readable
}

TEST(MatHdf5Fuzz, MutatedHdf5FilesOnlyThrowInputError) {
  const TempDir dir;
  const std::string path = dir.file("seed.h5");
  testing::write_fixture(
      dir, {{"format", "hdf5"},
            {"path", path},
            {"groups", {{{"path", "/g"}, {"attrs", {{"fs", 100.0}}}}}},
            {"variables",
             {fixture_variable("/g/data", "float32", {64, 2}, ramp(128, 0.5),
                               {{"dT", 0.01}, {"units", "m/s"}}),
              fixture_variable("/g/t", "float64", {64}, ramp(64, 0.01)),
              fixture_variable("/x", "int16", {64}, ramp(64, 3.0, -90), {{"fs", 100.0}}, ">")}}});
  const std::string plain = testing::read_file(path);
  const std::string compressed_path = dir.file("seedz.h5");
  testing::write_fixture(
      dir, {{"format", "hdf5"},
            {"path", compressed_path},
            {"compress", true},
            {"variables",
             {fixture_variable("/g/data", "float32", {64, 2}, ramp(128, 0.5), {{"dT", 0.01}}),
              fixture_variable("/g/t", "float64", {64}, ramp(64, 0.01)),
              fixture_variable("/x", "int16", {64}, ramp(64, 3.0, -90))}}});
  const FuzzStats stats =
      fuzz_on_two_threads(hdf5_format(), {plain, testing::read_file(compressed_path)}, ".h5",
                          sidecar_for({{"/g/data", 0}, {"/x", -1}}, {"/g/t", -1}), 59);
  report("HDF5", stats);
  EXPECT_GT(stats.read, 0);
}

}  // namespace
}  // namespace oscilab::daq
