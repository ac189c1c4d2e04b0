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
#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <string_view>
#include <system_error>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

constexpr int kHeaderRecords = 11;  // records 1-11 of dataset 58, the "ASCII lines" of 58b
constexpr std::string_view kAliasPrefix = "dataset ";

bool is_blank(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && (is_blank(text.back()) || text.back() == '\r')) text.remove_suffix(1);
  return text;
}

bool is_delimiter(std::string_view line) { return trim(line) == "-1"; }
bool is_blank_line(std::string_view line) { return trim(line).empty(); }

// Text for names and properties: valid UTF-8 (nlohmann::json refuses anything else), control
// characters as '?', trimmed.
std::string clean_text(std::string_view text) {
  text = trim(text);
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t length = c < 0x80         ? 1
                         : (c >> 5) == 6  ? 2
                         : (c >> 4) == 14 ? 3
                         : (c >> 3) == 30 ? 4
                                          : 0;
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      valid = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    }
    if (!valid) {
      out.push_back('?');
      ++i;
    } else if (length == 1 && (c < 0x20 || c == 0x7F)) {
      out.push_back(c == '\t' ? ' ' : '?');
      ++i;
    } else {
      out.append(text.substr(i, length));
      i += length;
    }
  }
  return out;
}

// Byte index of the character `count` characters after byte `from`: Fortran A fields count
// characters, and writers that emit UTF-8 (HBM catman writes "m/s²") pad by characters.
std::size_t advance_characters(std::string_view line, std::size_t from, std::size_t count) {
  std::size_t i = from;
  for (std::size_t k = 0; k < count && i < line.size(); ++k) {
    ++i;
    while (i < line.size() && (static_cast<unsigned char>(line[i]) & 0xC0) == 0x80) ++i;
  }
  return i;
}

// Fixed-column fields of a record: `widths` in characters, the last field runs to the line's end
// when `last_to_end`; a short line gives empty fields.
std::vector<std::string_view> fixed_fields(std::string_view line,
                                           std::initializer_list<std::size_t> widths) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (const std::size_t width : widths) {
    const std::size_t end = advance_characters(line, start, width);
    fields.push_back(line.substr(start, end - start));
    start = end;
  }
  return fields;
}

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (is_blank(line[i]) || line[i] == '\r')) ++i;
    if (i == line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && !is_blank(line[i]) && line[i] != '\r') ++i;
    out.push_back(line.substr(start, i - start));
  }
  return out;
}

// A Fortran I field: blank is 0. Empty optional when it is not an integer.
std::optional<long long> integer_field(std::string_view field) {
  field = trim(field);
  if (field.empty()) return 0;
  if (field.front() == '+') field.remove_prefix(1);
  long long value = 0;
  const auto result = std::from_chars(field.data(), field.data() + field.size(), value);
  if (result.ec != std::errc() || result.ptr != field.data() + field.size()) return std::nullopt;
  return value;
}

// A Fortran E/D field or free-format real: "1.5E-05", "1.5D-05", "0.00000E+000", "+2.0".
// Empty optional when it is not a number or overflows ("1E999"); "nan" and "inf" are numbers.
std::optional<double> real_field(std::string_view field) {
  field = trim(field);
  if (field.empty()) return 0.0;
  if (field.size() > 1 && field.front() == '+' && field[1] != '-' && field[1] != '+') {
    field.remove_prefix(1);
  }
  std::array<char, 64> buffer{};
  if (field.size() >= buffer.size()) return std::nullopt;
  for (std::size_t i = 0; i < field.size(); ++i) {
    buffer[i] = (field[i] == 'D' || field[i] == 'd') ? 'E' : field[i];
  }
  double value = 0.0;
  const auto result = std::from_chars(buffer.data(), buffer.data() + field.size(), value,
                                      std::chars_format::general);
  if (result.ptr != buffer.data() + field.size()) return std::nullopt;
  if (result.ec == std::errc()) return value;
  if (result.ec == std::errc::result_out_of_range) {
    const double parsed = std::strtod(buffer.data(), nullptr);  // underflow: a number
    if (std::isfinite(parsed)) return parsed;
  }
  return std::nullopt;
}

std::string shown(std::string_view text) { return in_quotes(clean_text(text.substr(0, 40))); }

