// HDF5 through libhdf5: a Terra15 DAS file, and files h5py writes at test time.
#include <gtest/gtest.h>

#include "tests/instrument_files.h"

#include <cmath>
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

const std::string kTerra15 =
    oscilab::testing::instrument_files() + "/hdf5/terra15_v5_test_file.hdf5";

const SignalFileReader& reader() { return dynamic_cast<const SignalFileReader&>(hdf5_format()); }

Sidecar one_channel(double rate_hz, const std::string& source, int column) {
  Sidecar sidecar;
  sidecar.sample_rate_hz = rate_hz;
  ChannelInfo channel = testing::channel("v", ChannelRole::Mass, Quantity::Velocity, "m/s");
  channel.source = source;
  channel.column = column;
  sidecar.channels.push_back(channel);
  return sidecar;
}

TEST(Hdf5Format, ReadsTheTerra15FileAsReadme) {
  OSCILAB_SKIP_WITHOUT_INSTRUMENT_FILES();
  EXPECT_EQ(&format_for_file(kTerra15), &hdf5_format());
  const FileContents contents = hdf5_format().describe(kTerra15);
  EXPECT_EQ(contents.container.rfind("HDF5", 0), 0u);
  const FileSignal& data = signal_named(contents, "/data_product/data");
  EXPECT_EQ(data.sample_count, 2060);
  EXPECT_EQ(data.columns, 43);
  EXPECT_EQ(data.stored_type, "float32");
  ASSERT_TRUE(data.sample_rate_hz.has_value());
  EXPECT_NEAR(*data.sample_rate_hz, 1.0 / 0.00031096, 1e-9);  // README: dT 0.00031096 s
  EXPECT_EQ(data.properties.at("sample_rate_from"),
            "attribute \"dT\" of /data_product/data (0.00031096 s)");
  EXPECT_EQ(signal_named(contents, "/data_product/posix_time").sample_count, 2060);
  EXPECT_FALSE(signal_named(contents, "/data_product/posix_time").sample_rate_hz.has_value());
  EXPECT_EQ(contents.properties.at("attributes").at("data_product"), "velocity");

  // README: RMS 1.04e-4 m/s over the whole matrix (h5py with NumPy: 1.0411521e-4).
  double sum = 0.0;
  for (int c = 0; c < 43; ++c) {
    const std::vector<double> column = reader().read_signal(kTerra15, data, c);
    ASSERT_EQ(column.size(), 2060u);
    for (const double value : column) sum += value * value;
  }
  EXPECT_NEAR(std::sqrt(sum / (2060.0 * 43.0)), 1.0411521438784377e-4, 1e-12);

  // Mapped at the file's rate; a sidecar rate 1 % off is refused.
  const Recording recording =
      read_recording(kTerra15, one_channel(1.0 / 0.00031096, "/data_product/data", 7));
  EXPECT_EQ(recording.samples_stored.rows(), 2060);
  EXPECT_NE(input_error_of([&] {
              read_recording(kTerra15, one_channel(1.01 / 0.00031096, "/data_product/data", 7));
            }).find("is sampled at 3215.85 Hz"),
            std::string::npos);
}

