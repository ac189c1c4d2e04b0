// Universal File Format, dataset 58 ("Universal Dataset Number 58, Function at Nodal DOF", the
// SDRC / Siemens I-DEAS universal file format documentation), in ASCII ("58") and binary ("58b").
//
// A universal file is a sequence of datasets, each between lines "    -1" (Format I6). The line
// after the opening "-1" holds the dataset number; "58b" marks the binary form of dataset 58,
// whose first record then reads Format(I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12):
//   dataset number 58, "b", byte ordering (1 little-endian, 2 big-endian), floating-point format
//   (1 DEC VMS, 2 IEEE 754, 3 IBM 5/370), number of ASCII lines that follow (11), number of bytes
//   of binary data after them, four unused fields.
// Dataset 58 then holds 11 ASCII records:
//   1-5  ID lines (80A1): description, free text, date "DD-MMM-YY HH:MM:SS", ...
//   6    DOF identification, Format(2(I5,I10),2(1X,10A1,I10,I4)): function type (1 = time
//        response), function id, version, load case, response entity name, node, direction,
//        reference entity name, node, direction
//   7    data form, Format(3I10,3E13.5): ordinate data type (2 real single, 4 real double,
//        5 complex single, 6 complex double), number of values, abscissa spacing (0 uneven,
//        1 even), abscissa minimum, abscissa increment, z-axis value
//   8-11 abscissa, ordinate (numerator), ordinate denominator and z-axis data characteristics,
//        Format(I10,3I5,2(1X,20A1)): specific data type, length, force and temperature unit
//        exponents, axis label, axis units label
// and record 12, the values: ASCII 6E13.5 (single) or 4E20.12 (double), or the binary values.
//
// Only time responses (function type 1) of real values on an even abscissa are recordings; other
// functions of dataset 58 (spectra, FRFs, ...) and other datasets (151 header, 164 units, 2411
// nodes, ...) are skipped and listed in FileContents.properties["skipped_datasets"].
//
// uff_fields reads the Fortran fields of the records, uff_datasets scans the datasets and the
// header records of dataset 58, uff_values reads the values of record 12.
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <string_view>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/formats/uff_datasets.h"
#include "daq/recording/formats/uff_fields.h"
#include "daq/recording/formats/uff_values.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

using uff::Dataset58;
using uff::Dof;
using uff::function_type_name;
using uff::is_blank;
using uff::is_blank_line;
using uff::is_delimiter;
using uff::Scan;
using uff::time_unit_s;
using uff::trim;
using uff::unused_text;

constexpr std::string_view kAliasPrefix = "dataset ";

// Record 6 Field 7 / 10: ±1..±3 translations along X, Y, Z, ±4..±6 rotations about them.
std::string direction_text(long long direction) {
  static constexpr std::array<const char*, 6> kAxes = {"X", "Y", "Z", "RX", "RY", "RZ"};
  if (direction == 0) return "scalar";
  if (direction >= -6 && direction <= 6) {
    return std::string(direction > 0 ? "+" : "-") + kAxes[std::llabs(direction) - 1];
  }
  return std::to_string(direction);
}

// The sample rate of an increment as printed: the whole number of hertz nearest to 1/increment
// when it lies within the increment's rounding (E13.5 keeps 6 significant digits, so 65 536 Hz
// prints as 1.52588E-05 s, which is 65 536.2 Hz), else 1/increment.
double rate_from_increment(double increment_s, double unit_s, std::size_t decimals,
                           long long exponent) {
  const double rate_hz = 1.0 / increment_s;
  if (decimals > 30 || exponent < -300 || exponent > 300) return rate_hz;
  const double half_ulp_s =
      0.5 * std::pow(10.0, static_cast<double>(exponent) - static_cast<double>(decimals)) * unit_s;
  const double whole_hz = std::round(rate_hz);
  if (!(whole_hz > 0.0) || !(half_ulp_s < increment_s)) return rate_hz;
  const bool within =
      whole_hz >= 1.0 / (increment_s + half_ulp_s) && whole_hz <= 1.0 / (increment_s - half_ulp_s);
  return within ? whole_hz : rate_hz;
}

// The DOF of record 6 as a signal name, "Mic 01:0:+X", or "" when record 6 names none.
std::string dof_name(const Dataset58& set) {
  const bool entity = !unused_text(set.response.entity);
  if (!entity && set.response.node == 0) return "";
  return (entity ? set.response.entity + ":" : std::string()) + std::to_string(set.response.node) +
         ":" + direction_text(set.response.direction);
}