// Function types of record 6 Field 1, as the dataset 58 description lists them.
std::string function_type_name(long long type) {
  static const std::map<long long, const char*> kNames = {{0, "general or unknown"},
                                                          {1, "time response"},
                                                          {2, "auto spectrum"},
                                                          {3, "cross spectrum"},
                                                          {4, "frequency response function"},
                                                          {5, "transmissibility"},
                                                          {6, "coherence"},
                                                          {7, "auto correlation"},
                                                          {8, "cross correlation"},
                                                          {9, "power spectral density"},
                                                          {10, "energy spectral density"},
                                                          {11, "probability density function"},
                                                          {12, "spectrum"},
                                                          {13, "cumulative frequency distribution"},
                                                          {14, "peaks valley"},
                                                          {15, "stress/cycles"},
                                                          {16, "strain/cycles"},
                                                          {17, "orbit"},
                                                          {18, "mode indicator function"},
                                                          {19, "force pattern"},
                                                          {20, "partial power"},
                                                          {21, "partial coherence"},
                                                          {22, "eigenvalue"},
                                                          {23, "eigenvector"},
                                                          {24, "shock response spectrum"},
                                                          {25, "finite impulse response filter"},
                                                          {26, "multiple coherence"},
                                                          {27, "order function"}};
  const auto it = kNames.find(type);
  return it == kNames.end() ? "unknown" : it->second;
}

// Names of the datasets a universal file from a test or FE program commonly holds besides 58.
std::string dataset_name(long long number) {
  static const std::map<long long, const char*> kNames = {{15, "nodes"},
                                                          {18, "coordinate systems"},
                                                          {55, "data at nodes"},
                                                          {82, "trace lines"},
                                                          {151, "header"},
                                                          {164, "units"},
                                                          {1858, "qualifiers for dataset 58"},
                                                          {2400, "model header"},
                                                          {2411, "nodes"},
                                                          {2412, "elements"},
                                                          {2414, "analysis data"},
                                                          {2420, "coordinate systems"},
                                                          {2467, "permanent groups"}};
  const auto it = kNames.find(number);
  return it == kNames.end() ? "" : it->second;
}

// Record 6 Field 7 / 10: ±1..±3 translations along X, Y, Z, ±4..±6 rotations about them.
std::string direction_text(long long direction) {
  static constexpr std::array<const char*, 6> kAxes = {"X", "Y", "Z", "RX", "RY", "RZ"};
  if (direction == 0) return "scalar";
  if (direction >= -6 && direction <= 6) {
    return std::string(direction > 0 ? "+" : "-") + kAxes[std::llabs(direction) - 1];
  }
  return std::to_string(direction);
}

bool unused_text(std::string_view text) {
  text = trim(text);
  return text.empty() || text == "NONE";
}

// Record 8 Field 6: the time unit of the abscissa (minimum and increment). "NONE" or blank: s.
std::optional<double> time_unit_s(std::string_view units) {
  units = trim(units);
  if (unused_text(units) || units == "s" || units == "S" || units == "sec" || units == "Sec" ||
      units == "SEC" || units == "seconds") {
    return 1.0;
  }
  if (units == "ms" || units == "msec") return 1e-3;
  return std::nullopt;
}

// How a real field was printed: digits after the point and the exponent ("1.52588E-05": 5, -5).
void printed_precision(std::string_view text, std::string_view::size_type& decimals,
                       long long& exponent) {
  const std::size_t letter = text.find_first_of("eEdD");
  const std::string_view mantissa = text.substr(0, letter);
  const std::size_t point = mantissa.find('.');
  decimals = point == std::string_view::npos ? 0 : mantissa.size() - point - 1;
  exponent = 0;
  if (letter != std::string_view::npos) {
    exponent = integer_field(text.substr(letter + 1)).value_or(0);
  }
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

// Reads the file a line at a time and keeps the byte offset of the next line, so that binary
// data can be skipped by seeking. Lines lose their '\n' and a '\r' before it.
class LineReader {
 public:
  explicit LineReader(const std::string& path) : in_(path, std::ios::binary) {
    if (!in_) throw InputError(path + ": cannot open: " + std::strerror(errno));
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
    in_.seekg(0);
  }
  std::uint64_t size() const { return size_; }
  std::uint64_t offset() const { return offset_; }
  // "line 17", or "byte 4096" once binary data was skipped (lines are no longer counted).
  std::string where() const {
    return counting_lines_ ? "line " + std::to_string(line_number_)
                           : "byte " + std::to_string(line_offset_);
  }
  long line_number() const { return line_number_; }
  bool counting_lines() const { return counting_lines_; }

  bool next(std::string& line) {
    if (offset_ >= size_) return false;
    line_offset_ = offset_;
    if (!std::getline(in_, line)) return false;
    offset_ += line.size() + (in_.eof() ? 0 : 1);
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_offset_ == 0 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // BOM
    return true;
  }

  // Moves past `bytes` bytes (the caller checked that the file holds them).
  void skip(std::uint64_t bytes) {
    offset_ += bytes;
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset_));
    counting_lines_ = false;
  }

 private:
  std::ifstream in_;
  std::uint64_t size_ = 0;
  std::uint64_t offset_ = 0;
  std::uint64_t line_offset_ = 0;
  long line_number_ = 0;
  bool counting_lines_ = true;
};

