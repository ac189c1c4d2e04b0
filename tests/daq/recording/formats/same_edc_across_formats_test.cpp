// The same stored values in every format reach the same EDC table as the FLAC they came from, to
// the last bit: the bundled positive-well sample (134 401 24-bit counts per channel) written as a
// 64-bit WAV and a CSV by Oscilab's writers, as a TDMS file and a big-endian float64 UFF 58b built
// byte by byte from their published descriptions, as a MATLAB v5 file, a MATLAB v7.3 file and
// an HDF5 file written by SciPy and h5py, and through Oscilab's own MATLAB export. Each is mapped
// by a sidecar that names its signals, read, and analysed by the same offline pipeline.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "analysis/pipeline/offline_analysis.h"
#include "daq/export/mat_export.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/recording/recording.h"
#include "tests/daq/recording/formats/mat_hdf5_fixture.h"
#include "tests/daq/recording/formats/tdms_test_bytes.h"
#include "tests/daq/recording/formats/uff_test_files.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::TempDir;

const Recording& flac() {
  static const Recording recording =
      read_recording(OSCILAB_SOURCE_DIR "/samples/stepped_positive.flac");
  return recording;
}

std::vector<double> stored_column(int c) {
  const Eigen::VectorXd column = flac().samples_stored.col(c);
  return {column.data(), column.data() + column.size()};
}

// The FLAC's sidecar with each channel reading `sources[c]` of a file of named signals.
Sidecar mapped_sidecar(const std::vector<std::string>& sources) {
  Sidecar sidecar = flac().sidecar;
  for (std::size_t c = 0; c < sources.size(); ++c) sidecar.channels[c].source = sources[c];
  return sidecar;
}

// One TDMS segment: group "rig", channels "base_acc" and "y", contiguous float64 at 512 Hz.
std::string tdms_file() {
  using namespace testing;
  const std::size_t n = static_cast<std::size_t>(flac().sample_count());
  TdmsBytes m;          // metadata, little-endian
  m.u32(3);             // 3 objects
  m.str("/'rig'");      // object 0: the group
  m.u32(kIndexNoData);  //   no raw data
  m.u32(0);             //   no properties
  for (const char* name : {"base_acc", "y"}) {
    m.str(std::string("/'rig'/'") + name + "'");          // a channel
    m.u32(kIndexPlain);                                   //   raw data index of 20 bytes:
    m.u32(kTdsF64);                                       //     float64
    m.u32(1);                                             //     array dimension 1
    m.u64(n);                                             //     n values per chunk
    m.u32(1);                                             //   1 property
    m.str("wf_increment").u32(kTdsF64).f64(1.0 / 512.0);  // s: 512 Hz
  }
  TdmsBytes raw;  // one chunk: every value of base_acc, then of y
  for (int c = 0; c < 2; ++c) {
    for (const double v : stored_column(c)) raw.f64(v);
  }
  return tdms_segment(kTocMetaData | kTocNewObjList | kTocRawData, m.bytes(), raw.bytes());
}

// Two binary datasets 58b, big-endian float64, named "table:1:+X" and "mass:2:+X".
std::string uff_file() {
  using namespace testing;
  std::string file;
  const char* entities[] = {"table", "mass"};
  for (int c = 0; c < 2; ++c) {
    Uff58Header h;
    h.response_entity = entities[c];
    h.response_node = std::to_string(c + 1);
    h.response_direction = "1";  // +X
    h.ordinate_type = "4";       // real double
    h.count = std::to_string(flac().sample_count());
    h.increment = "1.953125E-03";  // 1/512 s, exact in an E13.5 field
    h.ordinate_units = "NONE";
    std::string data;
    for (const double v : stored_column(c)) data += ieee_bytes(v, 2);
    file += binary_uff58(h, 2, data);
  }
  return file;
}

nlohmann::json matlab_spec(const std::string& format, const std::string& path) {
  const auto n = static_cast<std::size_t>(flac().sample_count());
  return {{"format", format},
          {"path", path},
          {"compress", true},
          {"variables",
           {testing::fixture_variable("base_acc", "float64", {1, n}, stored_column(0)),
            testing::fixture_variable("y", "float64", {n, 1}, stored_column(1))}}};
}

std::vector<analysis::LevelResult> edc_levels(const Recording& recording) {
  return analysis::analyze_record(measurement_channels(recording), analysis::PipelineSettings())
      .levels;
}

