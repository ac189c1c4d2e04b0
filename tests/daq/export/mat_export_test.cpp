// MATLAB v5 export (daq/export/mat_export). Each file is read twice: by a small parser of the
// MAT-file level 5 layout written here from MathWorks' "MAT-File Format" document (independent of
// matio), and by matio itself for the cell arrays.
#include "daq/export/mat_export.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <matio.h>
#include <zlib.h>

#include <nlohmann/json.hpp>

#include "analysis/common/input_error.h"
#include "tests/daq/recording/recording_test_util.h"

namespace oscilab::daq {
namespace {

using testing::channel;
using testing::input_error_of;
using testing::read_file;
using testing::sine_recording;
using testing::TempDir;

// --- an independent reader of MAT-file level 5 --------------------------------------------------
// A 128-byte header (116 bytes of text, 8 of subsystem offset, version 0x0100, endian "IM"), then
// data elements: a tag (uint32 type, uint32 byte count) and the data, padded to 8 bytes. A small
// element packs its byte count (≤ 4) into the upper half of the first tag word and its data into
// the second. miCOMPRESSED (15) holds one zlib stream that inflates to a miMATRIX (14) element,
// whose sub-elements are: array flags (miUINT32: class in the low byte, logical = 0x0200),
// dimensions (miINT32), name (miINT8), then the real part (or, for a cell, one miMATRIX each).

constexpr std::uint32_t kMiInt8 = 1;
constexpr std::uint32_t kMiUint8 = 2;
constexpr std::uint32_t kMiUint16 = 4;
constexpr std::uint32_t kMiInt32 = 5;
constexpr std::uint32_t kMiUint32 = 6;
constexpr std::uint32_t kMiDouble = 9;
constexpr std::uint32_t kMiMatrix = 14;
constexpr std::uint32_t kMiCompressed = 15;
constexpr int kMxCellClass = 1;
constexpr int kMxCharClass = 4;
constexpr int kMxDoubleClass = 6;
constexpr int kMxUint8Class = 9;

std::uint32_t u32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);  // the files are little-endian ("IM"), as is x86
  return value;
}

struct Element {
  std::uint32_t type = 0;
  std::string data;
  std::size_t next = 0;  // offset of the following element
};

Element read_element(const std::string& bytes, std::size_t at) {
  Element element;
  const std::uint32_t word = u32(bytes, at);
  if ((word >> 16) != 0) {  // small data element
    element.type = word & 0xFFFF;
    element.data = bytes.substr(at + 4, word >> 16);
    element.next = at + 8;
    return element;
  }
  element.type = word;
  const std::uint32_t count = u32(bytes, at + 4);
  element.data = bytes.substr(at + 8, count);
  // Compressed elements are not padded; everything else is padded to a multiple of 8 bytes.
  element.next = at + 8 + (element.type == kMiCompressed ? count : (count + 7) / 8 * 8);
  return element;
}

std::string inflate_all(const std::string& compressed) {
  z_stream stream{};
  EXPECT_EQ(inflateInit(&stream), Z_OK);
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = static_cast<uInt>(compressed.size());
  std::string out;
  char buffer[65536];
  int status = Z_OK;
  while (status == Z_OK) {
    stream.next_out = reinterpret_cast<Bytef*>(buffer);
    stream.avail_out = sizeof(buffer);
    status = inflate(&stream, Z_NO_FLUSH);
    out.append(buffer, sizeof(buffer) - stream.avail_out);
  }
  EXPECT_EQ(status, Z_STREAM_END);
  inflateEnd(&stream);
  return out;
}

struct RawVariable {
  std::string name;
  int class_id = 0;
  bool logical = false;
  std::vector<std::int32_t> dims;
  std::uint32_t data_type = 0;  // of the real part
  std::string data;             // the real part's bytes
  std::vector<RawVariable> cells;
};