// Records 8-11 of dataset 58.
struct Axis {
  long long specific_data_type = 0;
  long long length_exponent = 0;
  long long force_exponent = 0;
  long long temperature_exponent = 0;
  std::string label;
  std::string units;

  nlohmann::json to_json() const {
    return {{"specific_data_type", specific_data_type},
            {"length_unit_exponent", length_exponent},
            {"force_unit_exponent", force_exponent},
            {"temperature_unit_exponent", temperature_exponent},
            {"label", label},
            {"units", units}};
  }
};

struct Dof {
  std::string entity;
  long long node = 0;
  long long direction = 0;
};

// Records 1-11 of one dataset 58 and where its values lie.
struct Dataset58 {
  int index = 0;  // 1-based position among all datasets of the file
  std::array<std::string, 5> id_lines;
  long long function_type = 0;
  long long function_id = 0;
  long long version = 0;
  long long load_case = 0;
  Dof response;
  Dof reference;
  long long ordinate_type = 0;
  long long count = 0;
  long long spacing = 0;
  double abscissa_min = 0.0;
  double abscissa_increment = 0.0;
  std::string_view::size_type increment_decimals = 0;  // digits after the point, as printed
  long long increment_exponent = 0;                    // its decimal exponent, as printed
  double z_value = 0.0;
  std::array<Axis, 4> axes;  // abscissa, ordinate, ordinate denominator, z axis
  bool binary = false;
  int byte_order = 1;  // 1 little-endian, 2 big-endian
  std::uint64_t data_offset = 0;
  std::uint64_t data_bytes = 0;
  long data_line = 0;  // first line of the ASCII values, 0 when unknown
};

// Everything describe finds, before naming.
struct Scan {
  std::vector<Dataset58> time_responses;
  nlohmann::json skipped = nlohmann::json::array();
  int datasets = 0;
  bool any_ascii = false;
  bool any_binary = false;
  std::string byte_orders;
};

class Scanner {
 public:
  explicit Scanner(const std::string& path) : path_(path), reader_(path) {}

