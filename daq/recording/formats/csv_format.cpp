// Delimited text (CSV, TSV): read with a header naming the columns or with the sidecar's
// "column"s, an optional time column checked against the rate; written with a t_s column.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>
#include <system_error>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/formats.h"
#include "daq/recording/stored_samples.h"

namespace oscilab::daq {
namespace {

bool is_text_extension(std::string_view extension) {
  return extension == ".csv" || extension == ".tsv" || extension == ".txt";
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

bool blank_line(std::string_view line) {
  return std::all_of(line.begin(), line.end(), [](char c) { return is_blank(c); });
}

// Splits on `delimiter`; ' ' splits on runs of spaces and tabs.
void split(std::string_view line, char delimiter, std::vector<std::string_view>& cells) {
  cells.clear();
  if (delimiter == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_blank(line[i])) ++i;
      if (i == line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !is_blank(line[i])) ++i;
      cells.push_back(line.substr(start, i - start));
    }
    return;
  }
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = line.find(delimiter, start);
    if (end == std::string_view::npos) {
      cells.push_back(line.substr(start));
      return;
    }
    cells.push_back(line.substr(start, end - start));
    start = end + 1;
  }
}

// A cell without surrounding blanks and quotes.
std::string_view clean_cell(std::string_view cell) {
  while (!cell.empty() && is_blank(cell.front())) cell.remove_prefix(1);
  while (!cell.empty() && is_blank(cell.back())) cell.remove_suffix(1);
  if (cell.size() >= 2 && cell.front() == '"' && cell.back() == '"') {
    cell = cell.substr(1, cell.size() - 2);
    while (!cell.empty() && is_blank(cell.front())) cell.remove_prefix(1);
    while (!cell.empty() && is_blank(cell.back())) cell.remove_suffix(1);
  }
  return cell;
}

// Parses a number cell; returns an empty string on success, else the problem.
std::string parse_number(std::string_view cell, double& value) {
  cell = clean_cell(cell);
  if (cell.empty()) return "empty cell";
  std::string_view digits = cell;
  if (digits.size() > 1 && digits.front() == '+' && digits[1] != '-' && digits[1] != '+') {
    digits.remove_prefix(1);
  }
  const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value,
                                      std::chars_format::general);
  if (result.ptr == digits.data() + digits.size()) {
    if (result.ec == std::errc()) return "";
    if (result.ec == std::errc::result_out_of_range) {
      // Underflow to a subnormal or zero is a number; overflow is not.
      const double parsed = std::strtod(std::string(digits).c_str(), nullptr);
      if (std::isfinite(parsed)) {
        value = parsed;
        return "";
      }
      return "number out of range: " + in_quotes(std::string(cell.substr(0, 40)));
    }
  }
  return "not a number: " + in_quotes(std::string(cell.substr(0, 40)));
}

class CsvLineReader {
 public:
  explicit CsvLineReader(const std::string& path) : in_(path, std::ios::binary) {
    std::error_code error;
    size_bytes_ = static_cast<double>(std::filesystem::file_size(path, error));
    if (error) size_bytes_ = 0.0;
  }
  bool is_open() const { return static_cast<bool>(in_); }
  /// The share of the file read so far (0 when its size is unknown).
  double share_read() {
    const auto at = in_.tellg();
    if (!(size_bytes_ > 0.0) || at < 0) return 0.0;
    return std::min(1.0, static_cast<double>(at) / size_bytes_);
  }
  bool bad() const { return in_.bad(); }
  long line_number() const { return line_number_; }
  const std::string& line() const { return line_; }

  bool next() {
    if (!std::getline(in_, line_)) return false;
    ++line_number_;
    if (!line_.empty() && line_.back() == '\r') line_.pop_back();
    if (line_number_ == 1 && line_.rfind("\xEF\xBB\xBF", 0) == 0) line_.erase(0, 3);  // BOM
    return true;
  }

 private:
  std::ifstream in_;
  std::string line_;
  long line_number_ = 0;
  double size_bytes_ = 0.0;
};

// Lines between two looks at the opening's control: a few milliseconds of parsing.
constexpr long kLinesPerPoll = 4096;