RawVariable parse_matrix(const std::string& data) {
  RawVariable variable;
  const Element flags = read_element(data, 0);
  EXPECT_EQ(flags.type, kMiUint32);
  variable.class_id = static_cast<int>(u32(flags.data, 0) & 0xFF);
  variable.logical = (u32(flags.data, 0) & 0x0200) != 0;
  const Element dims = read_element(data, flags.next);
  EXPECT_EQ(dims.type, kMiInt32);
  for (std::size_t i = 0; i + 4 <= dims.data.size(); i += 4) {
    variable.dims.push_back(static_cast<std::int32_t>(u32(dims.data, i)));
  }
  const Element name = read_element(data, dims.next);
  EXPECT_EQ(name.type, kMiInt8);
  variable.name = name.data;
  std::size_t at = name.next;
  if (variable.class_id == kMxCellClass) {
    while (at < data.size()) {
      const Element cell = read_element(data, at);
      EXPECT_EQ(cell.type, kMiMatrix);
      variable.cells.push_back(parse_matrix(cell.data));
      at = cell.next;
    }
  } else if (at < data.size()) {
    const Element real = read_element(data, at);
    variable.data_type = real.type;
    variable.data = real.data;
  }
  return variable;
}

struct RawFile {
  std::string header_text;
  std::uint16_t version = 0;
  std::string endian;
  std::vector<RawVariable> variables;
  bool all_compressed = true;
};

RawFile parse_mat5(const std::string& bytes) {
  RawFile file;
  if (bytes.size() < 128) {
    ADD_FAILURE() << "shorter than a MAT-file header";
    return file;
  }
  file.header_text = bytes.substr(0, 116);
  std::memcpy(&file.version, bytes.data() + 124, 2);
  file.endian = bytes.substr(126, 2);
  std::size_t at = 128;
  while (at + 8 <= bytes.size()) {
    const Element element = read_element(bytes, at);
    at = element.next;
    if (element.type == kMiCompressed) {
      const std::string inflated = inflate_all(element.data);
      const Element matrix = read_element(inflated, 0);
      EXPECT_EQ(matrix.type, kMiMatrix);
      file.variables.push_back(parse_matrix(matrix.data));
    } else {
      file.all_compressed = false;
      EXPECT_EQ(element.type, kMiMatrix);
      file.variables.push_back(parse_matrix(element.data));
    }
  }
  EXPECT_EQ(at, bytes.size());
  return file;
}

std::vector<double> doubles_of(const RawVariable& variable) {
  EXPECT_EQ(variable.data_type, kMiDouble) << variable.name;
  std::vector<double> values(variable.data.size() / 8);
  std::memcpy(values.data(), variable.data.data(), values.size() * 8);
  return values;
}

// UTF-16 code units (miUINT16 char data) back to UTF-8.
std::string utf8_of_char_array(const RawVariable& variable) {
  EXPECT_EQ(variable.class_id, kMxCharClass) << variable.name;
  EXPECT_EQ(variable.data_type, kMiUint16) << variable.name;
  std::string out;
  const std::size_t n = variable.data.size() / 2;
  const auto unit = [&](std::size_t i) {
    std::uint16_t u = 0;
    std::memcpy(&u, variable.data.data() + 2 * i, 2);
    return static_cast<char32_t>(u);
  };
  for (std::size_t i = 0; i < n; ++i) {
    char32_t code = unit(i);
    if (code >= 0xD800 && code < 0xDC00 && i + 1 < n) {
      code = 0x10000 + ((code - 0xD800) << 10) + (unit(i + 1) - 0xDC00);
      ++i;
    }
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }
  return out;
}

std::vector<std::string> names_of(const RawFile& file) {
  std::vector<std::string> names;
  for (const auto& variable : file.variables) names.push_back(variable.name);
  return names;
}

const RawVariable* find(const RawFile& file, const std::string& name) {
  for (const auto& variable : file.variables) {
    if (variable.name == name) return &variable;
  }
  return nullptr;
}

// --- matio, for what the raw reader does not decode -------------------------------------------

struct MatClose {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};
struct MatVarFree {
  void operator()(matvar_t* variable) const { Mat_VarFree(variable); }
};
using MatFile = std::unique_ptr<mat_t, MatClose>;
using MatVar = std::unique_ptr<matvar_t, MatVarFree>;

std::vector<std::string> matio_strings(mat_t* mat, const std::string& name) {
  MatVar cell(Mat_VarRead(mat, name.c_str()));
  std::vector<std::string> out;
  if (!cell || cell->class_type != MAT_C_CELL) {
    ADD_FAILURE() << name << " is not a cell array";
    return out;
  }
  const std::size_t n = cell->dims[0] * cell->dims[1];
  for (std::size_t i = 0; i < n; ++i) {
    const matvar_t* element = Mat_VarGetCell(cell.get(), static_cast<int>(i));
    std::string text;
    const auto* units = static_cast<const std::uint16_t*>(element->data);
    for (std::size_t k = 0; k < element->nbytes / 2; ++k) text += static_cast<char>(units[k]);
    out.push_back(text);
  }
  return out;
}

