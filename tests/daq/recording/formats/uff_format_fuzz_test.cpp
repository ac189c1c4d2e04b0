// Mutated universal files: the UFF 58 reader either reads them or throws InputError; it never
// crashes, hangs, throws anything else or allocates far beyond what the file's size justifies.
// Fixed seeds, so a failure reproduces from its iteration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/uff_test_files.h"
#include "tests/daq/recording/fuzz_mutation.h"
#include "tests/daq/recording/largest_allocation.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::ascii_uff58;
using testing::binary_uff58;
using testing::e13_lines;
using testing::ieee_bytes;
using testing::TempDir;
using testing::Uff58Header;

// Numbers that break parsers and counts: zero, signs, tiny and huge, special values, integer
// limits, rates far beyond any sidecar's Nyquist frequency (1E-9 s: 1 GHz), text.
const std::vector<std::string> kExtremes = {"0",
                                            "-1",
                                            "1E-300",
                                            "1E+300",
                                            "1E-320",
                                            "NaN",
                                            "Inf",
                                            "-Inf",
                                            "2147483647",
                                            "-2147483648",
                                            "9223372036854775807",
                                            "18446744073709551615",
                                            "99999999999999999999",
                                            "",
                                            "1E-9",
                                            "3.5",
                                            "x"};

// One variant of the three base files with some header field set to `value`. `field` selects
// which; the binary header fields only apply to the binary bases.
struct Base {
  Uff58Header header;
  int byte_order = 0;  // 0: ASCII
  bool float64 = false;
  std::vector<double> values;
};

std::string build(const Base& base, int field, const std::string& value) {
  Base b = base;
  Uff58Header& h = b.header;
  std::string order_field;
  std::string format_field = "2";
  std::string lines_field = "11";
  long long bytes = -1;
  switch (field) {
    case 0:
      h.function_type = value;
      break;
    case 1:
      h.response_node = value;
      break;
    case 2:
      h.response_direction = value;
      break;
    case 3:
      h.ordinate_type = value;
      break;
    case 4:
      h.count = value;
      break;
    case 5:
      h.spacing = value;
      break;
    case 6:
      h.abscissa_min = value;
      break;
    case 7:
      h.increment = value;
      break;
    case 8:
      order_field = value.empty() ? " " : value;
      break;
    case 9:
      format_field = value;
      break;
    case 10:
      lines_field = value;
      break;
    case 11:
      bytes = std::strtoll(value.c_str(), nullptr, 10);
      break;
    default:
      break;
  }
  std::string file = "    -1\n   164\n         1SI                           2\n    -1\n";
  if (b.byte_order == 0) {
    file += ascii_uff58(h, e13_lines(b.values, h.eol));
  } else {
    std::string data;
    for (const double v : b.values) {
      data += b.float64 ? ieee_bytes<double>(v, b.byte_order)
                        : ieee_bytes<float>(static_cast<float>(v), b.byte_order);
    }
    file += binary_uff58(h, b.byte_order, data, bytes, order_field, format_field, lines_field);
  }
  Uff58Header frf;
  frf.function_type = "4";
  frf.count = "2";
  file += ascii_uff58(frf, e13_lines({1.0, 2.0, 3.0, 4.0}));
  return file;
}

std::vector<Base> bases() {
  std::vector<double> values;
  for (int i = 0; i < 16; ++i) values.push_back(0.25 * i - 1.0);
  Base ascii;
  ascii.header.count = "16";
  ascii.values = values;
  Base little = ascii;
  little.byte_order = 1;
  little.header.eol = "\r\n";
  Base big = ascii;
  big.byte_order = 2;
  big.float64 = true;
  big.header.ordinate_type = "4";
  return {ascii, little, big};
}

std::string mutate(std::string bytes, std::mt19937_64& rng) {
  switch (std::uniform_int_distribution<int>(0, 4)(rng)) {
    case 0:
      testing::truncate_anywhere(bytes, rng);
      break;
    case 1:
      testing::flip_bits(bytes, std::uniform_int_distribution<int>(1, 8)(rng), rng);
      break;
    case 2: {  // random bytes, newlines and minus signs among them
      constexpr std::string_view kSpecial = "\n\r -+.E0123456789b";
      testing::overwrite_bytes(bytes, std::uniform_int_distribution<int>(1, 6)(rng), rng, kSpecial);
      break;
    }
    case 3: {  // deleted range
      const std::size_t start = testing::random_position(bytes.size(), rng);
      const std::size_t length = std::uniform_int_distribution<std::size_t>(1, 200)(rng);
      bytes.erase(start, length);
      break;
    }
    default: {  // inserted range: a copy of another part of the file
      if (bytes.empty()) break;
      const std::size_t from = testing::random_position(bytes.size() - 1, rng);
      const std::size_t length = std::uniform_int_distribution<std::size_t>(1, 200)(rng);
      testing::repeat_range(bytes, from, length, rng);
      break;
    }
  }
  return bytes;
}

