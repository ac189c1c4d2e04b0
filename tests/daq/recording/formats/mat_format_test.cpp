// MATLAB MAT-files through matio: a real instrument's file, files SciPy and h5py write at test
// time, and a Level 5 file built byte by byte.
#include <gtest/gtest.h>

#include "tests/instrument_files.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "daq/recording/format_reader.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/mat_hdf5_fixture.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using nlohmann::json;
using testing::fixture_variable;
using testing::input_error_of;
using testing::signal_named;
using testing::TempDir;
using testing::varied_values;

const std::string kSilverbox = oscilab::testing::instrument_files() + "/mat/SNLS80mV.mat";
constexpr double kSilverboxRateHz = 1e7 / 16384.0;  // 10^7 / 2^14, the benchmark's documentation

const SignalFileReader& mat_reader() { return dynamic_cast<const SignalFileReader&>(mat_format()); }

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double value : values) sum += value * value;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

Sidecar sidecar_of(double rate_hz, const std::vector<std::pair<std::string, int>>& sources) {
  Sidecar sidecar;
  sidecar.sample_rate_hz = rate_hz;
  const Quantity quantities[] = {Quantity::Acceleration, Quantity::Displacement, Quantity::Force};
  const ChannelRole roles[] = {ChannelRole::Base, ChannelRole::Mass, ChannelRole::Force};
  const char* units[] = {"m/s^2", "m", "N"};
  for (std::size_t i = 0; i < sources.size(); ++i) {
    ChannelInfo channel =
        testing::channel("ch" + std::to_string(i), roles[i % 3], quantities[i % 3], units[i % 3]);
    channel.source = sources[i].first;
    channel.column = sources[i].second;
    sidecar.channels.push_back(channel);
  }
  return sidecar;
}

TEST(MatFormat, DescribesTheSilverboxFileAsReadme) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  const FileContents contents = mat_format().describe(kSilverbox);
  EXPECT_EQ(contents.container, "MATLAB 5.0 MAT-file (v5, uncompressed)");
  EXPECT_EQ(contents.properties.at("header").get<std::string>().rfind("MATLAB 5.0 MAT-file", 0),
            0u);
  ASSERT_EQ(contents.file_signals.size(), 4u);
  for (const char* name : {"V1", "V2"}) {
    const FileSignal& signal = signal_named(contents, name);
    EXPECT_EQ(signal.sample_count, 131072);
    EXPECT_EQ(signal.columns, 1);
    EXPECT_EQ(signal.stored_type, "float64");
    EXPECT_FALSE(signal.sample_rate_hz.has_value());  // not in the file
  }
  // Ovld1 is class double stored as miUINT8 (README): its class stands for its type.
  const FileSignal& flag = signal_named(contents, "Ovld1");
  EXPECT_EQ(flag.stored_type, "float64");
  EXPECT_EQ(flag.sample_count, 1);
}

// RMS and first samples measured with SciPy 1.10 (scipy.io.loadmat) on the same file.
TEST(MatFormat, ReadsTheSilverboxVoltagesAsSciPyDoes) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  const FileContents contents = mat_format().describe(kSilverbox);
  const std::vector<double> v1 =
      mat_reader().read_signal(kSilverbox, signal_named(contents, "V1"), -1);
  const std::vector<double> v2 =
      mat_reader().read_signal(kSilverbox, signal_named(contents, "V2"), -1);
  ASSERT_EQ(v1.size(), 131072u);
  ASSERT_EQ(v2.size(), 131072u);
  EXPECT_NEAR(rms(v1), 0.02277538091174399, 1e-15);  // the sum's rounding only
  EXPECT_NEAR(rms(v2), 0.053375704560125706, 1e-15);
  EXPECT_NEAR(v1[0], 0.00577562, 5e-9);  // SciPy's printout, 6 significant digits
  EXPECT_NEAR(v2[4], -0.00396474, 5e-9);
  const std::vector<double> flag =
      mat_reader().read_signal(kSilverbox, signal_named(contents, "Ovld1"), -1);
  EXPECT_EQ(flag, std::vector<double>{0.0});

  // Through a sidecar at the documented rate: the same values.
  const Recording recording =
      read_recording(kSilverbox, sidecar_of(kSilverboxRateHz, {{"V1", -1}, {"V2", -1}}));
  ASSERT_EQ(recording.samples_stored.rows(), 131072);
  EXPECT_EQ(recording.samples_stored(1000, 0), v1[1000]);
  EXPECT_EQ(recording.samples_stored(1000, 1), v2[1000]);
  EXPECT_EQ(recording.container, "MATLAB 5.0 MAT-file (v5, uncompressed)");
}