std::vector<double> matio_doubles(mat_t* mat, const std::string& name) {
  MatVar variable(Mat_VarRead(mat, name.c_str()));
  if (!variable || variable->class_type != MAT_C_DOUBLE) {
    ADD_FAILURE() << name << " is not a double array";
    return {};
  }
  const auto* values = static_cast<const double*>(variable->data);
  return std::vector<double>(values, values + variable->nbytes / sizeof(double));
}

Recording test_recording() {
  Recording recording =
      sine_recording(512.0, 1001,
                     {channel("base_acc", ChannelRole::Base, Quantity::Acceleration, "m/s^2"),
                      channel("y pos", ChannelRole::Mass, Quantity::Displacement, "mm"),
                      channel("t_s", ChannelRole::Force, Quantity::Force, "N")});
  Excitation excitation;
  excitation.type = "stepped-sine";
  excitation.frequency_hz = 9.0;
  recording.sidecar.excitation = excitation;
  // Non-ASCII text: a BMP character (z₊*) and one outside it (U+1D467, a surrogate pair).
  recording.sidecar.notes = "well z\u208A* \U0001D467";
  recording.samples_si(7, 1) = std::numeric_limits<double>::quiet_NaN();  // a gap
  return recording;
}

TEST(MatlabIdentifier, MakesValidNames) {
  EXPECT_EQ(matlab_identifier("base_acc"), "base_acc");
  EXPECT_EQ(matlab_identifier("y pos [mm]"), "y_pos__mm_");
  EXPECT_EQ(matlab_identifier("1st"), "x1st");
  EXPECT_EQ(matlab_identifier("_a"), "x_a");
  EXPECT_EQ(matlab_identifier(""), "x");
  EXPECT_EQ(matlab_identifier("end"), "end_");
  EXPECT_EQ(matlab_identifier("z\u208A"), "z___");  // 3 UTF-8 bytes, one underscore each
  EXPECT_EQ(matlab_identifier(std::string(80, 'a')).size(), 63u);  // namelengthmax
}

TEST(MatChannelVariables, AvoidsFixedNamesAndDuplicates) {
  Sidecar sidecar;
  sidecar.channels = {channel("a b", ChannelRole::Base, Quantity::Acceleration, "m/s^2"),
                      channel("a-b", ChannelRole::Mass, Quantity::Displacement, "m"),
                      channel("t_s", ChannelRole::Force, Quantity::Force, "N"),
                      channel("mass_kg", ChannelRole::Force, Quantity::Force, "N")};
  EXPECT_EQ(mat_channel_variables(sidecar),
            (std::vector<std::string>{"a_b", "a_b_2", "t_s_2", "mass_kg_2"}));
}

