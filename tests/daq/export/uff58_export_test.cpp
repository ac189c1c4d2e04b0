// Universal File export (daq/export/uff58_export), read back by a fixed-column parser written
// here from the dataset definitions (SDRL, University of Cincinnati: "Universal Dataset Number
// 58: Function at Nodal DOF" and "Number 164: Units"), not from the writer.
#include "daq/export/uff58_export.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::channel;
using testing::input_error_of;
using testing::read_file;
using testing::sine_recording;
using testing::TempDir;

// A dataset: the lines between a "    -1" that opens it and the "    -1" that closes it.
struct Dataset {
  int number = 0;
  std::vector<std::string> records;  // the lines after the dataset number
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<Dataset> parse_universal_file(const std::string& text) {
  std::vector<Dataset> datasets;
  const std::vector<std::string> lines = lines_of(text);
  std::size_t i = 0;
  while (i < lines.size()) {
    EXPECT_EQ(lines[i], "    -1") << "line " << i + 1 << " should open a dataset";
    if (lines[i] != "    -1" || i + 1 >= lines.size()) break;
    Dataset dataset;
    EXPECT_EQ(lines[i + 1].size(), 6u) << "dataset number is I6";
    dataset.number = std::atoi(lines[i + 1].c_str());
    i += 2;
    while (i < lines.size() && lines[i] != "    -1") dataset.records.push_back(lines[i++]);
    EXPECT_LT(i, lines.size()) << "dataset " << dataset.number << " is not closed";
    ++i;  // the closing delimiter
    datasets.push_back(dataset);
  }
  return datasets;
}

// Fixed columns [from, from + width) of a record, as Fortran reads them.
std::string field(const std::string& record, std::size_t from, std::size_t width) {
  return record.size() > from ? record.substr(from, width) : std::string();
}
long long int_field(const std::string& record, std::size_t from, std::size_t width) {
  const std::string text = field(record, from, width);
  EXPECT_NE(text.find_first_not_of(' '), std::string::npos) << "blank I field in: " << record;
  return std::strtoll(text.c_str(), nullptr, 10);
}
double real_field(const std::string& record, std::size_t from, std::size_t width) {
  std::string text = field(record, from, width);
  for (char& c : text) {
    if (c == 'D') c = 'E';  // Fortran double-precision exponent
  }
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  EXPECT_NE(end, text.c_str()) << "no number in [" << text << "]";
  return value;
}
std::string trimmed(const std::string& text) {
  const auto last = text.find_last_not_of(' ');
  return last == std::string::npos ? std::string() : text.substr(0, last + 1);
}

struct Axis {  // records 8–11: Format(I10,3I5,2(1X,20A1))
  long long data_type;
  long long length_exp, force_exp, temperature_exp;
  std::string label, unit;
};
Axis axis_of(const std::string& record) {
  EXPECT_EQ(record[25], ' ');
  EXPECT_EQ(record[46], ' ');
  return {int_field(record, 0, 10), int_field(record, 10, 5),       int_field(record, 15, 5),
          int_field(record, 20, 5), trimmed(field(record, 26, 20)), trimmed(field(record, 47, 20))};
}

Recording test_recording(double rate_hz, Eigen::Index samples) {
  Recording recording =
      sine_recording(rate_hz, samples,
                     {channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "m/s^2"),
                      channel("y", ChannelRole::Mass, Quantity::Velocity, "m/s"),
                      channel("z", ChannelRole::Relative, Quantity::Displacement, "m"),
                      channel("force_applied", ChannelRole::Force, Quantity::Force, "N")});
  recording.sidecar.channels[0].sensor = "accelerometer";
  recording.source_path = "samples/run1.flac";
  Excitation excitation;
  excitation.type = "stepped-sine";
  excitation.frequency_hz = 9.0;
  recording.sidecar.excitation = excitation;
  // Magnitudes far from 1 in both directions, and a negative value, for the exponent fields.
  recording.samples_si(0, 0) = -1.234567890123456e-300;
  recording.samples_si(1, 0) = 9.87654321098765e+250;
  recording.samples_si(2, 0) = 0.0;
  return recording;
}

// "DD-MMM-YY HH:MM:SS" (UFF ID line dates), checked character by character: std::regex trips a
// false -Wmaybe-uninitialized of GCC 12 in the sanitizer build.
bool is_uff_date(const std::string& text) {
  const std::string pattern = "99-AAA-99 99:99:99";
  if (text.size() != pattern.size()) return false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const bool ok = pattern[i] == '9'   ? std::isdigit(c) != 0
                    : pattern[i] == 'A' ? std::isupper(c) != 0
                                        : text[i] == pattern[i];
    if (!ok) return false;
  }
  return true;
}