// A Level 5 file built from "MAT-File Format" (MathWorks): a double-class 1x4 matrix whose
// values are stored as miUINT8, as the Silverbox file stores its overload flags. matio converts
// them to double.
TEST(MatFormat, ConvertsADoubleStoredAsUint8) {
  std::string bytes = std::string("MATLAB 5.0 MAT-file, hand-made test file").append(116 - 40, ' ');
  bytes.append(8, '\0');                                // subsystem data offset: none
  testing::append_le<std::uint16_t>(bytes, 0x0100);     // version
  bytes += "IM";                                        // little-endian writer
  testing::append_le<std::uint32_t>(bytes, 14);         // miMATRIX
  testing::append_le<std::uint32_t>(bytes, 64);         // bytes that follow in the element
  testing::append_le<std::uint32_t>(bytes, 6);          // array flags: miUINT32
  testing::append_le<std::uint32_t>(bytes, 8);          //   8 bytes
  testing::append_le<std::uint32_t>(bytes, 6);          //   mxDOUBLE_CLASS, no flags
  testing::append_le<std::uint32_t>(bytes, 0);          //   nzmax (sparse only)
  testing::append_le<std::uint32_t>(bytes, 5);          // dimensions: miINT32
  testing::append_le<std::uint32_t>(bytes, 8);          //   8 bytes
  testing::append_le<std::int32_t>(bytes, 1);           //   1 row
  testing::append_le<std::int32_t>(bytes, 4);           //   4 columns
  testing::append_le<std::uint32_t>(bytes, 1);          // array name: miINT8
  testing::append_le<std::uint32_t>(bytes, 4);          //   4 bytes
  bytes += std::string("flag\0\0\0\0", 8);              //   "flag", padded to 8
  testing::append_le<std::uint32_t>(bytes, 2);          // real part: miUINT8
  testing::append_le<std::uint32_t>(bytes, 4);          //   4 bytes
  bytes += std::string("\x00\x01\xff\x07\0\0\0\0", 8);  //   0, 1, 255, 7, padded to 8
  const TempDir dir;
  const std::string path = dir.file("flag.mat");
  testing::write_file(path, bytes);
  const FileContents contents = mat_format().describe(path);
  ASSERT_EQ(contents.file_signals.size(), 1u);
  EXPECT_EQ(contents.file_signals[0].stored_type, "float64");
  EXPECT_EQ(contents.file_signals[0].sample_count, 4);
  EXPECT_EQ(mat_reader().read_signal(path, contents.file_signals[0], -1),
            (std::vector<double>{0.0, 1.0, 255.0, 7.0}));
}

