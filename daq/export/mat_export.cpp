#include "daq/export/mat_export.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <set>

#include <matio.h>

#include "analysis/common/input_error.h"
#include "analysis/pipeline/result_units.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::daq {
namespace {

constexpr std::size_t kMaxNameLength = 63;  // MATLAB's namelengthmax

// iskeyword in MATLAB R2023a: a variable cannot take these names.
const std::set<std::string> kKeywords = {"break",  "case",   "catch",     "classdef", "continue",
                                         "else",   "elseif", "end",       "for",      "function",
                                         "global", "if",     "otherwise", "parfor",   "persistent",
                                         "return", "spmd",   "switch",    "try",      "while"};

// The names write_recording_mat uses itself; channels never take them.
const std::set<std::string> kFixedNames = {"t_s",          "sample_rate_hz", "mass_kg",
                                           "sidecar_json", "channel_names",  "channel_variables",
                                           "channel_units"};

struct MatVarFree {
  void operator()(matvar_t* variable) const { Mat_VarFree(variable); }
};
using MatVar = std::unique_ptr<matvar_t, MatVarFree>;

// UTF-8 to UTF-16 code units, which is how MATLAB stores char arrays (miUINT16). A byte that does
// not start a valid sequence becomes U+FFFD, so any std::string can be written.
std::u16string utf16_of(const std::string& utf8) {
  std::u16string out;
  out.reserve(utf8.size());
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(utf8[i]); };
  std::size_t i = 0;
  while (i < utf8.size()) {
    const unsigned char lead = byte(i);
    int length = 0;
    char32_t code = 0;
    if (lead < 0x80) {
      length = 1;
      code = lead;
    } else if ((lead & 0xE0) == 0xC0) {
      length = 2;
      code = lead & 0x1F;
    } else if ((lead & 0xF0) == 0xE0) {
      length = 3;
      code = lead & 0x0F;
    } else if ((lead & 0xF8) == 0xF0) {
      length = 4;
      code = lead & 0x07;
    }
    bool valid = length > 0 && i + length <= utf8.size();
    for (int k = 1; valid && k < length; ++k) {
      valid = (byte(i + k) & 0xC0) == 0x80;
      code = (code << 6) | (byte(i + k) & 0x3F);
    }
    // Overlong forms, surrogates and values beyond U+10FFFF are not valid UTF-8.
    static constexpr char32_t kMinimum[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (valid &&
        (code < kMinimum[length] || code > 0x10FFFF || (code >= 0xD800 && code < 0xE000))) {
      valid = false;
    }
    if (!valid) {
      out.push_back(u'\uFFFD');
      ++i;
      continue;
    }
    if (code >= 0x10000) {
      code -= 0x10000;
      out.push_back(static_cast<char16_t>(0xD800 + (code >> 10)));
      out.push_back(static_cast<char16_t>(0xDC00 + (code & 0x3FF)));
    } else {
      out.push_back(static_cast<char16_t>(code));
    }
    i += length;
  }
  return out;
}

// A 1×k char array (name may be null for a cell element). matio copies the data.
MatVar char_variable(const char* name, const std::string& text) {
  std::u16string units = utf16_of(text);
  std::size_t dims[2] = {1, units.size()};
  return MatVar(Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT16, 2, dims, units.data(), 0));
}

// An n×1 double column that points at `values` (matio neither copies nor frees it), so `values`
// must outlive the write.
MatVar double_column(const std::string& name, const double* values, std::size_t n) {
  std::size_t dims[2] = {n, 1};
  return MatVar(Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                              const_cast<double*>(values), MAT_F_DONT_COPY_DATA));
}

MatVar double_scalar(const std::string& name, double value) {
  std::size_t dims[2] = {1, 1};
  return MatVar(Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, &value, 0));
}