// Where each channel and the time are in a row, and how many cells a row has.
struct ColumnMap {
  std::vector<std::size_t> column;  // per channel
  long time_column = -1;            // -1: none
  std::size_t expected_cells = 0;   // 0: set by the first data row
};

// The sidecar's 0-based "column"s (and csv.time_column) against the `available` cells; throws
// InputError naming the channel and `what` (the line) when one is beyond them.
void check_columns(const std::string& path, const Sidecar& sidecar, std::size_t available,
                   const std::string& what, ColumnMap& map) {
  for (std::size_t c = 0; c < sidecar.channels.size(); ++c) {
    const ChannelInfo& channel = sidecar.channels[c];
    if (channel.column >= 0 && static_cast<std::size_t>(channel.column) >= available) {
      throw InputError(path + ": " + what + ": channel " + in_quotes(channel.name) +
                       " reads column " + std::to_string(channel.column) +
                       " (0-based), but there are only " + std::to_string(available));
    }
    if (channel.column >= 0) map.column[c] = static_cast<std::size_t>(channel.column);
  }
  if (map.time_column >= 0 && static_cast<std::size_t>(map.time_column) >= available) {
    throw InputError(path + ": " + what + ": csv.time_column is " +
                     std::to_string(map.time_column) + " (0-based), but there are only " +
                     std::to_string(available) + " columns");
  }
}

// The header line: the first line not blank. Each channel without a "column" is found by its
// name (once), the time by "t_s" unless csv.time_column says; a time column that is also a
// channel's is read as the channel.
void read_header(CsvLineReader& reader, const std::string& path, const Sidecar& sidecar,
                 const std::string& sidecar_name, const CsvLayout& layout, ColumnMap& map) {
  bool found = false;
  while (reader.next()) {
    if (!blank_line(reader.line())) {
      found = true;
      break;
    }
  }
  if (!found) throw InputError(path + ": no samples (empty file: no header line)");
  const std::string where = "line " + std::to_string(reader.line_number());
  std::vector<std::string_view> cells;
  split(reader.line(), layout.delimiter, cells);
  std::vector<std::string> names;
  for (const std::string_view cell : cells) names.emplace_back(clean_cell(cell));
  map.expected_cells = names.size();
  check_columns(path, sidecar, map.expected_cells, where + " (header)", map);
  for (std::size_t c = 0; c < sidecar.channels.size(); ++c) {
    const ChannelInfo& channel = sidecar.channels[c];
    if (channel.column >= 0) continue;
    const auto matches = std::count(names.begin(), names.end(), channel.name);
    if (matches == 0) {
      std::string list;
      for (std::size_t i = 0; i < names.size() && i < 12; ++i) {
        list += (i == 0 ? "" : ", ") + in_quotes(names[i].substr(0, 40));
      }
      if (names.size() > 12) list += ", ...";
      const bool numeric = std::all_of(names.begin(), names.end(), [](const std::string& name) {
        double value = 0.0;
        return parse_number(name, value).empty();
      });
      throw InputError(path + ": " + where + ": the header has no column " +
                       in_quotes(channel.name) + " for that channel of " + sidecar_name +
                       " (found " + list + ")" +
                       (numeric ? "; a file without a header needs \"csv\": {\"header\": "
                                  "false} and a \"column\" for each channel"
                                : ""));
    }
    if (matches > 1) {
      throw InputError(path + ": " + where + ": the header names " + in_quotes(channel.name) +
                       " more than once");
    }
    map.column[c] = static_cast<std::size_t>(std::find(names.begin(), names.end(), channel.name) -
                                             names.begin());
  }
  if (map.time_column < 0) {
    const auto it = std::find(names.begin(), names.end(), "t_s");
    if (it != names.end()) map.time_column = it - names.begin();
  }
  for (std::size_t c = 0; c < sidecar.channels.size(); ++c) {
    if (static_cast<long>(map.column[c]) == map.time_column) map.time_column = -1;
  }
}