// Every numeric class SciPy writes, row and column vectors, a matrix with its samples down the
// rows and one with them along the rows; compressed and not.
void check_numeric_variables(bool compress) {
  const TempDir dir;
  const std::string path = dir.file("run.mat");
  const std::vector<double> row = varied_values(50, 1, 2.0);
  const std::vector<double> column = varied_values(40, 2, 1e-3);
  std::vector<double> counts(30);
  for (std::size_t i = 0; i < counts.size(); ++i)
    counts[i] = std::round(varied_values(30, 3, 25000.0)[i]);
  std::vector<double> singles = varied_values(20, 4, 5.0);
  for (double& value : singles) value = static_cast<float>(value);
  // A 3 x 25 matrix: samples along the rows (each row is one "column").
  const std::vector<double> wide = varied_values(75, 5, 1.0);
  std::vector<double> u8(10);
  for (std::size_t i = 0; i < u8.size(); ++i) u8[i] = static_cast<double>(i * 25);
  const json spec = {
      {"format", "mat5"},
      {"path", path},
      {"compress", compress},
      {"variables",
       {fixture_variable("row", "float64", {1, 50}, row),
        fixture_variable("column", "float64", {40, 1}, column),
        fixture_variable("counts", "int16", {1, 30}, counts),
        fixture_variable("single", "float32", {20, 1}, singles),
        fixture_variable("wide", "float64", {3, 25}, wide),
        fixture_variable("bytes", "uint8", {1, 10}, u8),
        fixture_variable("big", "int64", {1, 3}, {-9007199254740992.0, 0.0, 9007199254740992.0}),
        fixture_variable("ubig", "uint32", {1, 2}, {0.0, 4294967295.0})}},
      {"special",
       {{{"name", "c"}, {"kind", "cell"}},
        {{"name", "s"}, {"kind", "struct"}},
        {{"name", "text"}, {"kind", "char"}},
        {{"name", "sp"}, {"kind", "sparse"}},
        {{"name", "z"}, {"kind", "complex"}},
        {{"name", "cube"}, {"kind", "3d"}},
        {{"name", "nothing"}, {"kind", "empty"}},
        {{"name", "mask"}, {"kind", "logical"}}}}};
  testing::write_fixture(dir, spec);
  const FileContents contents = mat_format().describe(path);
  EXPECT_EQ(contents.container, compress ? "MATLAB 5.0 MAT-file (v5, compressed)"
                                         : "MATLAB 5.0 MAT-file (v5, uncompressed)");
  const auto read = [&](const std::string& name, int column = -1) {
    return mat_reader().read_signal(path, signal_named(contents, name), column);
  };
  EXPECT_EQ(read("row"), row);
  EXPECT_EQ(read("column"), column);
  EXPECT_EQ(read("counts"), counts);
  EXPECT_EQ(signal_named(contents, "counts").stored_type, "int16");
  EXPECT_EQ(read("single"), singles);
  EXPECT_EQ(signal_named(contents, "single").stored_type, "float32");
  EXPECT_EQ(read("bytes"), u8);
  EXPECT_EQ(read("big"), (std::vector<double>{-9007199254740992.0, 0.0, 9007199254740992.0}));
  EXPECT_EQ(read("ubig"), (std::vector<double>{0.0, 4294967295.0}));
  const FileSignal& wide_signal = signal_named(contents, "wide");
  EXPECT_EQ(wide_signal.sample_count, 25);
  EXPECT_EQ(wide_signal.columns, 3);
  EXPECT_EQ(wide_signal.properties.at("column_k_is"), "row k of the matrix");
  for (int r = 0; r < 3; ++r) {
    EXPECT_EQ(read("wide", r),
              std::vector<double>(wide.begin() + 25 * r, wide.begin() + 25 * (r + 1)));
  }
  EXPECT_EQ(read("mask"), (std::vector<double>{1.0, 0.0, 1.0, 1.0}));
  EXPECT_EQ(signal_named(contents, "mask").stored_type, "logical");
  EXPECT_EQ(signal_named(contents, "nothing").sample_count, 0);

  std::map<std::string, std::string> skipped;
  for (const json& item : contents.properties.at("skipped")) {
    skipped[item.at("name")] = item.at("reason");
  }
  EXPECT_EQ(skipped.size(), 6u) << contents.properties.dump();
  EXPECT_EQ(skipped["c"], "it is a cell array, not a numeric matrix");
  EXPECT_EQ(skipped["s"], "it is a struct, not a numeric matrix");
  EXPECT_EQ(skipped["text"], "it is a char array, not a numeric matrix");
  EXPECT_EQ(skipped["sp"], "it is a sparse matrix, not a numeric matrix");
  EXPECT_EQ(skipped["z"], "it is complex");
  EXPECT_EQ(skipped["cube"], "it has 3 dimensions, not 2");
}

TEST(MatFormat, ReadsSciPysUncompressedVariablesValueByValue) { check_numeric_variables(false); }
TEST(MatFormat, ReadsSciPysCompressedVariablesValueByValue) { check_numeric_variables(true); }