// n×1 cell of char. The cell owns its elements and frees them with itself.
MatVar string_cell(const std::string& name, const std::vector<std::string>& texts) {
  std::size_t dims[2] = {texts.size(), 1};
  MatVar cell(Mat_VarCreate(name.c_str(), MAT_C_CELL, MAT_T_CELL, 2, dims, nullptr, 0));
  if (!cell) return cell;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    MatVar element = char_variable(nullptr, texts[i]);
    if (!element) return MatVar();
    Mat_VarSetCell(cell.get(), static_cast<int>(i), element.release());
  }
  return cell;
}

MatVar logical_column(const std::string& name, const std::vector<std::uint8_t>& values) {
  std::size_t dims[2] = {values.size(), 1};
  return MatVar(Mat_VarCreate(name.c_str(), MAT_C_UINT8, MAT_T_UINT8, 2, dims,
                              const_cast<std::uint8_t*>(values.data()), MAT_F_LOGICAL));
}

// A MAT-file being written to a temporary beside `target`; commit() closes and renames it.
class MatWriter {
 public:
  explicit MatWriter(const std::string& target) : file_(target) {
    errno = 0;
    mat_ = Mat_CreateVer(file_.path().c_str(), nullptr, MAT_FT_MAT5);
    if (!mat_) {
      throw InputError(target + ": cannot write" +
                       (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string()));
    }
  }
  MatWriter(const MatWriter&) = delete;
  MatWriter& operator=(const MatWriter&) = delete;
  ~MatWriter() {
    if (mat_) Mat_Close(mat_);
  }

  void write(const std::string& name, const MatVar& variable) {
    if (!variable) throw InputError(file_.target() + ": cannot create variable " + name);
    if (Mat_VarWrite(mat_, variable.get(), MAT_COMPRESSION_ZLIB) != 0) {
      throw InputError(file_.target() + ": write failed (variable " + name + ")");
    }
  }

  void commit() {
    const int status = Mat_Close(mat_);
    mat_ = nullptr;
    if (status != 0) throw InputError(file_.target() + ": write failed");
    file_.commit();
  }

 private:
  TemporaryFile file_;
  mat_t* mat_ = nullptr;
};

}  // namespace

std::string matlab_identifier(const std::string& name) {
  std::string id;
  for (const char c : name) {
    const bool word = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    id.push_back(word ? c : '_');
  }
  const bool letter_first =
      !id.empty() && ((id[0] >= 'a' && id[0] <= 'z') || (id[0] >= 'A' && id[0] <= 'Z'));
  if (!letter_first) id.insert(id.begin(), 'x');
  if (kKeywords.count(id) != 0) id.push_back('_');
  if (id.size() > kMaxNameLength) id.resize(kMaxNameLength);
  return id;
}