// The data rows: blank lines skipped, every row with the header's (or the first row's) number of
// cells, every channel's cell a number, the time column (when there is one) on the sidecar's
// rate. Throws InputError naming the line and column.
StoredSamples read_rows(CsvLineReader& reader, const std::string& path, const Sidecar& sidecar,
                        const std::string& sidecar_name, const CsvLayout& layout, ColumnMap& map,
                        const OpeningControl& control) {
  StoredSamples stored;
  TimeAxisCheck time_check(sidecar.sample_rate_hz, sidecar_name);
  const auto cell_error = [&](std::size_t index, const std::string& what,
                              const std::string& problem) {
    throw InputError(path + ": line " + std::to_string(reader.line_number()) + ", column " +
                     std::to_string(index + 1) + " (" + what + "): " + problem);
  };
  std::vector<std::string_view> cells;
  while (reader.next()) {
    if (reader.line_number() % kLinesPerPoll == 0) {
      if (control.cancel.cancelled()) throw OpeningCancelled();
      if (control.progress) control.progress(reader.share_read());
    }
    if (blank_line(reader.line())) continue;
    split(reader.line(), layout.delimiter, cells);
    if (map.expected_cells == 0) {
      map.expected_cells = cells.size();
      check_columns(path, sidecar, map.expected_cells,
                    "line " + std::to_string(reader.line_number()), map);
    }
    if (cells.size() != map.expected_cells) {
      throw InputError(path + ": line " + std::to_string(reader.line_number()) + ": expected " +
                       std::to_string(map.expected_cells) + " columns, found " +
                       std::to_string(cells.size()) + " (truncated or malformed row)");
    }
    for (std::size_t c = 0; c < sidecar.channels.size(); ++c) {
      double value = 0.0;
      const std::string problem = parse_number(cells[map.column[c]], value);
      if (!problem.empty()) {
        cell_error(map.column[c], "channel " + in_quotes(sidecar.channels[c].name), problem);
      }
      stored.values.push_back(value);
    }
    stored.lines.push_back(reader.line_number());
    if (map.time_column >= 0) {
      const auto index = static_cast<std::size_t>(map.time_column);
      double t_s = 0.0;
      const std::string problem = parse_number(cells[index], t_s);
      if (!problem.empty()) cell_error(index, "time", problem);
      if (const std::string time_problem = time_check.next(t_s); !time_problem.empty()) {
        cell_error(index, "time", time_problem);
      }
    }
  }
  if (reader.bad()) throw InputError(path + ": cannot read: " + std::strerror(errno));
  if (stored.lines.empty()) throw InputError(path + ": no samples (the file holds no data rows)");
  return stored;
}

Recording read_csv(const std::string& path, const Sidecar& sidecar, const std::string& sidecar_name,
                   const OpeningControl& control) {
  CsvLayout layout;
  if (sidecar.csv) {
    layout = *sidecar.csv;
  } else if (lower_extension(path) == ".tsv") {
    layout.delimiter = '\t';
  }
  CsvLineReader reader(path);
  if (!reader.is_open()) throw InputError(path + ": cannot open: " + std::strerror(errno));
  for (int i = 0; i < layout.skip_lines; ++i) {
    if (!reader.next()) {
      throw InputError(path + ": no samples: the file ends within the " +
                       std::to_string(layout.skip_lines) + " lines csv.skip_lines skips");
    }
  }
  ColumnMap map;
  map.column.assign(sidecar.channels.size(), 0);
  map.time_column = layout.time_column;
  if (layout.header) read_header(reader, path, sidecar, sidecar_name, layout, map);
  const StoredSamples stored = read_rows(reader, path, sidecar, sidecar_name, layout, map, control);

  Recording recording;
  recording.sidecar = sidecar;
  recording.samples_si = calibrate(stored, sidecar, path);
  recording.samples_stored = as_matrix(stored, recording.samples_si.cols());
  recording.source_path = path;
  std::string delimiter = layout.delimiter == '\t'  ? "tab"
                          : layout.delimiter == ' ' ? "spaces"
                                                    : in_quotes(std::string(1, layout.delimiter));
  recording.container = std::string("CSV, ") + (layout.header ? "with" : "without") +
                        " header, delimiter " + delimiter;
  if (control.cancel.cancelled()) throw OpeningCancelled();
  if (control.progress) control.progress(1.0);
  return recording;
}

