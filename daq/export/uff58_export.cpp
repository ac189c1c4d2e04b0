// Universal File Format datasets 164 (units) and 58 (function at nodal DOF), ASCII. The record
// layouts follow the I-DEAS definitions as the Structural Dynamics Research Lab (University of
// Cincinnati) publishes them ("Universal Dataset Number 58: Function at Nodal DOF", "Universal
// Dataset Number 164: Units"). Numbers are formatted with std::to_chars, not printf, so the
// output does not depend on the C locale (a Qt application switches LC_NUMERIC to the user's).
#include "daq/export/uff58_export.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string_view>

#include "analysis/common/input_error.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::daq {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kLineWidth = 80;
constexpr std::string_view kDelimiter = "    -1\n";  // I6: -1 opens and closes every dataset

// Fortran A field: `text` left-aligned in `width` columns, cut to fit.
std::string a_field(std::string text, std::size_t width) {
  if (text.size() > width) text.resize(width);
  text.append(width - text.size(), ' ');
  return text;
}

// Fortran I field: right-aligned integer. The callers' values always fit their widths.
std::string i_field(long long value, std::size_t width) {
  const std::string digits = std::to_string(value);
  return std::string(width > digits.size() ? width - digits.size() : 0, ' ') + digits;
}

// Scientific notation with `precision` digits after the point, upper-case exponent letter.
std::string scientific(double value, int precision, char exponent_letter = 'E') {
  std::array<char, 48> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::scientific, precision);
  std::string text(buffer.data(), result.ptr);
  for (char& c : text) {
    if (c == 'e') c = exponent_letter;
  }
  return text;
}

// The shortest text that reads back as `value` (for messages and ID lines).
std::string plain(double value) {
  std::array<char, 48> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

// Fortran E/D field of `width` columns: the most digits (up to `max_precision` after the point)
// that leave at least one blank in front, so fields stay apart for readers that split on blanks.
std::string e_field(double value, std::size_t width, int max_precision, char letter = 'E') {
  for (int precision = max_precision; precision >= 0; --precision) {
    const std::string text = scientific(value, precision, letter);
    if (text.size() < width) return std::string(width - text.size(), ' ') + text;
  }
  return std::string(width, '*');  // unreachable for finite doubles and width >= 13
}

// ID lines and entity names: printable ASCII only (the format is 80A1), never blank.
std::string ascii(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    out.push_back(u >= 0x20 && u < 0x7F ? c : (u == '\t' ? ' ' : '?'));
  }
  if (out.find_first_not_of(' ') == std::string::npos) return "NONE";
  return out;
}

std::string entity_name(const std::string& name) {
  std::string out = ascii(name);
  for (char& c : out) {
    if (c == ' ') c = '_';
  }
  return a_field(out, 10);
}

std::string id_line(const std::string& text) { return a_field(ascii(text), kLineWidth) + '\n'; }

std::string date_time_now() {
  static constexpr const char* kMonths[] = {"JAN", "FEB", "MAR", "APR", "MAY", "JUN",
                                            "JUL", "AUG", "SEP", "OCT", "NOV", "DEC"};
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%02d-%s-%02d %02d:%02d:%02d", local.tm_mday,
                kMonths[local.tm_mon], local.tm_year % 100, local.tm_hour, local.tm_min,
                local.tm_sec);
  return text.data();
}

// Record 8 Field 1 (specific data type) for a channel's quantity.
int specific_data_type(const ChannelInfo& channel) {
  switch (channel.quantity) {
    case Quantity::Displacement:
      return 8;
    case Quantity::Velocity:
      return 11;
    case Quantity::Acceleration:
      return 12;
    case Quantity::Force:
      return 13;  // excitation force: the force applied to the structure
  }
  return 0;
}

std::string quantity_label(Quantity quantity) {
  std::string label = to_string(quantity);
  if (!label.empty()) label[0] = static_cast<char>(label[0] - 'a' + 'A');
  return label;
}

// Records 8–11: Format(I10,3I5,2(1X,20A1)).
std::string axis_record(int data_type, const std::string& label, const std::string& unit) {
  return i_field(data_type, 10) + i_field(0, 5) + i_field(0, 5) + i_field(0, 5) + ' ' +
         a_field(ascii(label), 20) + ' ' + a_field(ascii(unit), 20) + '\n';
}

std::string units_dataset() {
  std::string out(kDelimiter);
  out += i_field(164, 6) + '\n';
  // Record 1: Format(I10,20A1,I10): units code 1 (SI: meter, newton), description, temperature
  // mode 2 (relative).
  out += i_field(1, 10) + a_field("SI: Meter (newton)", 20) + i_field(2, 10) + '\n';
  // Record 2: Format(3D25.17): length, force, temperature factors to SI. Record 3: Format(D25.17):
  // temperature offset (273.15: Celsius to kelvin, unused here).
  // 16 significant digits: every double that has a shorter decimal form prints as that form.
  out += e_field(1.0, 25, 15, 'D') + e_field(1.0, 25, 15, 'D') + e_field(1.0, 25, 15, 'D') + '\n';
  out += e_field(273.15, 25, 15, 'D') + '\n';
  out += kDelimiter;
  return out;
}