TEST(Uff58Export, WritesOneDatasetPerChannelInTheStandardRecords) {
  TempDir dir;
  const Eigen::Index n = 1001;  // not a multiple of 4: the last data line holds one value
  const Recording recording = test_recording(512.0, n);
  const std::string path = dir.file("run1.uff");
  Uff58Options options;
  options.created = "05-MAR-24 14:03:59";
  write_recording_uff58(recording, path, options);
  const std::string text = read_file(path);

  for (const std::string& line : lines_of(text)) {
    ASSERT_LE(line.size(), 80u) << line;  // the format is card images of 80 columns
  }
  const std::vector<Dataset> datasets = parse_universal_file(text);
  ASSERT_EQ(datasets.size(), 5u);  // units + one per channel

  // Dataset 164: Format(I10,20A1,I10) / 3D25.17 / D25.17: SI, factors 1.
  ASSERT_EQ(datasets[0].number, 164);
  ASSERT_EQ(datasets[0].records.size(), 3u);
  EXPECT_EQ(int_field(datasets[0].records[0], 0, 10), 1);  // SI: meter (newton)
  EXPECT_EQ(int_field(datasets[0].records[0], 30, 10), 2);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(real_field(datasets[0].records[1], 25 * k, 25), 1.0);
  EXPECT_EQ(real_field(datasets[0].records[2], 0, 25), 273.15);  // 16 digits: exact

  const int expected_type[] = {12, 11, 8, 13};  // acceleration, velocity, displacement, force
  const char* expected_unit[] = {"m/s^2", "m/s", "m", "N"};
  const char* expected_label[] = {"Acceleration", "Velocity", "Displacement", "Force"};
  const int expected_node[] = {1, 2, 2, 2};
  for (int c = 0; c < 4; ++c) {
    SCOPED_TRACE("channel " + std::to_string(c));
    const Dataset& d = datasets[static_cast<std::size_t>(c) + 1];
    ASSERT_EQ(d.number, 58);
    ASSERT_GE(d.records.size(), 11u);
    // Records 1–5: ID lines, never blank.
    const std::string& name = recording.sidecar.channels[static_cast<std::size_t>(c)].name;
    EXPECT_EQ(d.records[0].rfind(name + ": ", 0), 0u) << d.records[0];
    EXPECT_EQ(trimmed(d.records[1]), "Oscilab recording run1.flac");
    EXPECT_EQ(trimmed(d.records[2]), "05-MAR-24 14:03:59");
    EXPECT_EQ(trimmed(d.records[3]), "stepped-sine at 9 Hz");
    EXPECT_EQ(trimmed(d.records[4]), c == 0 ? "accelerometer" : "NONE");

    // Record 6: Format(2(I5,I10),2(1X,10A1,I10,I4)).
    const std::string& r6 = d.records[5];
    EXPECT_EQ(r6.size(), 80u);
    EXPECT_EQ(int_field(r6, 0, 5), 1);  // time response
    EXPECT_EQ(int_field(r6, 5, 10), c + 1);
    EXPECT_EQ(int_field(r6, 15, 5), 0);
    EXPECT_EQ(int_field(r6, 20, 10), 0);  // single point excitation
    EXPECT_EQ(r6[30], ' ');
    EXPECT_EQ(trimmed(field(r6, 31, 10)), name.substr(0, 10));  // "force_appl"
    EXPECT_EQ(int_field(r6, 41, 10), expected_node[c]);
    EXPECT_EQ(int_field(r6, 51, 4), 1);  // +X translation
    EXPECT_EQ(r6[55], ' ');
    EXPECT_EQ(trimmed(field(r6, 56, 10)), "table");
    EXPECT_EQ(int_field(r6, 66, 10), 1);
    EXPECT_EQ(int_field(r6, 76, 4), 1);

    // Record 7: Format(3I10,3E13.5).
    const std::string& r7 = d.records[6];
    EXPECT_EQ(r7.size(), 69u);
    EXPECT_EQ(int_field(r7, 0, 10), 4);  // real, double precision
    EXPECT_EQ(int_field(r7, 10, 10), n);
    EXPECT_EQ(int_field(r7, 20, 10), 1);  // even spacing
    EXPECT_EQ(real_field(r7, 30, 13), 0.0);
    EXPECT_EQ(real_field(r7, 43, 13), 1.0 / 512.0);  // 1.953125E-03: exact in 7 digits
    EXPECT_EQ(real_field(r7, 56, 13), 0.0);

    // Records 8–11.
    const Axis abscissa = axis_of(d.records[7]);
    EXPECT_EQ(abscissa.data_type, 17);  // time
    EXPECT_EQ(abscissa.label, "Time");
    EXPECT_EQ(abscissa.unit, "s");
    const Axis ordinate = axis_of(d.records[8]);
    EXPECT_EQ(ordinate.data_type, expected_type[c]);
    EXPECT_EQ(ordinate.length_exp + ordinate.force_exp + ordinate.temperature_exp, 0);
    EXPECT_EQ(ordinate.label, expected_label[c]);
    EXPECT_EQ(ordinate.unit, expected_unit[c]);
    EXPECT_EQ(axis_of(d.records[9]).data_type, 0);
    EXPECT_EQ(axis_of(d.records[10]).data_type, 0);

    // Record 12: 4E20.12, ceil(n / 4) lines. 12 significant digits round to within half a unit
    // of the 12th digit: |error| ≤ 5e-12 |x|.
    const std::size_t data_lines = d.records.size() - 11;
    ASSERT_EQ(data_lines, static_cast<std::size_t>((n + 3) / 4));
    std::vector<double> values;
    for (std::size_t l = 11; l < d.records.size(); ++l) {
      const std::string& line = d.records[l];
      EXPECT_EQ(line.size() % 20, 0u) << line;
      for (std::size_t k = 0; k + 20 <= line.size(); k += 20) {
        EXPECT_EQ(line[k], ' ') << "fields stay apart: " << line;
        values.push_back(real_field(line, k, 20));
      }
    }
    ASSERT_EQ(values.size(), static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) {
      const double expected = recording.samples_si(i, c);
      ASSERT_NEAR(values[static_cast<std::size_t>(i)], expected, 5e-12 * std::abs(expected))
          << "sample " << i;
    }
  }
}