nlohmann::json dof_json(const Dof& dof) {
  return {{"entity", dof.entity},
          {"node", dof.node},
          {"direction", dof.direction},
          {"direction_name", direction_text(dof.direction)}};
}

FileSignal file_signal(const Dataset58& set, const std::string& name) {
  FileSignal signal;
  signal.name = name;
  signal.sample_count = set.count;
  signal.unit = unused_text(set.axes[1].units) ? "" : set.axes[1].units;
  const double unit_s = *time_unit_s(set.axes[0].units);
  signal.sample_rate_hz = rate_from_increment(set.abscissa_increment * unit_s, unit_s,
                                              set.increment_decimals, set.increment_exponent);
  const bool single = set.ordinate_type == 2;
  signal.stored_type = set.binary ? (single ? "float32" : "float64")
                                  : (single ? "text, real single" : "text, real double");
  nlohmann::json& p = signal.properties;
  p["dataset"] = set.index;
  p["alias"] = std::string(kAliasPrefix) + std::to_string(set.index);
  p["id_lines"] = set.id_lines;
  p["function_type"] = set.function_type;
  p["function_type_name"] = function_type_name(set.function_type);
  p["function_id"] = set.function_id;
  p["version"] = set.version;
  p["load_case"] = set.load_case;
  p["response"] = dof_json(set.response);
  p["reference"] = dof_json(set.reference);
  p["ordinate_data_type"] = set.ordinate_type;
  p["abscissa_minimum"] = set.abscissa_min;
  p["abscissa_increment"] = set.abscissa_increment;
  p["z_axis_value"] = set.z_value;
  p["abscissa"] = set.axes[0].to_json();
  p["ordinate"] = set.axes[1].to_json();
  p["ordinate_denominator"] = set.axes[2].to_json();
  p["z_axis"] = set.axes[3].to_json();
  nlohmann::json storage = {{"encoding", set.binary ? "binary" : "ascii"},
                            {"offset_bytes", set.data_offset},
                            {"bytes", set.data_bytes}};
  if (set.binary) {
    storage["byte_order"] = set.byte_order == 1 ? "little-endian" : "big-endian";
  } else if (set.data_line > 0) {
    storage["first_line"] = set.data_line;
  }
  p["storage"] = storage;
  return signal;
}

class UffFormat final : public SignalFileReader {
 public:
  std::string_view format_name() const override { return "UFF 58"; }

  // A first non-blank line "-1" and then a dataset number ("58", "58b", "151", ...).
  bool matches_signature(std::string_view head) const override {
    if (head.rfind("\xEF\xBB\xBF", 0) == 0) head.remove_prefix(3);
    std::vector<std::string_view> lines;
    std::size_t start = 0;
    while (start < head.size() && lines.size() < 2) {
      std::size_t end = head.find('\n', start);
      if (end == std::string_view::npos) return false;  // need whole lines
      const std::string_view line = head.substr(start, end - start);
      if (!lines.empty() || !is_blank_line(line)) lines.push_back(line);
      start = end + 1;
    }
    // Format I6 right-aligns both numbers in six columns ("    -1", "    58", "    58b"), which
    // a column of numbers in a text file does not do.
    if (lines.size() < 2 || lines[0].substr(0, 6) != "    -1" || !is_delimiter(lines[0])) {
      return false;
    }
    const std::string_view number_field = lines[1].substr(0, 6);
    const std::string_view number = trim(number_field);
    const std::string_view rest = lines[1].substr(number_field.size());
    return number_field.size() == 6 && !number.empty() && number_field.back() != ' ' &&
           std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
           (rest.empty() || rest.front() == 'b' || rest.front() == 'B' || is_blank(rest.front()) ||
            rest.front() == '\r');
  }

  bool matches_extension(std::string_view extension) const override {
    return extension == ".uff" || extension == ".unv";
  }