// An N x 3 matrix [t x1 x2]: column 0 is the time, checked against the rate.
TEST(MatFormat, ReadsAMatrixWithItsTimeColumn) {
  const TempDir dir;
  const std::string path = dir.file("m.mat");
  const double rate_hz = 512.0;
  const std::vector<double> x1 = varied_values(200, 6, 3.0);
  const std::vector<double> x2 = varied_values(200, 7, 0.01);
  const auto matrix_with_time = [&](double time_rate_hz) {
    std::vector<double> m;
    for (std::size_t i = 0; i < 200; ++i) {
      m.insert(m.end(), {static_cast<double>(i) / time_rate_hz, x1[i], x2[i]});
    }
    return m;
  };
  testing::write_fixture(
      dir, {{"format", "mat5"},
            {"path", path},
            {"variables",
             {fixture_variable("M", "float64", {200, 3}, matrix_with_time(rate_hz)),
              fixture_variable("off", "float64", {200, 3}, matrix_with_time(rate_hz * 1.01)),
              fixture_variable("short", "float64", {1, 3}, {1, 2, 3})}}});
  Sidecar sidecar = sidecar_of(rate_hz, {{"M", 1}, {"M", 2}});
  sidecar.time = SignalTime{"M", 0};
  const Recording recording = read_recording(path, sidecar);
  ASSERT_EQ(recording.samples_stored.rows(), 200);
  for (Eigen::Index r = 0; r < 200; ++r) {
    ASSERT_EQ(recording.samples_stored(r, 0), x1[r]);
    ASSERT_EQ(recording.samples_stored(r, 1), x2[r]);
  }
  EXPECT_EQ(signal_named(mat_format().describe(path), "M").columns, 3);

  // Refusals: a time 1 % off the rate, a column the matrix lacks, a matrix without a column.
  sidecar.time = SignalTime{"off", 0};
  EXPECT_NE(input_error_of([&] { read_recording(path, sidecar); }).find("\"off\", sample"),
            std::string::npos);
  sidecar.time.reset();
  sidecar.channels[0].column = 3;
  EXPECT_NE(input_error_of([&] { read_recording(path, sidecar); }).find("reads column 3"),
            std::string::npos);
  sidecar.channels[0].column = -1;
  EXPECT_NE(input_error_of([&] { read_recording(path, sidecar); }).find("must pick one"),
            std::string::npos);
  sidecar.channels[0].column = 1;
  sidecar.channels[1].source = "short";
  sidecar.channels[1].column = -1;
  EXPECT_NE(input_error_of([&] { read_recording(path, sidecar); }).find("one length"),
            std::string::npos);
}

TEST(MatFormat, RefusesMissingNonNumericAndEmptyVariables) {
  const TempDir dir;
  const std::string path = dir.file("r.mat");
  testing::write_fixture(
      dir, {{"format", "mat5"},
            {"path", path},
            {"variables", {fixture_variable("x", "float64", {1, 4}, {1, 2, 3, 4})}},
            {"special",
             {{{"name", "text"}, {"kind", "char"}}, {{"name", "nothing"}, {"kind", "empty"}}}}});
  const auto error_for = [&](const std::string& source) {
    return input_error_of([&] { read_recording(path, sidecar_of(100.0, {{source, -1}})); });
  };
  EXPECT_EQ(error_for("x"), "");
  EXPECT_NE(error_for("y").find("which the file does not hold (it holds \"x\""), std::string::npos)
      << error_for("y");
  EXPECT_EQ(error_for("text"),
            path +
                ": channel \"ch0\" of the sidecar given reads \"text\", which is not a signal: "
                "it is a char array, not a numeric matrix");
  EXPECT_NE(error_for("nothing").find("\"nothing\" holds no samples"), std::string::npos);
}

TEST(MatFormat, RefusesFilesMatioCannotOpen) {
  const TempDir dir;
  const std::string path = dir.file("bad.mat");
  testing::write_file(path, std::string("MATLAB 5.0 MAT-file").append(200, '\x7f'));
  const std::string error = input_error_of([&] { mat_format().describe(path); });
  EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  testing::write_file(path, "");
  EXPECT_NE(input_error_of([&] { mat_format().describe(path); }), "");
  EXPECT_NE(input_error_of([&] { mat_format().describe(dir.file("absent.mat")); }), "");
}