TEST(Uff58Export, PrintsAFractionalRateIncrementToSevenDigits) {
  TempDir dir;
  const double rate_hz = 511.987;  // a measured clock
  write_recording_uff58(test_recording(rate_hz, 8), dir.file("r.uff"));
  const std::vector<Dataset> datasets = parse_universal_file(read_file(dir.file("r.uff")));
  ASSERT_EQ(datasets.size(), 5u);
  // E13.5 with 7 significant digits: half a unit of the 7th digit, ≤ 5e-7 relative.
  EXPECT_NEAR(real_field(datasets[1].records[6], 43, 13), 1.0 / rate_hz, 5e-7 / rate_hz);
  EXPECT_EQ(datasets[1].records.size(), 11u + 2u);  // 8 values: two full lines
  // Without a fixed date, ID line 3 holds now as DD-MMM-YY HH:MM:SS.
  EXPECT_TRUE(is_uff_date(trimmed(datasets[1].records[2]))) << datasets[1].records[2];
}

TEST(Uff58Export, ThrowsInputErrorOnANonFiniteSampleAndWritesNothing) {
  TempDir dir;
  Recording recording = test_recording(512.0, 100);
  recording.samples_si(64, 1) = std::numeric_limits<double>::quiet_NaN();
  const std::string path = dir.file("gap.uff");
  const std::string message = input_error_of([&] { write_recording_uff58(recording, path); });
  EXPECT_NE(message.find("gap.uff: channel y: sample 64 (t = 0.125 s) is not finite"),
            std::string::npos)
      << message;
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(Uff58Export, ThrowsInputErrorOnBadOptionsAndUnwritablePaths) {
  TempDir dir;
  const Recording recording = test_recording(512.0, 10);
  Uff58Options options;
  options.direction = 7;
  EXPECT_NE(input_error_of([&] {
              write_recording_uff58(recording, dir.file("a.uff"), options);
            }).find("a.uff: direction 7"),
            std::string::npos);
  const std::string missing = dir.file("none/a.uff");
  EXPECT_NE(input_error_of([&] { write_recording_uff58(recording, missing); }).find(missing),
            std::string::npos);
  std::filesystem::create_directory(dir.file("taken.uff"));
  EXPECT_NE(input_error_of([&] {
              write_recording_uff58(recording, dir.file("taken.uff"));
            }).find("taken.uff: cannot write"),
            std::string::npos);
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++entries;
  }
  EXPECT_EQ(entries, 1u);  // the directory in the way; no temporary left
}

}  // namespace
}  // namespace oscilab::daq