  Scan scan() {
    Scan scan;
    std::string line;
    while (reader_.next(line)) {
      if (is_blank_line(line)) continue;
      if (!is_delimiter(line)) {
        fail(reader_.where() + ": expected the line \"    -1\" that opens a dataset, found " +
             shown(line));
      }
      if (!reader_.next(line)) break;  // a last "-1" with nothing after it
      ++scan.datasets;
      dataset_ = scan.datasets;
      read_dataset(line, scan);
    }
    if (scan.datasets == 0)
      fail("no dataset (a universal file holds datasets between \"-1\" lines)");
    return scan;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_ + ": " + problem);
  }
  [[noreturn]] void fail_dataset(const std::string& problem) const {
    fail("dataset " + std::to_string(dataset_) + " (" + reader_.where() + "): " + problem);
  }

  void read_dataset(const std::string& number_line, Scan& scan) {
    const std::vector<std::string_view> fields = tokens(number_line);
    std::string_view number_field = fields.empty() ? std::string_view() : fields.front();
    const bool binary =
        !number_field.empty() && (number_field.back() == 'b' || number_field.back() == 'B');
    if (binary) number_field.remove_suffix(1);
    const std::optional<long long> number =
        number_field.empty() ? std::nullopt : integer_field(number_field);
    if (!number || *number <= 0) {
      fail_dataset("expected a dataset number after the \"-1\" line, found " + shown(number_line));
    }
    std::uint64_t binary_bytes = 0;
    int byte_order = 1;
    if (binary) read_binary_header(fields, *number, binary_bytes, byte_order);

    if (*number != 58) {
      const std::string name = dataset_name(*number);
      scan.skipped.push_back(
          {{"dataset", dataset_},
           {"type", std::to_string(*number) + (binary ? "b" : "")},
           {"reason", name.empty() ? "not dataset 58" : name + ", not dataset 58"}});
      if (binary) {
        skip_binary(binary_bytes);
      } else {
        skip_to_delimiter();
      }
      return;
    }

    Dataset58 set = read_header(binary, byte_order);
    if (binary) {
      check_binary_bytes(binary_bytes);
      set.data_offset = reader_.offset();
      set.data_bytes = binary_bytes;
    }
    if (set.function_type != 1) {
      scan.skipped.push_back(
          {{"dataset", dataset_},
           {"type", binary ? "58b" : "58"},
           {"reason", "function type " + std::to_string(set.function_type) + " (" +
                          function_type_name(set.function_type) + "), not a time response"}});
      if (binary) {
        reader_.skip(binary_bytes);
        expect_closing_delimiter(binary_bytes);
      } else {
        skip_to_delimiter();
      }
      return;
    }
    check_time_response(set);
    if (binary) {
      const std::uint64_t value_bytes = set.ordinate_type == 2 ? 4 : 8;
      if (static_cast<std::uint64_t>(set.count) > binary_bytes / value_bytes ||
          static_cast<std::uint64_t>(set.count) * value_bytes != binary_bytes) {
        fail_dataset("record 7 declares " + std::to_string(set.count) + " values of " +
                     std::to_string(value_bytes) + " bytes, the binary header " +
                     std::to_string(binary_bytes) + " bytes of data");
      }
      reader_.skip(binary_bytes);
      expect_closing_delimiter(binary_bytes);
      scan.any_binary = true;
      const std::string order = byte_order == 1 ? "little-endian" : "big-endian";
      if (scan.byte_orders.find(order) == std::string::npos) {
        scan.byte_orders += (scan.byte_orders.empty() ? "" : " and ") + order;
      }
    } else {
      set.data_offset = reader_.offset();
      set.data_line = reader_.counting_lines() ? reader_.line_number() + 1 : 0;
      const std::uint64_t end = skip_to_delimiter();
      set.data_bytes = end - set.data_offset;
      // A value takes at least one character and is set apart from the next by a blank or by
      // the next one's sign: n values need at least 2n - 1 characters.
      if (static_cast<std::uint64_t>(set.count) > (set.data_bytes + 1) / 2) {
        fail("dataset " + std::to_string(dataset_) + ": record 7 declares " +
             std::to_string(set.count) + " values, but its " + std::to_string(set.data_bytes) +
             " bytes of text cannot hold them");
      }
      scan.any_ascii = true;
    }
    scan.time_responses.push_back(std::move(set));
  }

  // Record 1 of a binary dataset: Format(I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12).
  void read_binary_header(const std::vector<std::string_view>& fields, long long number,
                          std::uint64_t& bytes, int& byte_order) {
    const std::string what = std::to_string(number) + "b";
    if (fields.size() < 5) {
      fail_dataset("the binary header of " + what +
                   " needs byte ordering, floating-point format, number of ASCII lines and "
                   "number of bytes; it has " +
                   std::to_string(fields.size() - 1) + " fields");
    }
    std::array<long long, 4> value{};
    static constexpr std::array<const char*, 4> kNames = {
        "byte ordering", "floating-point format", "number of ASCII lines", "number of bytes"};
    for (std::size_t i = 0; i < 4; ++i) {
      const std::optional<long long> parsed = integer_field(fields[i + 1]);
      if (!parsed) {
        fail_dataset("binary header of " + what + ": " + kNames[i] +
                     " is not an integer: " + shown(fields[i + 1]));
      }
      value[i] = *parsed;
    }
    if (value[0] != 1 && value[0] != 2) {
      fail_dataset("binary header of " + what + ": byte ordering " + std::to_string(value[0]) +
                   " is neither 1 (little-endian) nor 2 (big-endian)");
    }
    if (value[1] != 2) {
      const std::string name = value[1] == 1 ? " (DEC VMS)" : value[1] == 3 ? " (IBM 5/370)" : "";
      fail_dataset("binary header of " + what + ": floating-point format " +
                   std::to_string(value[1]) + name + " is not read; only 2 (IEEE 754) is");
    }
    if (number == 58 && value[2] != kHeaderRecords) {
      fail_dataset("binary header of 58b: " + std::to_string(value[2]) +
                   " ASCII lines announced, dataset 58 has 11");
    }
    if (value[2] < 0 || value[3] < 0) {
      fail_dataset("binary header of " + what + ": negative count of lines or bytes");
    }
    byte_order = static_cast<int>(value[0]);
    bytes = static_cast<std::uint64_t>(value[3]);
    ascii_lines_ = value[2];
  }

  void check_binary_bytes(std::uint64_t bytes) const {
    const std::uint64_t remaining = reader_.size() - reader_.offset();
    if (bytes > remaining) {
      fail("dataset " + std::to_string(dataset_) + ": the binary header announces " +
           std::to_string(bytes) + " bytes of data at byte " + std::to_string(reader_.offset()) +
           ", beyond the end of the file (" + std::to_string(remaining) + " bytes remain)");
    }
  }

  void skip_binary(std::uint64_t bytes) {
    std::string line;
    for (long long i = 0; i < ascii_lines_; ++i) {
      if (!reader_.next(line)) fail_dataset("the file ends within the dataset's ASCII lines");
    }
    check_binary_bytes(bytes);
    reader_.skip(bytes);
    expect_closing_delimiter(bytes);
  }

  // After binary data: blank rest of line(s), then "-1" (or the end of the file).
  void expect_closing_delimiter(std::uint64_t bytes) {
    std::string line;
    while (reader_.next(line)) {
      if (is_delimiter(line)) return;
      if (!is_blank_line(line)) {
        fail_dataset("after the " + std::to_string(bytes) +
                     " bytes of binary data the binary header announces, expected the closing "
                     "\"    -1\", found " +
                     shown(line));
      }
    }
  }

  // Skips lines up to and including the closing "-1"; returns the offset where that line starts
  // (the end of the file when the dataset is the last one and the line is missing).
  std::uint64_t skip_to_delimiter() {
    std::string line;
    for (;;) {
      const std::uint64_t start = reader_.offset();
      if (!reader_.next(line)) return reader_.size();
      if (is_delimiter(line)) return start;
    }
  }

  std::string next_record(int record) {
    std::string line;
    if (!reader_.next(line)) {
      fail("dataset " + std::to_string(dataset_) + ": the file ends within the header, before " +
           "record " + std::to_string(record));
    }
    if (is_delimiter(line)) {
      fail_dataset("the dataset closes within its header, before record " + std::to_string(record));
    }
    return line;
  }

  long long integer(std::string_view field, int record, const char* what) const {
    const std::optional<long long> value = integer_field(field);
    if (!value) {
      fail_dataset("record " + std::to_string(record) + ", " + what +
                   ": not an integer: " + shown(field));
    }
    return *value;
  }

  Dataset58 read_header(bool binary, int byte_order) {
    Dataset58 set;
    set.index = dataset_;
    set.binary = binary;
    set.byte_order = byte_order;
    for (int record = 1; record <= 5; ++record) {
      set.id_lines[record - 1] = clean_text(next_record(record));
    }
    {  // Record 6: Format(2(I5,I10),2(1X,10A1,I10,I4))
      const std::string line = next_record(6);
      const auto f = fixed_fields(line, {5, 10, 5, 10, 1, 10, 10, 4, 1, 10, 10, 4});
      set.function_type = integer(f[0], 6, "function type");
      set.function_id = integer(f[1], 6, "function identification number");
      set.version = integer(f[2], 6, "version number");
      set.load_case = integer(f[3], 6, "load case");
      set.response = {clean_text(f[5]), integer(f[6], 6, "response node"),
                      integer(f[7], 6, "response direction")};
      set.reference = {clean_text(f[9]), integer(f[10], 6, "reference node"),
                       integer(f[11], 6, "reference direction")};
    }
    {  // Record 7: Format(3I10,3E13.5), read as six blank-separated numbers when it splits so
       // (tolerates wider fields), else by its columns (fields that touch).
      const std::string line = next_record(7);
      std::vector<std::string_view> f = tokens(line);
      bool by_tokens = f.size() == 6;
      for (std::size_t i = 0; by_tokens && i < 6; ++i) {
        by_tokens = i < 3 ? integer_field(f[i]).has_value() : real_field(f[i]).has_value();
      }
      if (!by_tokens) f = fixed_fields(line, {10, 10, 10, 13, 13, 13});
      set.ordinate_type = integer(f[0], 7, "ordinate data type");
      set.count = integer(f[1], 7, "number of data values");
      set.spacing = integer(f[2], 7, "abscissa spacing");
      static constexpr std::array<const char*, 3> kReals = {"abscissa minimum",
                                                            "abscissa increment", "z-axis value"};
      std::array<double, 3> reals{};
      for (std::size_t i = 0; i < 3; ++i) {
        const std::optional<double> value = real_field(f[3 + i]);
        if (!value) {
          fail_dataset(std::string("record 7, ") + kReals[i] +
                       ": not a number: " + shown(f[3 + i]));
        }
        reals[i] = *value;
      }
      printed_precision(trim(f[4]), set.increment_decimals, set.increment_exponent);
      set.abscissa_min = reals[0];
      set.abscissa_increment = reals[1];
      set.z_value = reals[2];
    }
    for (int record = 8; record <= 11; ++record) {  // Format(I10,3I5,2(1X,20A1))
      const std::string line = next_record(record);
      const auto f = fixed_fields(line, {10, 5, 5, 5, 1, 20, 1});
      Axis& axis = set.axes[record - 8];
      axis.specific_data_type = integer(f[0], record, "specific data type");
      axis.length_exponent = integer(f[1], record, "length units exponent");
      axis.force_exponent = integer(f[2], record, "force units exponent");
      axis.temperature_exponent = integer(f[3], record, "temperature units exponent");
      axis.label = clean_text(f[5]);
      // The units label is the last field: the rest of the line (some writers pad it by bytes).
      const std::size_t start = advance_characters(line, 0, 10 + 15 + 1 + 20 + 1);
      axis.units = clean_text(std::string_view(line).substr(start, 80));
    }
    return set;
  }

  void check_time_response(const Dataset58& set) const {
    const std::string where = "dataset " + std::to_string(dataset_) + " (time response): ";
    if (set.ordinate_type == 5 || set.ordinate_type == 6) {
      fail(where + "record 7: ordinate data type " + std::to_string(set.ordinate_type) +
           " is complex; a recording is real (2 single, 4 double precision)");
    }
    if (set.ordinate_type != 2 && set.ordinate_type != 4) {
      fail(where + "record 7: unknown ordinate data type " + std::to_string(set.ordinate_type) +
           " (2, 4 real single/double, 5, 6 complex)");
    }
    if (set.spacing == 0) {
      fail(where + "record 7: uneven abscissa spacing (abscissa values stored with each value) " +
           "is not read; a recording needs an even spacing (1)");
    }
    if (set.spacing != 1) {
      fail(where + "record 7: abscissa spacing " + std::to_string(set.spacing) +
           " is neither 0 (uneven) nor 1 (even)");
    }
    if (set.count < 0) {
      fail(where + "record 7: negative number of data values " + std::to_string(set.count));
    }
    const std::optional<double> unit_s = time_unit_s(set.axes[0].units);
    if (!unit_s) {
      fail(where + "record 8: abscissa units " + in_quotes(set.axes[0].units) +
           " are not a time unit (s, ms)");
    }
    const double increment_s = set.abscissa_increment * *unit_s;
    if (!(increment_s > 0.0) || !std::isfinite(increment_s) || !std::isfinite(1.0 / increment_s)) {
      fail(where + "record 7: abscissa increment " + number_text(set.abscissa_increment) +
           " is not a positive time step");
    }
  }

  std::string path_;
  LineReader reader_;
  int dataset_ = 0;
  long long ascii_lines_ = 0;
};

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