TEST(Hdf5Format, ReadsH5pyDatasetsValueByValueWithRatesAndUnits) {
  const TempDir dir;
  const std::string path = dir.file("run.h5");
  const std::vector<double> a = varied_values(100, 1, 2.0);
  const std::vector<double> be = varied_values(100, 2, 1000.0);
  std::vector<double> counts(100);
  for (std::size_t i = 0; i < 100; ++i) counts[i] = std::round(be[i] * 20.0);
  std::vector<double> singles = varied_values(100, 3, 1.0);
  for (double& value : singles) value = static_cast<float>(value);
  const std::vector<double> matrix = varied_values(100 * 4, 4, 1.0);  // 100 x 4
  const std::vector<double> wide = varied_values(3 * 100, 5, 1.0);    // 3 x 100
  testing::write_fixture(
      dir, {{"format", "hdf5"},
            {"path", path},
            {"groups",
             {{{"path", "/run"}, {"attrs", {{"sample_rate_hz", 500.0}}}},
              {{"path", "/run/deep/er"}, {"attrs", json::object()}},
              {{"path", "/other"}, {"attrs", {{"wf_increment", 0.004}}}}}},
            {"variables",
             {fixture_variable("/run/deep/er/a", "float64", {100}, a, {{"units", "m/s^2"}}),
              fixture_variable("/run/be", "float64", {100}, be, {{"dt", 0.001}}, ">"),
              fixture_variable("/run/counts", "int32", {100}, counts, json::object(), ">"),
              fixture_variable("/other/single", "float32", {100}, singles, {{"unit", "N"}}),
              fixture_variable("/other/matrix", "float64", {100, 4}, matrix),
              fixture_variable("/other/wide", "float64", {3, 100}, wide, {{"fs", -5.0}})}},
            {"special",
             {{{"name", "/odd/compound"}, {"kind", "compound"}},
              {{"name", "/odd/string"}, {"kind", "string"}},
              {{"name", "/odd/vlen"}, {"kind", "vlen"}},
              {{"name", "/odd/cube"}, {"kind", "3d"}},
              {{"name", "/odd/scalar"}, {"kind", "scalar"}},
              {{"name", "/odd/bools"}, {"kind", "enum"}},
              {{"name", "/odd/soft"}, {"kind", "soft"}, {"target", "/run/be"}},
              {{"name", "/odd/external"}, {"kind", "external"}},
              {{"name", "/odd/elsewhere"}, {"kind", "external_data"}},
              {{"name", "/odd/empty"}, {"kind", "empty"}},
              {{"name", "/run/deep/er/loop"}, {"kind", "cycle"}, {"target", "/run"}}}}});
  const FileContents contents = hdf5_format().describe(path);
  const auto read = [&](const std::string& name, int column = -1) {
    return reader().read_signal(path, signal_named(contents, name), column);
  };
  EXPECT_EQ(read("/run/deep/er/a"), a);
  EXPECT_EQ(signal_named(contents, "/run/deep/er/a").unit, "m/s^2");
  EXPECT_EQ(*signal_named(contents, "/run/deep/er/a").sample_rate_hz, 500.0);  // from /run
  EXPECT_EQ(signal_named(contents, "/run/deep/er/a").properties.at("sample_rate_from"),
            "attribute \"sample_rate_hz\" of /run (500 Hz)");
  EXPECT_EQ(read("/run/be"), be);
  EXPECT_EQ(signal_named(contents, "/run/be").properties.at("byte_order"), "big-endian");
  EXPECT_EQ(*signal_named(contents, "/run/be").sample_rate_hz, 1000.0);  // its own dt
  EXPECT_EQ(read("/run/counts"), counts);
  EXPECT_EQ(signal_named(contents, "/run/counts").stored_type, "int32");
  EXPECT_EQ(read("/other/single"), singles);
  EXPECT_EQ(signal_named(contents, "/other/single").unit, "N");
  EXPECT_EQ(*signal_named(contents, "/other/single").sample_rate_hz, 250.0);  // wf_increment
  const FileSignal& m = signal_named(contents, "/other/matrix");
  EXPECT_EQ(m.columns, 4);
  EXPECT_EQ(m.properties.at("column_k_is"), "data[:, k]");
  for (int c = 0; c < 4; ++c) {
    const std::vector<double> column = read("/other/matrix", c);
    for (std::size_t r = 0; r < 100; ++r) ASSERT_EQ(column[r], matrix[r * 4 + c]);
  }
  const FileSignal& w = signal_named(contents, "/other/wide");
  EXPECT_EQ(w.sample_count, 100);
  EXPECT_EQ(w.columns, 3);
  EXPECT_EQ(w.properties.at("column_k_is"), "data[k, :]");
  EXPECT_EQ(read("/other/wide", 2), std::vector<double>(wide.begin() + 200, wide.end()));
  EXPECT_FALSE(w.sample_rate_hz.has_value());  // fs -5 is no rate
  EXPECT_EQ(w.properties.at("sample_rate_ignored"),
            "attribute \"fs\" of /other/wide is -5 Hz, not a positive rate");

  std::map<std::string, std::string> skipped;
  for (const json& item : contents.properties.at("skipped"))
    skipped[item.at("name")] = item.at("reason");
  EXPECT_EQ(skipped["/odd/compound"], "not numeric: compound type");
  EXPECT_EQ(skipped["/odd/string"], "not numeric: strings");
  EXPECT_EQ(skipped["/odd/vlen"], "not numeric: variable-length type");
  EXPECT_EQ(skipped["/odd/cube"], "3 dimensions, not 1 or 2");
  EXPECT_EQ(skipped["/odd/scalar"], "a single value (scalar)");
  EXPECT_EQ(skipped["/odd/bools"], "not numeric: enumeration (booleans are one)");
  EXPECT_EQ(skipped["/odd/soft"], "a soft link (not followed)");
  EXPECT_EQ(skipped["/odd/external"], "an external or user-defined link (not followed)");
  EXPECT_EQ(skipped["/run/deep/er/loop"], "another link to an object listed already");
  EXPECT_EQ(skipped["/odd/elsewhere"], "its values are in external files");
  EXPECT_EQ(signal_named(contents, "/odd/empty").sample_count, 0);
  EXPECT_NE(input_error_of([&] {
              read_recording(path, one_channel(1000.0, "/odd/empty", -1));
            }).find("\"/odd/empty\" holds no samples"),
            std::string::npos);

  // Refusals through a sidecar.
  EXPECT_EQ(input_error_of([&] { read_recording(path, one_channel(1000.0, "/run/be", -1)); }), "");
  EXPECT_NE(input_error_of([&] {
              read_recording(path, one_channel(1000.0, "/run/nope", -1));
            }).find("which the file does not hold"),
            std::string::npos);
  EXPECT_EQ(input_error_of([&] { read_recording(path, one_channel(1000.0, "/odd/string", -1)); }),
            path +
                ": channel \"v\" of the sidecar given reads \"/odd/string\", which is not a "
                "signal: not numeric: strings");
  EXPECT_NE(input_error_of([&] {
              read_recording(path, one_channel(990.0, "/run/be", -1));
            }).find("is sampled at 1000 Hz"),
            std::string::npos);
}

