// The MAT-file export the program sees: the variables are laid out here, and written by
// oscilab_hdf5_module (mat_file_writer.cpp, matio), which is loaded on the first export.
#include "daq/export/mat_export.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <set>

#include "analysis/common/input_error.h"
#include "daq/hdf5_module/hdf5_module_loader.h"
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

// The variables of one MAT-file as the module's C interface takes them. It keeps the names,
// scalars and text lists it is given; the arrays of `doubles` and `logicals` and the strings of
// `texts` stay the caller's and must outlive write().
class MatVariables {
 public:
  void doubles(const std::string& name, const double* values, std::size_t n) {
    add(name, kOscilabMatDoubles, n).doubles = values;
  }
  void scalar(const std::string& name, double value) {
    doubles(name, &scalars_.emplace_back(value), 1);
  }
  void logicals(const std::string& name, const std::vector<std::uint8_t>& values) {
    add(name, kOscilabMatLogicals, values.size()).logicals = values.data();
  }
  void text(const std::string& name, std::string text) {
    const std::string& kept = owned_texts_.emplace_back(std::move(text));
    add(name, kOscilabMatText, 1).texts = &text_lists_.emplace_back(1, c_text(kept)).front();
  }
  void texts(const std::string& name, const std::vector<std::string>& texts) {
    std::vector<OscilabTextV1>& list = text_lists_.emplace_back();
    for (const std::string& text : texts) list.push_back(c_text(text));
    add(name, kOscilabMatTexts, texts.size()).texts = list.data();
  }

  // Writes the file through the module, under a temporary name renamed into place.
  void write(const std::string& path) const {
    const OscilabHdf5ModuleV1& module = hdf5_module("writing " + path);
    TemporaryFile file(path);
    const OscilabMatWriteResultV1 result =
        module.write_mat(file.path().c_str(), variables_.data(), variables_.size());
    const auto variable = [&] { return names_.at(result.variable); };
    switch (result.status) {
      case kOscilabMatWritten:
        break;
      case kOscilabMatCannotCreate:
        throw InputError(path + ": cannot write" +
                         (result.error_number != 0
                              ? std::string(": ") + std::strerror(result.error_number)
                              : std::string()));
      case kOscilabMatCannotMakeVariable:
        throw InputError(path + ": cannot create variable " + variable());
      case kOscilabMatCannotWriteVariable:
        throw InputError(path + ": write failed (variable " + variable() + ")");
      case kOscilabMatCannotClose:
        throw InputError(path + ": write failed");
      default:
        throw InputError(path + ": write failed (out of memory)");
    }
    file.commit();
  }

 private:
  static OscilabTextV1 c_text(const std::string& text) { return {text.data(), text.size()}; }

  OscilabMatVariableV1& add(const std::string& name, OscilabMatKindV1 kind, std::size_t rows) {
    const std::string& kept = names_.emplace_back(name);
    return variables_.emplace_back(
        OscilabMatVariableV1{kept.c_str(), kind, rows, nullptr, nullptr, nullptr});
  }

  // Deques: what they hold stays where it is as they grow, so the pointers stay valid.
  std::deque<std::string> names_;
  std::deque<double> scalars_;
  std::deque<std::string> owned_texts_;
  std::deque<std::vector<OscilabTextV1>> text_lists_;
  std::vector<OscilabMatVariableV1> variables_;
};

// A Real or an Integer cell as MATLAB's double (integers are counts, exact below 2⁵³).
double number_of(const analysis::CellValue& value) {
  if (const auto* integer = std::get_if<std::int64_t>(&value)) {
    return static_cast<double>(*integer);
  }
  return std::get<double>(value);
}

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

  MatVariables mat;
  mat.doubles("t_s", t_s.data(), n);
  for (Eigen::Index c = 0; c < channels; ++c) {
    mat.doubles(variables[static_cast<std::size_t>(c)], recording.samples_si.col(c).data(), n);
  }
  mat.scalar("sample_rate_hz", sidecar.sample_rate_hz);
  if (sidecar.mass_kg) mat.scalar("mass_kg", *sidecar.mass_kg);
  mat.text("sidecar_json", sidecar_to_json(sidecar).dump(2));
  mat.texts("channel_names", names);
  mat.texts("channel_variables", variables);
  mat.texts("channel_units", units);
  mat.write(path);
}

void write_edc_mat(const std::vector<EdcTableRow>& rows, const std::string& path) {
  if (rows.empty()) {
    throw InputError(path + ": no EDC levels to write (no stepped-sine level was found)");
  }
  const auto& columns = analysis::edc_table_columns();
  // Every column's values, held until the write: MatVariables keeps pointers to them.
  std::deque<std::vector<double>> reals;
  std::deque<std::vector<std::uint8_t>> flags;
  std::deque<std::vector<std::string>> texts;
  MatVariables mat;
  for (const auto& column : columns) {
    switch (column.kind) {
      case analysis::ColumnKind::Real:
      case analysis::ColumnKind::Integer: {
        std::vector<double>& values = reals.emplace_back();
        for (const EdcTableRow& row : rows) values.push_back(number_of(column.value(row)));
        mat.doubles(column.name, values.data(), values.size());
        break;
      }
      case analysis::ColumnKind::Flag: {
        std::vector<std::uint8_t>& values = flags.emplace_back();
        for (const EdcTableRow& row : rows) values.push_back(std::get<bool>(column.value(row)));
        mat.logicals(column.name, values);
        break;
      }
      case analysis::ColumnKind::Text: {
        std::vector<std::string>& values = texts.emplace_back();
        for (const EdcTableRow& row : rows) {
          values.push_back(std::get<std::string>(column.value(row)));
        }
        mat.texts(column.name, values);
        break;
      }
    }
  }
  mat.write(path);
}

}  // namespace oscilab::daq