// Reads `path` via describe and through a sidecar; true when nothing but InputError came out.
bool survives(const std::string& path, std::string& failure, int& recordings) {
  Sidecar sidecar;
  sidecar.sample_rate_hz = 1000.0;
  sidecar.channels = {testing::channel("p", ChannelRole::Force, Quantity::Force, "V")};
  try {
    try {
      uff_format().describe(path);
    } catch (const InputError&) {
    }
    for (const char* source : {"mic:3:-Y", "dataset 2"}) {
      sidecar.channels[0].source = source;
      try {
        read_recording(path, sidecar);
        ++recordings;
      } catch (const InputError&) {
      }
    }
  } catch (const std::exception& error) {
    failure = error.what();
    return false;
  } catch (...) {
    failure = "an exception that is not a std::exception";
    return false;
  }
  return true;
}

// Allocation bound: a read holds the file's bytes of one dataset (≤ file size), the values as
// doubles (ASCII: n values need ≥ 2n - 1 characters, so ≤ 4 × (size + 1) bytes; float32: 2 ×
// size) and the recording's matrices of the same size; getline may grow a line to 2 × size.
// 8 × the file size plus 64 KiB for buffers and names bounds every single allocation.
constexpr std::size_t kAllocationFactor = 8;
constexpr std::size_t kAllocationSlack = 64 * 1024;

TEST(UffFormatFuzz, OnlyInputErrorFromTenThousandMutatedFiles) {
  const TempDir dir;
  const std::string path = dir.file("fuzz.uff");
  const std::vector<Base> all = bases();
  std::mt19937_64 rng(20261125);
  int files = 0;
  int recordings = 0;  // reads that succeeded: the mutations leave many files readable
  std::size_t worst_ratio_bytes = 0;
  auto run = [&](const std::string& bytes, const std::string& what) {
    testing::write_file(path, bytes);
    std::string failure;
    testing::start_tracking_allocations();
    const bool ok = survives(path, failure, recordings);
    const std::size_t largest = testing::stop_tracking_allocations();
    ++files;
    ASSERT_TRUE(ok) << what << ": " << failure;
    ASSERT_LE(largest, kAllocationFactor * bytes.size() + kAllocationSlack)
        << what << ": file of " << bytes.size() << " bytes";
    worst_ratio_bytes = std::max(worst_ratio_bytes, largest);
  };
  // Every header field of every base set to every extreme.
  for (std::size_t b = 0; b < all.size(); ++b) {
    for (int field = 0; field < 12; ++field) {
      if (all[b].byte_order == 0 && field >= 8) continue;
      for (const std::string& value : kExtremes) {
        run(build(all[b], field, value), "base " + std::to_string(b) + ", field " +
                                             std::to_string(field) + " = \"" + value + "\"");
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
  // Random mutations (one to three at a time) of the bases and of their extreme variants.
  for (int iteration = 0; files < 10500; ++iteration) {
    const std::size_t b = rng() % all.size();
    // A quarter of them start from an extreme header field, the rest from a readable file.
    const int field = rng() % 4 == 0 ? static_cast<int>(rng() % 12) : 12;  // 12: none
    std::string bytes = build(all[b], field, kExtremes[rng() % kExtremes.size()]);
    const int rounds = 1 + static_cast<int>(rng() % 2);
    for (int r = 0; r < rounds; ++r) bytes = mutate(std::move(bytes), rng);
    run(bytes, "iteration " + std::to_string(iteration) + " (seed 20261125)");
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GE(files, 10000);
  EXPECT_GT(recordings, 1000);
  EXPECT_GT(worst_ratio_bytes, 0u);  // the tracking saw the reads' allocations
  std::printf("%d files, %d recordings read, largest allocation %zu bytes\n", files, recordings,
              worst_ratio_bytes);
}

}  // namespace
}  // namespace oscilab::daq