std::string excitation_text(const Sidecar& sidecar) {
  if (!sidecar.excitation) return "NONE";
  std::string text = sidecar.excitation->type.empty() ? "excitation" : sidecar.excitation->type;
  if (sidecar.excitation->frequency_hz) {
    text += " at " + plain(*sidecar.excitation->frequency_hz) + " Hz";
  }
  if (!sidecar.excitation->levels.empty()) {
    text += ", " + std::to_string(sidecar.excitation->levels.size()) + " levels";
  }
  return text;
}

}  // namespace

void write_recording_uff58(const Recording& recording, const std::string& path,
                           const Uff58Options& options) {
  const Sidecar& sidecar = recording.sidecar;
  if (recording.samples_si.cols() != static_cast<Eigen::Index>(sidecar.channels.size())) {
    throw InputError(path + ": the recording has " + std::to_string(sidecar.channels.size()) +
                     " channels in its sidecar but " + std::to_string(recording.samples_si.cols()) +
                     " sample columns");
  }
  if (!(sidecar.sample_rate_hz > 0.0) || !std::isfinite(sidecar.sample_rate_hz)) {
    throw InputError(
        path + ": sample_rate_hz: not a positive rate: " + std::to_string(sidecar.sample_rate_hz));
  }
  if (options.direction < -6 || options.direction > 6) {
    throw InputError(path + ": direction " + std::to_string(options.direction) +
                     ": not a UFF direction (-6 to 6)");
  }
  if (options.base_node < 0 || options.mass_node < 0) {
    throw InputError(path + ": node numbers must not be negative");
  }
  const Eigen::Index n = recording.sample_count();
  if (n == 0) throw InputError(path + ": the recording holds no samples");
  for (Eigen::Index c = 0; c < recording.samples_si.cols(); ++c) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!std::isfinite(recording.samples_si(i, c))) {
        throw InputError(path + ": channel " + sidecar.channels[static_cast<std::size_t>(c)].name +
                         ": sample " + std::to_string(i) +
                         " (t = " + plain(static_cast<double>(i) / sidecar.sample_rate_hz) +
                         " s) is not finite, and UFF 58 has no missing value; export MAT instead");
      }
    }
  }

  const std::string created = options.created.empty() ? date_time_now() : options.created;
  const std::string source =
      recording.source_path.empty()
          ? "NONE"
          : "Oscilab recording " + fs::path(recording.source_path).filename().string();
  const std::string excitation = excitation_text(sidecar);
  const double dt_s = 1.0 / sidecar.sample_rate_hz;

  TemporaryFile file(path);
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> stream(std::fopen(file.path().c_str(), "w"),
                                                         &std::fclose);
  if (!stream) throw InputError(path + ": cannot write: " + std::strerror(errno));
  bool ok = true;
  const auto put = [&](const std::string& text) {
    ok = ok && std::fwrite(text.data(), 1, text.size(), stream.get()) == text.size();
  };
  put(units_dataset());
  std::string line;
  for (std::size_t c = 0; c < sidecar.channels.size(); ++c) {
    const ChannelInfo& channel = sidecar.channels[c];
    const int node = channel.role == ChannelRole::Base ? options.base_node : options.mass_node;
    std::string header(kDelimiter);
    header += i_field(58, 6) + '\n';
    // Records 1–5: ID lines (80A1).
    header += id_line(channel.name + ": " + to_string(channel.role) + " " +
                      to_string(channel.quantity) + " [" + si_unit(channel.quantity) + "]");
    header += id_line(source);
    header += id_line(created);
    header += id_line(excitation);
    header += id_line(channel.sensor);
    // Record 6: Format(2(I5,I10),2(1X,10A1,I10,I4)): function type 1 (time response), function
    // id, version 0, load case 0 (single point excitation), response entity/node/direction,
    // reference entity/node/direction (the table, which excites the structure).
    header += i_field(1, 5) + i_field(static_cast<long long>(c) + 1, 10) + i_field(0, 5) +
              i_field(0, 10) + ' ' + entity_name(channel.name) + i_field(node, 10) +
              i_field(options.direction, 4) + ' ' + entity_name("table") +
              i_field(options.base_node, 10) + i_field(options.direction, 4) + '\n';
    // Record 7: Format(3I10,3E13.5): ordinate type 4 (real, double), points, spacing 1 (even),
    // abscissa minimum, increment, z-axis value.
    header += i_field(4, 10) + i_field(n, 10) + i_field(1, 10) + e_field(0.0, 13, 6) +
              e_field(dt_s, 13, 6) + e_field(0.0, 13, 6) + '\n';
    // Records 8–11: abscissa (17 time), ordinate, ordinate denominator and z axis (unused).
    header += axis_record(17, "Time", "s");
    header += axis_record(specific_data_type(channel), quantity_label(channel.quantity),
                          si_unit(channel.quantity));
    header += axis_record(0, "NONE", "NONE");
    header += axis_record(0, "NONE", "NONE");
    put(header);
    // Record 12: case 5 of the definition (real, double, even): Format(4E20.12).
    for (Eigen::Index i = 0; i < n && ok; i += 4) {
      line.clear();
      for (Eigen::Index k = i; k < std::min(i + 4, n); ++k) {
        line += e_field(recording.samples_si(k, static_cast<Eigen::Index>(c)), 20, 11);
      }
      line += '\n';
      put(line);
    }
    put(std::string(kDelimiter));
  }
  const bool flushed = std::fflush(stream.get()) == 0;
  if (std::fclose(stream.release()) != 0 || !ok || !flushed) {
    throw InputError(path + ": write failed");
  }
  file.commit();
}

}  // namespace oscilab::daq