TEST(MatExport, WritesAV5FileWithEveryVariableBitExact) {
  TempDir dir;
  const Recording recording = test_recording();
  const std::string path = dir.file("run.mat");
  write_recording_mat(recording, path);

  const RawFile file = parse_mat5(read_file(path));
  EXPECT_EQ(file.header_text.rfind("MATLAB 5.0 MAT-file", 0), 0u) << file.header_text;
  EXPECT_EQ(file.version, 0x0100);
  EXPECT_EQ(file.endian, "IM");
  EXPECT_TRUE(file.all_compressed);
  EXPECT_EQ(names_of(file),
            (std::vector<std::string>{"t_s", "base_acc", "y_pos", "t_s_2", "sample_rate_hz",
                                      "mass_kg", "sidecar_json", "channel_names",
                                      "channel_variables", "channel_units"}));

  const std::size_t n = 1001;
  const RawVariable* t = find(file, "t_s");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->class_id, kMxDoubleClass);
  EXPECT_EQ(t->dims, (std::vector<std::int32_t>{1001, 1}));  // a column vector
  const std::vector<double> t_s = doubles_of(*t);
  ASSERT_EQ(t_s.size(), n);
  EXPECT_EQ(t_s[0], 0.0);
  EXPECT_EQ(t_s[1000], 1000.0 / 512.0);  // exact: binary fractions
  // Channels: the SI samples, bit for bit (double storage, lossless compression); NaN kept.
  const char* channel_variables[] = {"base_acc", "y_pos", "t_s_2"};
  for (int c = 0; c < 3; ++c) {
    const RawVariable* variable = find(file, channel_variables[c]);
    ASSERT_NE(variable, nullptr);
    EXPECT_EQ(variable->dims, (std::vector<std::int32_t>{1001, 1}));
    const std::vector<double> values = doubles_of(*variable);
    ASSERT_EQ(values.size(), n);
    for (std::size_t i = 0; i < n; ++i) {
      const double expected = recording.samples_si(static_cast<Eigen::Index>(i), c);
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(values[i])) << channel_variables[c] << "[" << i << "]";
      } else {
        ASSERT_EQ(values[i], expected) << channel_variables[c] << "[" << i << "]";
      }
    }
  }
  EXPECT_EQ(doubles_of(*find(file, "sample_rate_hz")), std::vector<double>{512.0});
  EXPECT_EQ(doubles_of(*find(file, "mass_kg")), std::vector<double>{0.26});

  // The sidecar as JSON text, UTF-16 in the file, equal to sidecar_to_json after the round trip.
  const RawVariable* json_text = find(file, "sidecar_json");
  ASSERT_NE(json_text, nullptr);
  EXPECT_EQ(json_text->dims.at(0), 1);
  const nlohmann::json json = nlohmann::json::parse(utf8_of_char_array(*json_text));
  EXPECT_EQ(json, sidecar_to_json(recording.sidecar));
  EXPECT_EQ(json.at("notes").get<std::string>(), "well z\u208A* \U0001D467");

  const RawVariable* names = find(file, "channel_names");
  ASSERT_NE(names, nullptr);
  EXPECT_EQ(names->class_id, kMxCellClass);
  EXPECT_EQ(names->dims, (std::vector<std::int32_t>{3, 1}));
  ASSERT_EQ(names->cells.size(), 3u);
  EXPECT_EQ(utf8_of_char_array(names->cells[1]), "y pos");

  // matio reads the same file (it is what MATLAB-compatible tools see) and the cells.
  MatFile mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  ASSERT_NE(mat, nullptr);
  EXPECT_EQ(Mat_GetVersion(mat.get()), MAT_FT_MAT5);
  EXPECT_EQ(matio_strings(mat.get(), "channel_variables"),
            (std::vector<std::string>{"base_acc", "y_pos", "t_s_2"}));
  EXPECT_EQ(matio_strings(mat.get(), "channel_units"),
            (std::vector<std::string>{"m/s^2", "m", "N"}));
  EXPECT_EQ(matio_doubles(mat.get(), "t_s").back(), 1000.0 / 512.0);
}

TEST(MatExport, LeavesOutMassWhenTheSidecarHasNone) {
  TempDir dir;
  Recording recording = test_recording();
  recording.sidecar.mass_kg.reset();
  write_recording_mat(recording, dir.file("run.mat"));
  const RawFile file = parse_mat5(read_file(dir.file("run.mat")));
  EXPECT_EQ(find(file, "mass_kg"), nullptr);
  EXPECT_NE(find(file, "sample_rate_hz"), nullptr);
}

TEST(MatExport, ThrowsInputErrorNamingTheFileAndLeavesNothingBehind) {
  TempDir dir;
  const Recording recording = test_recording();
  const std::string missing_dir = dir.file("no/such/dir/run.mat");
  EXPECT_NE(input_error_of([&] { write_recording_mat(recording, missing_dir); }).find(missing_dir),
            std::string::npos);
  // A directory in the way: the temporary is written, the rename fails, the temporary goes.
  std::filesystem::create_directory(dir.file("taken.mat"));
  const std::string message =
      input_error_of([&] { write_recording_mat(recording, dir.file("taken.mat")); });
  EXPECT_NE(message.find("taken.mat: cannot write"), std::string::npos) << message;
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++entries;
  }
  EXPECT_EQ(entries, 1u);  // only the directory itself
  Recording broken = recording;
  broken.sidecar.channels.pop_back();
  EXPECT_NE(input_error_of([&] {
              write_recording_mat(broken, dir.file("b.mat"));
            }).find("b.mat: the recording has 2 channels in its sidecar but 3 sample columns"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.file("b.mat")));
}