void expect_same_edc(const Recording& read, const std::string& what, bool same_stored = true) {
  ASSERT_EQ(read.samples_si.rows(), flac().samples_si.rows()) << what;
  // Bit for bit: the same stored values through the same calibration.
  if (same_stored) {
    EXPECT_TRUE((read.samples_stored.array() == flac().samples_stored.array()).all()) << what;
  }
  EXPECT_TRUE((read.samples_si.array() == flac().samples_si.array()).all()) << what;
  static const std::vector<analysis::LevelResult> reference = edc_levels(flac());
  ASSERT_EQ(reference.size(), 26u);  // the sample's 0.2 to 2.7 N in 0.1 N steps
  const std::vector<analysis::LevelResult> levels = edc_levels(read);
  ASSERT_EQ(levels.size(), reference.size()) << what;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    EXPECT_EQ(levels[i].f0_n, reference[i].f0_n) << what << ", level " << i;
    EXPECT_EQ(levels[i].edc_mean_j, reference[i].edc_mean_j) << what << ", level " << i;
    EXPECT_EQ(levels[i].edc_std_j, reference[i].edc_std_j) << what << ", level " << i;
    EXPECT_EQ(levels[i].cycles, reference[i].cycles) << what << ", level " << i;
    EXPECT_EQ(levels[i].well, reference[i].well) << what << ", level " << i;
  }
}

TEST(SameEdcAcrossFormats, OscilabsOwnWavAndCsv) {
  TempDir dir;
  for (const std::string name : {"run.wav", "run.csv"}) {
    write_recording(flac(), dir.file(name));
    expect_same_edc(read_recording(dir.file(name)), name);
  }
}

// Oscilab's MATLAB export holds SI values and a t_s vector: read back with scale 1 and that time
// axis, it gives the same SI samples, so the same EDC table.
TEST(SameEdcAcrossFormats, ARoundTripThroughOscilabsMatlabExport) {
  TempDir dir;
  const std::string path = dir.file("export.mat");
  write_recording_mat(flac(), path);
  Sidecar sidecar = mapped_sidecar({"base_acc", "y"});
  for (ChannelInfo& channel : sidecar.channels) {
    channel.unit = si_unit(channel.quantity);
    channel.scale = 1.0;
  }
  sidecar.time = SignalTime{"t_s", -1};
  expect_same_edc(read_recording(path, sidecar), "MATLAB export", false);
}

TEST(SameEdcAcrossFormats, TdmsBuiltFromTheFormatDescription) {
  TempDir dir;
  testing::write_file(dir.file("run.tdms"), tdms_file());
  expect_same_edc(read_recording(dir.file("run.tdms"), mapped_sidecar({"rig/base_acc", "rig/y"})),
                  "TDMS");
}

TEST(SameEdcAcrossFormats, Uff58bBuiltFromTheDatasetDescription) {
  TempDir dir;
  testing::write_file(dir.file("run.uff"), uff_file());
  expect_same_edc(read_recording(dir.file("run.uff"), mapped_sidecar({"table:1:+X", "mass:2:+X"})),
                  "UFF 58b");
}

TEST(SameEdcAcrossFormats, MatlabV5AndV73AndHdf5WrittenBySciPyAndH5py) {
  TempDir dir;
  for (const std::string format : {"mat5", "mat73"}) {
    const std::string path = dir.file(format + ".mat");
    testing::write_fixture(dir, matlab_spec(format, path));
    expect_same_edc(read_recording(path, mapped_sidecar({"base_acc", "y"})), format);
  }
  const auto n = static_cast<std::size_t>(flac().sample_count());
  std::vector<double> both;  // an n × 2 dataset, row-major: base, mass in each row
  for (std::size_t r = 0; r < n; ++r) {
    both.push_back(flac().samples_stored(static_cast<Eigen::Index>(r), 0));
    both.push_back(flac().samples_stored(static_cast<Eigen::Index>(r), 1));
  }
  const std::string path = dir.file("run.h5");
  testing::write_fixture(dir, {{"format", "hdf5"},
                               {"path", path},
                               {"variables",
                                {testing::fixture_variable("/rig/signals", "float64", {n, 2}, both,
                                                           {{"sample_rate_hz", 512.0}})}}});
  Sidecar sidecar = mapped_sidecar({"/rig/signals", "/rig/signals"});
  sidecar.channels[0].column = 0;
  sidecar.channels[1].column = 1;
  expect_same_edc(read_recording(path, sidecar), "HDF5");
}

}  // namespace
}  // namespace oscilab::daq