std::vector<std::string> mat_channel_variables(const Sidecar& sidecar) {
  std::set<std::string> taken = kFixedNames;
  std::vector<std::string> names;
  for (const auto& channel : sidecar.channels) {
    const std::string base = matlab_identifier(channel.name);
    std::string name = base;
    for (int n = 2; taken.count(name) != 0; ++n) {
      const std::string suffix = "_" + std::to_string(n);
      name = base.substr(0, kMaxNameLength - suffix.size()) + suffix;
    }
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

void write_recording_mat(const Recording& recording, const std::string& path) {
  const Sidecar& sidecar = recording.sidecar;
  const auto channels = static_cast<Eigen::Index>(sidecar.channels.size());
  if (recording.samples_si.cols() != channels) {
    throw InputError(path + ": the recording has " + std::to_string(channels) +
                     " channels in its sidecar but " + std::to_string(recording.samples_si.cols()) +
                     " sample columns");
  }
  if (!(sidecar.sample_rate_hz > 0.0) || !std::isfinite(sidecar.sample_rate_hz)) {
    throw InputError(
        path + ": sample_rate_hz: not a positive rate: " + std::to_string(sidecar.sample_rate_hz));
  }
  const auto n = static_cast<std::size_t>(recording.sample_count());
  std::vector<double> t_s(n);
  for (std::size_t i = 0; i < n; ++i) t_s[i] = static_cast<double>(i) / sidecar.sample_rate_hz;

  const std::vector<std::string> variables = mat_channel_variables(sidecar);
  std::vector<std::string> names;
  std::vector<std::string> units;
  for (const auto& channel : sidecar.channels) {
    names.push_back(channel.name);
    units.push_back(si_unit(channel.quantity));
  }

  MatWriter mat(path);
  mat.write("t_s", double_column("t_s", t_s.data(), n));
  for (Eigen::Index c = 0; c < channels; ++c) {
    const std::string& name = variables[static_cast<std::size_t>(c)];
    mat.write(name, double_column(name, recording.samples_si.col(c).data(), n));
  }
  mat.write("sample_rate_hz", double_scalar("sample_rate_hz", sidecar.sample_rate_hz));
  if (sidecar.mass_kg) mat.write("mass_kg", double_scalar("mass_kg", *sidecar.mass_kg));
  mat.write("sidecar_json", char_variable("sidecar_json", sidecar_to_json(sidecar).dump(2)));
  mat.write("channel_names", string_cell("channel_names", names));
  mat.write("channel_variables", string_cell("channel_variables", variables));
  mat.write("channel_units", string_cell("channel_units", units));
  mat.commit();
}

std::vector<EdcTableRow> edc_table_rows(const analysis::CampaignAnalysis& campaign) {
  std::vector<EdcTableRow> rows;
  for (const auto& record : campaign.records) {
    for (const auto& level : record.levels) {
      rows.push_back({record.name, level, analysis::level_flags(record, level)});
    }
  }
  return rows;
}

void write_edc_mat(const std::vector<EdcTableRow>& rows, const std::string& path) {
  if (rows.empty()) {
    throw InputError(path + ": no EDC levels to write (no stepped-sine level was found)");
  }
  const std::size_t n = rows.size();
  std::vector<std::string> well(n);
  std::vector<std::string> record(n);
  std::vector<std::string> flags(n);
  std::vector<std::uint8_t> usable(n);
  // Numeric columns in the order they are written; names match the CSV of `analyze --edc`.
  struct Column {
    const char* name;
    double (*value)(const analysis::LevelResult&);
  };
  static constexpr Column kColumns[] = {
      {"f0_n", [](const analysis::LevelResult& l) { return l.f0_n; }},
      {"edc_mean_j", [](const analysis::LevelResult& l) { return l.edc_mean_j; }},
      {"edc_std_j", [](const analysis::LevelResult& l) { return l.edc_std_j; }},
      {"cycles", [](const analysis::LevelResult& l) { return static_cast<double>(l.cycles); }},
      {"edc_noise_floor_j", [](const analysis::LevelResult& l) { return l.edc_noise_floor_j; }},
      {"edc_eq13_mean_j", [](const analysis::LevelResult& l) { return l.edc_eq13_mean_j; }},
      {"edc_trapz_mean_j", [](const analysis::LevelResult& l) { return l.edc_trapz_mean_j; }},
      {"z1_abs_m", [](const analysis::LevelResult& l) { return l.z1_abs_m; }},
      {"z_mean_m", [](const analysis::LevelResult& l) { return l.z_mean_m; }},
      {"start_s", [](const analysis::LevelResult& l) { return l.start_s; }},
      {"end_s", [](const analysis::LevelResult& l) { return l.end_s; }},
  };
  std::vector<std::vector<double>> columns(std::size(kColumns), std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    const analysis::LevelResult& level = rows[i].level;
    well[i] = analysis::to_string(level.well);
    record[i] = rows[i].record;
    flags[i] = rows[i].flags;
    usable[i] = level.usable() ? 1 : 0;
    for (std::size_t c = 0; c < std::size(kColumns); ++c) columns[c][i] = kColumns[c].value(level);
  }

  MatWriter mat(path);
  mat.write("well", string_cell("well", well));
  for (std::size_t c = 0; c < std::size(kColumns); ++c) {
    mat.write(kColumns[c].name, double_column(kColumns[c].name, columns[c].data(), n));
  }
  mat.write("record", string_cell("record", record));
  mat.write("flags", string_cell("flags", flags));
  mat.write("usable", logical_column("usable", usable));
  mat.commit();
}

}  // namespace oscilab::daq