std::vector<EdcTableRow> edc_rows() {
  std::vector<EdcTableRow> rows;
  for (int i = 0; i < 3; ++i) {
    analysis::LevelResult level;
    level.well = i == 2 ? analysis::Well::Negative : analysis::Well::Positive;
    level.f0_n = 0.2 + 0.1 * i;
    level.edc_mean_j = 1e-4 * (i + 1);
    level.edc_std_j = 1e-6 * (i + 1);
    level.cycles = 80 + i;
    level.edc_noise_floor_j = 3e-7;
    level.start_s = 3.0 + 10.0 * i;
    level.end_s = 12.5 + 10.0 * i;
    level.lag_rad = 1.5 + 0.25 * i;
    level.transient_cycles = 3 - i;
    level.period1_change = 0.01 * (i + 1);
    level.period1 = i != 1;  // the middle level is not period-1: unusable
    rows.push_back({i == 2 ? "neg.flac" : "pos.flac", level, level.flags()});
  }
  return rows;
}

TEST(EdcMatExport, WritesTheContractColumnsAsColumnVectors) {
  TempDir dir;
  const std::vector<EdcTableRow> rows = edc_rows();
  const std::string path = dir.file("edc.mat");
  write_edc_mat(rows, path);

  const RawFile file = parse_mat5(read_file(path));
  // Every column of the table, in its order (the CSV's), and nothing else; each n×1.
  std::vector<std::string> names;
  for (const RawVariable& variable : file.variables) {
    names.push_back(variable.name);
    EXPECT_EQ(variable.dims, (std::vector<std::int32_t>{3, 1})) << variable.name;
  }
  EXPECT_EQ(names,
            (std::vector<std::string>{"well", "f0_n", "edc_mean_j", "edc_std_j", "cycles", "record",
                                      "edc_noise_floor_j", "edc_eq13_mean_j", "edc_trapz_mean_j",
                                      "z1_abs_m", "lag_rad", "z_mean_m", "start_s", "end_s",
                                      "transient_cycles", "period1_change", "usable", "flags"}));
  for (const char* text : {"well", "record", "flags"}) {
    EXPECT_EQ(find(file, text)->class_id, kMxCellClass) << text;
  }
  for (const char* number : {"f0_n", "cycles", "lag_rad", "transient_cycles", "period1_change"}) {
    EXPECT_EQ(find(file, number)->class_id, kMxDoubleClass) << number;
  }
  // Doubles, bit for bit, in row order.
  const auto column = [&](double analysis::LevelResult::*member) {
    std::vector<double> values;
    for (const auto& row : rows) values.push_back(row.level.*member);
    return values;
  };
  EXPECT_EQ(doubles_of(*find(file, "f0_n")), column(&analysis::LevelResult::f0_n));
  EXPECT_EQ(doubles_of(*find(file, "edc_mean_j")), column(&analysis::LevelResult::edc_mean_j));
  EXPECT_EQ(doubles_of(*find(file, "edc_std_j")), column(&analysis::LevelResult::edc_std_j));
  EXPECT_EQ(doubles_of(*find(file, "start_s")), column(&analysis::LevelResult::start_s));
  EXPECT_EQ(doubles_of(*find(file, "lag_rad")), column(&analysis::LevelResult::lag_rad));
  EXPECT_EQ(doubles_of(*find(file, "period1_change")),
            column(&analysis::LevelResult::period1_change));
  EXPECT_EQ(doubles_of(*find(file, "cycles")), (std::vector<double>{80, 81, 82}));
  EXPECT_EQ(doubles_of(*find(file, "transient_cycles")), (std::vector<double>{3, 2, 1}));
  const RawVariable* usable = find(file, "usable");
  EXPECT_EQ(usable->class_id, kMxUint8Class);
  EXPECT_TRUE(usable->logical);
  EXPECT_EQ(usable->data_type, kMiUint8);
  EXPECT_EQ(usable->data, std::string("\x01\x00\x01", 3));

  MatFile mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  ASSERT_NE(mat, nullptr);
  EXPECT_EQ(matio_strings(mat.get(), "well"),
            (std::vector<std::string>{"positive", "positive", "negative"}));
  EXPECT_EQ(matio_strings(mat.get(), "record"),
            (std::vector<std::string>{"pos.flac", "pos.flac", "neg.flac"}));
  EXPECT_EQ(matio_strings(mat.get(), "flags"),
            (std::vector<std::string>{"", rows[1].level.flags(), ""}));
  EXPECT_NE(rows[1].level.flags(), "");
}

TEST(EdcMatExport, ThrowsInputErrorOnAnEmptyTable) {
  TempDir dir;
  const std::string path = dir.file("edc.mat");
  EXPECT_NE(input_error_of([&] { write_edc_mat({}, path); }).find("edc.mat: no EDC levels"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace oscilab::daq