// MAT v7.3 (HDF5 behind the MATLAB header), as h5py writes it with MATLAB's attributes; read
// through the HDF5 reader's code (Debian's matio crashes on v7.3 files).
TEST(MatFormat, ReadsV73Files) {
  const TempDir dir;
  const std::string path = dir.file("v73.mat");
  const std::vector<double> row = varied_values(60, 8, 1.5);
  const std::vector<double> matrix = varied_values(40 * 3, 9, 1.0);  // 40 x 3, row-major
  std::vector<double> counts(10);
  for (std::size_t i = 0; i < counts.size(); ++i) counts[i] = -500.0 + 111.0 * i;
  testing::write_fixture(dir, {{"format", "mat73"},
                               {"path", path},
                               {"variables",
                                {fixture_variable("row", "float64", {1, 60}, row),
                                 fixture_variable("M", "float64", {40, 3}, matrix),
                                 fixture_variable("counts", "int16", {10, 1}, counts)}},
                               {"special",
                                {{{"name", "text"}, {"kind", "char"}},
                                 {{"name", "s"}, {"kind", "struct"}},
                                 {{"name", "nothing"}, {"kind", "empty"}},
                                 {{"name", "plain"}, {"kind", "plain"}}}}});
  EXPECT_EQ(&format_for_file(path), &mat_format());
  const FileContents contents = mat_format().describe(path);
  EXPECT_EQ(contents.container,
            "MATLAB 7.3 MAT-file (HDF5, superblock version 0, 512-byte user block)");
  EXPECT_EQ(mat_reader().read_signal(path, signal_named(contents, "row"), -1), row);
  EXPECT_EQ(mat_reader().read_signal(path, signal_named(contents, "counts"), -1), counts);
  const FileSignal& m = signal_named(contents, "M");
  EXPECT_EQ(m.sample_count, 40);
  EXPECT_EQ(m.columns, 3);
  EXPECT_EQ(m.properties.at("column_k_is"), "column k of the matrix");
  const std::vector<double> column2 = mat_reader().read_signal(path, m, 2);
  for (std::size_t r = 0; r < 40; ++r) EXPECT_EQ(column2[r], matrix[r * 3 + 2]) << r;
  EXPECT_EQ(signal_named(contents, "nothing").sample_count, 0);
  std::map<std::string, std::string> skipped;
  for (const json& item : contents.properties.at("skipped")) {
    skipped[item.at("name")] = item.at("reason");
  }
  EXPECT_EQ(skipped.size(), 3u) << contents.properties.dump();
  EXPECT_EQ(skipped["text"], "it is of class char, not a numeric matrix");
  EXPECT_EQ(skipped["s"], "it is of class struct, not a numeric matrix");
  EXPECT_EQ(skipped["plain"], "it has no MATLAB_class");
  EXPECT_NE(input_error_of([&] {
              read_recording(path, sidecar_of(100.0, {{"text", -1}}));
            }).find("which is not a signal: it is of class char"),
            std::string::npos);
}

TEST(MatFormat, IsChosenBySignatureThenExtension) {
  const TempDir dir;
  const std::string path = dir.file("data.bin");
  testing::write_fixture(dir, {{"format", "mat5"},
                               {"path", path},
                               {"variables", {fixture_variable("x", "float64", {1, 2}, {1, 2})}}});
  EXPECT_EQ(&format_for_file(path), &mat_format());
  EXPECT_TRUE(mat_format().matches_extension(".mat"));
  EXPECT_FALSE(mat_format().matches_signature("MATLAB 6.0 MAT-file"));
  EXPECT_FALSE(mat_format().matches_extension(".h5"));
}

// The same stored values in a MAT-file and in a WAV file (16-bit PCM, built from the WAV
// specification) give the same SI samples, bit for bit.
TEST(MatFormat, MapsToTheSameSamplesAsAWavFileOfTheSameValues) {
  const TempDir dir;
  std::vector<std::int16_t> interleaved;
  std::vector<double> a;
  std::vector<double> b;
  const std::vector<double> va = varied_values(300, 10, 20000.0);
  const std::vector<double> vb = varied_values(300, 11, 9000.0);
  for (std::size_t i = 0; i < 300; ++i) {
    a.push_back(std::round(va[i]));
    b.push_back(std::round(vb[i]));
    interleaved.push_back(static_cast<std::int16_t>(a.back()));
    interleaved.push_back(static_cast<std::int16_t>(b.back()));
  }
  testing::write_file(dir.file("run.wav"), testing::pcm16_wav(1000, 2, interleaved));
  testing::write_fixture(dir, {{"format", "mat5"},
                               {"path", dir.file("run.mat")},
                               {"compress", true},
                               {"variables",
                                {fixture_variable("a", "int16", {300, 1}, a),
                                 fixture_variable("b", "int16", {1, 300}, b)}}});
  Sidecar sidecar = sidecar_of(1000.0, {{"a", -1}, {"b", -1}});
  sidecar.channels[0].scale = 0.001;
  sidecar.channels[1].scale = 2e-6;
  sidecar.channels[1].offset = 1e-3;
  const Recording from_wav = read_recording(dir.file("run.wav"), sidecar);
  const Recording from_mat = read_recording(dir.file("run.mat"), sidecar);
  ASSERT_EQ(from_mat.samples_si.rows(), 300);
  EXPECT_TRUE(from_mat.samples_si == from_wav.samples_si);
  EXPECT_TRUE(from_mat.samples_stored == from_wav.samples_stored);
}

}  // namespace
}  // namespace oscilab::daq