// Splits a blank-free token into numbers: Fortran fields may touch ("-1.5E-02-2.5E-02") and
// E fields with three-digit exponents may drop the letter ("1.23456-100").
bool parse_token(std::string_view token, std::vector<double>& values, std::size_t limit,
                 std::string& problem) {
  std::size_t start = 0;
  while (start < token.size()) {
    std::size_t end = start + 1;
    while (end < token.size() &&
           !((token[end] == '-' || token[end] == '+') &&
             std::string_view("eEdD").find(token[end - 1]) == std::string_view::npos)) {
      ++end;
    }
    std::string_view piece = token.substr(start, end - start);
    std::string joined;
    if (end < token.size() && piece.find_first_of("eEdD") == std::string_view::npos &&
        piece.find('.') != std::string_view::npos) {
      // An exponent without its letter: a sign and digits up to the next sign or the end.
      std::size_t next = end + 1;
      while (next < token.size() && token[next] >= '0' && token[next] <= '9') ++next;
      if (next > end + 1 && (next == token.size() || token[next] == '-' || token[next] == '+')) {
        joined = std::string(piece) + "E" + std::string(token.substr(end, next - end));
        piece = joined;
        end = next;
      }
    }
    const std::optional<double> value = real_field(piece);
    if (!value || piece.empty()) {
      problem = "not a finite number: " + shown(token);
      return false;
    }
    if (values.size() == limit) {
      problem = "more values than the " + std::to_string(limit) + " record 7 declares";
      return false;
    }
    values.push_back(*value);
    start = end;
  }
  return true;
}

