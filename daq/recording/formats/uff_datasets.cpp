#include "daq/recording/formats/uff_datasets.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/uff_fields.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq::uff {
namespace {

constexpr int kHeaderRecords = 11;  // records 1-11 of dataset 58, the "ASCII lines" of 58b

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

}  // namespace

Scan scan_datasets(const std::string& path) { return Scanner(path).scan(); }

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

std::optional<double> time_unit_s(std::string_view units) {
  units = trim(units);
  if (unused_text(units)) return 1.0;
  // Instruments write the unit in any case, some in parentheses or brackets: a Data Translation
  // DT9837 writes "(Sec)", others "Sec", "sec", "Seconds", "[s]".
  if (units.size() >= 2 && ((units.front() == '(' && units.back() == ')') ||
                            (units.front() == '[' && units.back() == ']'))) {
    units = trim(units.substr(1, units.size() - 2));
  }
  std::string lower(units);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* name : {"s", "sec", "secs", "second", "seconds"}) {
    if (lower == name) return 1.0;
  }
  for (const char* name : {"ms", "msec", "msecs", "millisecond", "milliseconds"}) {
    if (lower == name) return 1e-3;
  }
  return std::nullopt;
}

}  // namespace oscilab::daq::uff