// A time dataset checked against the rate, and a user block (the HDF5 signature at 512).
TEST(Hdf5Format, ChecksATimeDatasetAndReadsFilesWithAUserBlock) {
  const TempDir dir;
  const std::string path = dir.file("ub.hdf5");
  std::vector<double> t(50);
  std::vector<double> t_off(50);
  for (std::size_t i = 0; i < 50; ++i) {
    t[i] = 10.0 + static_cast<double>(i) / 200.0;
    t_off[i] = 10.0 + static_cast<double>(i) / 190.0;
  }
  const std::vector<double> x = varied_values(50, 6, 1.0);
  testing::write_fixture(dir, {{"format", "hdf5"},
                               {"path", path},
                               {"userblock", 1024},
                               {"compress", true},
                               {"variables",
                                {fixture_variable("/t", "float64", {50}, t),
                                 fixture_variable("/t_off", "float64", {50}, t_off),
                                 fixture_variable("/x", "float32", {50}, x)}}});
  EXPECT_EQ(&format_for_file(path), &hdf5_format());  // by extension: the signature is at 1024
  EXPECT_NE(hdf5_format().describe(path).container.find("1024-byte user block"), std::string::npos);
  Sidecar sidecar = one_channel(200.0, "/x", -1);
  sidecar.time = SignalTime{"/t", -1};
  const Recording recording = read_recording(path, sidecar);
  for (Eigen::Index r = 0; r < 50; ++r) {
    ASSERT_EQ(recording.samples_stored(r, 0), static_cast<double>(static_cast<float>(x[r])));
  }
  sidecar.time = SignalTime{"/t_off", -1};
  EXPECT_NE(input_error_of([&] { read_recording(path, sidecar); }).find("\"/t_off\", sample"),
            std::string::npos);
}

TEST(Hdf5Format, RefusesWhatIsNotHdf5InOneLine) {
  const TempDir dir;
  const std::string path = dir.file("bad.h5");
  testing::write_file(path, std::string("\x89HDF\r\n\x1a\n", 8) + std::string(100, '\0'));
  const std::string error = input_error_of([&] { hdf5_format().describe(path); });
  EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_TRUE(hdf5_format().matches_signature(std::string("\x89HDF\r\n\x1a\n", 8)));
  EXPECT_FALSE(hdf5_format().matches_extension(".nc"));
  EXPECT_TRUE(hdf5_format().matches_extension(".he5"));
}

// The same stored values in an HDF5 file and a 16-bit WAV file: the same samples, bit for bit.
TEST(Hdf5Format, MapsToTheSameSamplesAsAWavFileOfTheSameValues) {
  const TempDir dir;
  std::vector<std::int16_t> interleaved;
  std::vector<double> matrix;  // 200 x 2
  const std::vector<double> va = varied_values(200, 7, 20000.0);
  const std::vector<double> vb = varied_values(200, 8, 9000.0);
  for (std::size_t i = 0; i < 200; ++i) {
    matrix.push_back(std::round(va[i]));
    matrix.push_back(std::round(vb[i]));
    interleaved.push_back(static_cast<std::int16_t>(matrix[2 * i]));
    interleaved.push_back(static_cast<std::int16_t>(matrix[2 * i + 1]));
  }
  testing::write_file(dir.file("run.wav"), testing::pcm16_wav(1000, 2, interleaved));
  testing::write_fixture(
      dir, {{"format", "hdf5"},
            {"path", dir.file("run.h5")},
            {"variables",
             {fixture_variable("/m", "int16", {200, 2}, matrix, {{"sample_rate", 1000.0}})}}});
  Sidecar sidecar = one_channel(1000.0, "/m", 0);
  ChannelInfo second = testing::channel("f", ChannelRole::Force, Quantity::Force, "N", 0.01, 0.5);
  second.source = "/m";
  second.column = 1;
  sidecar.channels.push_back(second);
  sidecar.channels[0].scale = 1e-4;
  const Recording from_wav = read_recording(dir.file("run.wav"), sidecar);
  const Recording from_h5 = read_recording(dir.file("run.h5"), sidecar);
  ASSERT_EQ(from_h5.samples_si.rows(), 200);
  EXPECT_TRUE(from_h5.samples_si == from_wav.samples_si);
}

}  // namespace
}  // namespace oscilab::daq