std::vector<double> read_ascii_values(const std::string& path, const FileSignal& signal,
                                      const std::string& text, long first_line) {
  const auto count = static_cast<std::size_t>(signal.sample_count);
  std::vector<double> values;
  values.reserve(std::min(count, (text.size() + 1) / 2));
  const std::string where_dataset =
      path + ": dataset " + std::to_string(signal.properties.value("dataset", 0));
  std::string problem;
  std::size_t position = 0;
  long line = first_line;
  while (position < text.size()) {
    std::size_t end = text.find('\n', position);
    if (end == std::string::npos) end = text.size();
    const std::string_view row(text.data() + position, end - position);
    std::size_t i = 0;
    while (i < row.size()) {
      while (i < row.size() && (is_blank(row[i]) || row[i] == '\r')) ++i;
      if (i == row.size()) break;
      const std::size_t start = i;
      while (i < row.size() && !is_blank(row[i]) && row[i] != '\r') ++i;
      const std::string_view token = row.substr(start, i - start);
      double value = 0.0;
      const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
      if (result.ec == std::errc() && result.ptr == token.data() + token.size() &&
          values.size() < count) {
        values.push_back(value);
      } else if (!parse_token(token, values, count, problem)) {
        throw InputError(where_dataset +
                         (first_line > 0 ? ", line " + std::to_string(line) : std::string()) +
                         ": " + problem);
      }
    }
    position = end + 1;
    ++line;
  }
  if (values.size() != count) {
    throw InputError(where_dataset + ": record 7 declares " + std::to_string(count) +
                     " values, the dataset holds " + std::to_string(values.size()));
  }
  return values;
}