  FileContents describe(const std::string& path) const override {
    check_data_file(path);
    const Scan scan = uff::scan_datasets(path);
    FileContents contents;
    std::map<std::string, int> uses;
    for (const Dataset58& set : scan.time_responses) ++uses[dof_name(set)];
    for (const Dataset58& set : scan.time_responses) {
      const std::string dof = dof_name(set);
      const std::string name = !dof.empty() && uses[dof] == 1
                                   ? dof
                                   : std::string(kAliasPrefix) + std::to_string(set.index);
      contents.file_signals.push_back(file_signal(set, name));
    }
    std::string container = scan.any_binary && scan.any_ascii ? "UFF 58 and 58b"
                            : scan.any_binary                 ? "UFF 58b"
                                                              : "UFF 58";
    if (scan.any_binary) container += ", " + scan.byte_orders;
    container += ", " + std::to_string(scan.time_responses.size()) + " time response" +
                 (scan.time_responses.size() == 1 ? "" : "s");
    if (!scan.skipped.empty()) {
      container += ", " + std::to_string(scan.skipped.size()) + " other dataset" +
                   (scan.skipped.size() == 1 ? "" : "s") + " skipped";
    }
    contents.container = container;
    contents.properties["datasets"] = scan.datasets;
    contents.properties["skipped_datasets"] = scan.skipped;
    if (contents.file_signals.empty()) {
      std::string reasons;
      for (const nlohmann::json& skipped : scan.skipped) {
        if (reasons.size() > 200) {
          reasons += "; ...";
          break;
        }
        reasons += (reasons.empty() ? "" : "; ") + std::string("dataset ") +
                   std::to_string(skipped["dataset"].get<int>()) + " " +
                   skipped["type"].get<std::string>() + ": " + skipped["reason"].get<std::string>();
      }
      throw InputError(path +
                       ": no time response (dataset 58, function type 1) to read as a "
                       "recording (" +
                       reasons + ")");
    }
    return contents;
  }

  Recording read(const std::string& path, const Sidecar& sidecar,
                 const std::string& sidecar_name) const override {
    return read_controlled(path, sidecar, sidecar_name, {});
  }

  // "dataset <k>" also names the time response in dataset k when its name is its DOF.
  Recording read_controlled(const std::string& path, const Sidecar& sidecar,
                            const std::string& sidecar_name,
                            const OpeningControl& control) const override {
    const auto is_alias = [](const std::string& name) { return name.rfind(kAliasPrefix, 0) == 0; };
    bool aliases = sidecar.time && is_alias(sidecar.time->source);
    for (const ChannelInfo& channel : sidecar.channels) {
      aliases = aliases || is_alias(channel.source.empty() ? channel.name : channel.source);
    }
    if (!aliases) return SignalFileReader::read_controlled(path, sidecar, sidecar_name, control);
    const FileContents contents = describe(path);
    const auto resolve = [&](const std::string& name) {
      for (const FileSignal& signal : contents.file_signals) {
        if (signal.properties.value("alias", "") == name) return signal.name;
      }
      return name;
    };
    Sidecar resolved = sidecar;
    for (ChannelInfo& channel : resolved.channels) {
      channel.source = resolve(channel.source.empty() ? channel.name : channel.source);
    }
    if (resolved.time) resolved.time->source = resolve(resolved.time->source);
    Recording recording = SignalFileReader::read_controlled(path, resolved, sidecar_name, control);
    recording.sidecar = sidecar;
    return recording;
  }

  std::vector<double> read_signal(const std::string& path, const FileSignal& signal,
                                  int /*column*/) const override {
    const nlohmann::json& storage = signal.properties.value("storage", nlohmann::json());
    if (!storage.is_object() || signal.sample_count < 0) {
      throw InputError(path + ": " + in_quotes(signal.name) + " is not a signal of this file");
    }
    const auto offset = storage.value("offset_bytes", std::uint64_t{0});
    const auto bytes = storage.value("bytes", std::uint64_t{0});
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const auto size = static_cast<std::uint64_t>(in.tellg());
    if (offset > size || bytes > size - offset) {
      throw InputError(path + ": " + in_quotes(signal.name) + ": the file changed (" +
                       std::to_string(size) + " bytes) since it was described");
    }
    std::string text(bytes, '\0');
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(text.data(), static_cast<std::streamsize>(bytes));
    if (static_cast<std::uint64_t>(in.gcount()) != bytes) {
      throw InputError(path + ": cannot read " + std::to_string(bytes) + " bytes at byte " +
                       std::to_string(offset));
    }
    if (storage.value("encoding", "") == "ascii") {
      return uff::read_ascii_values(path, signal, text, storage.value("first_line", 0L));
    }
    return uff::decode_binary_values(text, signal.stored_type == "float32",
                                     storage.value("byte_order", "") == "big-endian");
  }
};

}  // namespace

const FormatReader& uff_format() {
  static const UffFormat format;
  return format;
}

}  // namespace oscilab::daq