// Shortest text that reads back as the same double (std::to_chars round-trip guarantee).
void append_exact(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

class CsvFormat final : public FormatReader {
 public:
  std::string_view format_name() const override { return "CSV"; }
  bool matches_signature(std::string_view /*head*/) const override { return false; }
  bool matches_extension(std::string_view extension) const override {
    return is_text_extension(extension);
  }

  FileContents describe(const std::string& path) const override {
    CsvLineReader reader(path);
    if (!reader.is_open()) throw InputError(path + ": cannot open: " + std::strerror(errno));
    FileContents contents;
    contents.container = "CSV";
    contents.picked_by_source = false;
    const char delimiter = lower_extension(path) == ".tsv" ? '\t' : ',';
    std::vector<std::string_view> cells;
    std::vector<std::string> names;
    std::int64_t rows = 0;
    int time_column = -1;
    std::vector<double> first_times;
    while (reader.next()) {
      if (blank_line(reader.line())) continue;
      split(reader.line(), delimiter, cells);
      if (names.empty()) {
        for (std::size_t i = 0; i < cells.size(); ++i) {
          names.emplace_back(clean_cell(cells[i]));
          if (names.back() == "t_s") time_column = static_cast<int>(i);
        }
        continue;
      }
      ++rows;
      // The rate from the first two times of a t_s column.
      if (time_column >= 0 && first_times.size() < 2 &&
          static_cast<std::size_t>(time_column) < cells.size()) {
        double t_s = 0.0;
        if (parse_number(cells[static_cast<std::size_t>(time_column)], t_s).empty()) {
          first_times.push_back(t_s);
        }
      }
    }
    std::optional<double> rate_hz;
    if (first_times.size() == 2 && first_times[1] > first_times[0]) {
      rate_hz = 1.0 / (first_times[1] - first_times[0]);
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      FileSignal signal;
      signal.name = names[i];
      signal.sample_count = rows;
      signal.sample_rate_hz = rate_hz;
      signal.properties["column"] = i;
      contents.file_signals.push_back(std::move(signal));
    }
    return contents;
  }

  Recording read(const std::string& path, const Sidecar& sidecar,
                 const std::string& sidecar_name) const override {
    return read_csv(path, sidecar, sidecar_name, {});
  }
  /// Reports the share of the file's bytes read and polls the token every 4096 lines.
  Recording read_controlled(const std::string& path, const Sidecar& sidecar,
                            const std::string& sidecar_name,
                            const OpeningControl& control) const override {
    if (control.cancel.cancelled()) throw OpeningCancelled();
    return read_csv(path, sidecar, sidecar_name, control);
  }
};

}  // namespace

const FormatReader& csv_format() {
  static const CsvFormat format;
  return format;
}

void write_csv(const std::vector<double>& stored, const Sidecar& sidecar,
               const std::string& file_path, const std::string& path) {
  std::string text = "t_s";
  for (const ChannelInfo& channel : sidecar.channels) {
    if (channel.name.find_first_of(",\"") != std::string::npos) {
      throw InputError(path + ": channel " + in_quotes(channel.name) +
                       ": a name with a comma or a quote cannot head a CSV column");
    }
    text += "," + channel.name;
  }
  text += "\n";
  std::ofstream out(file_path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(path + ": cannot write: " + std::strerror(errno));
  const std::size_t channels = sidecar.channels.size();
  const std::size_t rows = stored.size() / channels;
  for (std::size_t r = 0; r < rows; ++r) {
    append_exact(text, static_cast<double>(r) / sidecar.sample_rate_hz);
    for (std::size_t c = 0; c < channels; ++c) {
      text += ',';
      append_exact(text, stored[r * channels + c]);
    }
    text += '\n';
    if (text.size() > (1u << 20)) {
      out << text;
      text.clear();
    }
  }
  out << text;
  out.flush();
  if (!out) throw InputError(path + ": cannot write: " + std::strerror(errno));
}

}  // namespace oscilab::daq