template <typename Word>
Word byte_swapped(Word word) {
  Word out = 0;
  for (std::size_t i = 0; i < sizeof(Word); ++i) {
    out = static_cast<Word>((out << 8) | ((word >> (8 * i)) & 0xFF));
  }
  return out;
}

template <typename Float, typename Word>
void decode_binary(const std::string& bytes, bool swap, std::vector<double>& values) {
  const std::size_t count = bytes.size() / sizeof(Float);
  values.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    Word word = 0;
    std::memcpy(&word, bytes.data() + i * sizeof(Float), sizeof(Float));
    if (swap) word = byte_swapped(word);
    values[i] = static_cast<double>(std::bit_cast<Float>(word));
  }
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
    Scanner scanner(path);
    const Scan scan = scanner.scan();
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

  // "dataset <k>" also names the time response in dataset k when its name is its DOF.
  Recording read(const std::string& path, const Sidecar& sidecar,
                 const std::string& sidecar_name) const override {
    const auto is_alias = [](const std::string& name) { return name.rfind(kAliasPrefix, 0) == 0; };
    bool aliases = sidecar.time && is_alias(sidecar.time->source);
    for (const ChannelInfo& channel : sidecar.channels) {
      aliases = aliases || is_alias(channel.source.empty() ? channel.name : channel.source);
    }
    if (!aliases) return SignalFileReader::read(path, sidecar, sidecar_name);
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
    Recording recording = SignalFileReader::read(path, resolved, sidecar_name);
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
      return read_ascii_values(path, signal, text, storage.value("first_line", 0L));
    }
    const bool big_endian = storage.value("byte_order", "") == "big-endian";
    const bool swap = big_endian != (std::endian::native == std::endian::big);
    std::vector<double> values;
    if (signal.stored_type == "float32") {
      decode_binary<float, std::uint32_t>(text, swap, values);
    } else {
      decode_binary<double, std::uint64_t>(text, swap, values);
    }
    return values;
  }
};

}  // namespace

const FormatReader& uff_format() {
  static const UffFormat format;
  return format;
}

}  // namespace oscilab::daq
