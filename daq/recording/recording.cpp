#include "daq/recording/recording.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include <sndfile.h>
#include <unistd.h>

#include "analysis/common/input_error.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::daq {
namespace {

namespace fs = std::filesystem;

std::string in_quotes(const std::string& text) { return "\"" + text + "\""; }

std::string number_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

// Shortest text that reads back as the same double (std::to_chars round-trip guarantee).
void append_exact(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

std::string lower_extension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool is_text_extension(const std::string& extension) {
  return extension == ".csv" || extension == ".tsv" || extension == ".txt";
}

void check_data_file(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(path + ": file not found");
  if (!fs::is_regular_file(status)) throw InputError(path + ": cannot read: not a regular file");
}

// Samples as stored in a file, interleaved: row r, channel c at values[r * channels + c].
struct StoredSamples {
  std::vector<double> values;
  std::vector<long> lines;  // CSV only: the file line of each row, for messages
};

// Where sample `row` sits, for messages: "sample 42 (t = 0.082 s, line 44)".
std::string sample_place(Eigen::Index row, double sample_rate_hz, const StoredSamples& stored) {
  std::string text = "sample " + std::to_string(row) +
                     " (t = " + number_text(static_cast<double>(row) / sample_rate_hz) + " s";
  if (!stored.lines.empty()) text += ", line " + std::to_string(stored.lines[row]);
  return text + ")";
}

// Whether sample `row` lies inside one of the sidecar's invalid intervals (a live recording's gap
// or bad samples), where non-finite values are what was recorded and are allowed.
bool declared_invalid(const Sidecar& sidecar, Eigen::Index row) {
  const double t_s = static_cast<double>(row) / sidecar.sample_rate_hz;
  const double half_sample_s = 0.5 / sidecar.sample_rate_hz;
  for (const InvalidInterval& interval : sidecar.invalid_intervals) {
    if (t_s >= interval.start_s - half_sample_s && t_s <= interval.end_s + half_sample_s) {
      return true;
    }
  }
  return false;
}

// physical = scale × stored + offset in the channel's unit, then × unit factor → SI.
// Non-finite samples are an error unless the sidecar declares them invalid.
Eigen::MatrixXd calibrate(const StoredSamples& stored, const Sidecar& sidecar,
                          const std::string& path) {
  const auto channels = static_cast<Eigen::Index>(sidecar.channels.size());
  const Eigen::Index rows = static_cast<Eigen::Index>(stored.values.size()) / channels;
  Eigen::MatrixXd samples(rows, channels);
  for (Eigen::Index c = 0; c < channels; ++c) {
    const ChannelInfo& channel = sidecar.channels[c];
    const double factor = unit_to_si(channel.unit, channel.quantity, path);
    Eigen::Index first_bad = -1;
    Eigen::Index bad_count = 0;
    for (Eigen::Index r = 0; r < rows; ++r) {
      const double value = stored.values[r * channels + c];
      const double si = (channel.scale * value + channel.offset) * factor;
      samples(r, c) = si;
      if (!std::isfinite(si) && !declared_invalid(sidecar, r)) {
        if (first_bad < 0) first_bad = r;
        ++bad_count;
      }
    }
    if (first_bad < 0) continue;
    const double value = stored.values[first_bad * channels + c];
    std::string problem = std::isnan(value) ? "is NaN"
                          : std::isinf(value)
                              ? "is infinite"
                              : "(" + number_text(value) + ") overflows after calibration (scale " +
                                    number_text(channel.scale) + ")";
    throw InputError(path + ": channel " + in_quotes(channel.name) + ": " +
                     sample_place(first_bad, sidecar.sample_rate_hz, stored) + " " + problem +
                     "; " + std::to_string(bad_count) + " of " + std::to_string(rows) +
                     " samples of this channel are not finite");
  }
  return samples;
}

// The interleaved stored values as a matrix: one row per sample, one column per channel.
Eigen::MatrixXd as_matrix(const StoredSamples& stored, Eigen::Index channels) {
  const Eigen::Index rows = static_cast<Eigen::Index>(stored.values.size()) / channels;
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      stored.values.data(), rows, channels);
}

// --- sound containers (libsndfile) ---------------------------------------------------------

struct SndfileCloser {
  void operator()(SNDFILE* file) const { sf_close(file); }
};
using SndfileHandle = std::unique_ptr<SNDFILE, SndfileCloser>;

std::string format_name(int format) {
  SF_FORMAT_INFO info{};
  info.format = format;
  if (sf_command(nullptr, SFC_GET_FORMAT_INFO, &info, sizeof info) != 0 || info.name == nullptr) {
    return "format 0x" + [&] {
      char buffer[16];
      std::snprintf(buffer, sizeof buffer, "%x", static_cast<unsigned>(format));
      return std::string(buffer);
    }();
  }
  return info.name;
}

// "WAV (Microsoft), 64 bit float".
std::string container_name(int format) {
  return format_name(format & SF_FORMAT_TYPEMASK) + ", " + format_name(format & SF_FORMAT_SUBMASK);
}

// libsndfile shortens a truncated WAV/W64/RF64/AIFF/CAF silently to the bytes present and only
// logs it: "data : 16000 (should be 14997)". Find that line; sizes 0 and 0xFFFFFFFF are the
// placeholders of streaming writers, not truncation.
std::string truncation_in_log(SNDFILE* file) {
  std::vector<char> log(16384, '\0');
  sf_command(file, SFC_GET_LOG_INFO, log.data(), static_cast<int>(log.size()) - 1);
  std::istringstream lines(std::string(log.data()));
  std::string line;
  while (std::getline(lines, line)) {
    const auto start = line.find_first_not_of(' ');
    if (start == std::string::npos) continue;
    const std::string_view text(line.c_str() + start);
    if (text.rfind("data", 0) != 0 && text.rfind("SSND", 0) != 0) continue;
    const auto colon = text.find(':');
    const auto should = text.find("(should be ");
    if (colon == std::string_view::npos || should == std::string_view::npos) continue;
    const long long declared =
        std::strtoll(std::string(text.substr(colon + 1)).c_str(), nullptr, 10);
    const long long present =
        std::strtoll(std::string(text.substr(should + 11)).c_str(), nullptr, 10);
    if (declared <= present || declared == 0 || declared == 0xFFFFFFFFLL) continue;
    return "truncated: the header promises " + std::to_string(declared) +
           " bytes of samples, the file holds " + std::to_string(present);
  }
  return "";
}

Recording read_sound(const std::string& path, const Sidecar& sidecar,
                     const std::string& sidecar_name) {
  SF_INFO info{};
  SndfileHandle file(sf_open(path.c_str(), SFM_READ, &info));
  if (!file) {
    throw InputError(path + ": not a sound file libsndfile can read (" + sf_strerror(nullptr) +
                     ")");
  }
  const auto channels = static_cast<int>(sidecar.channels.size());
  if (info.channels != channels) {
    throw InputError(path + ": the file holds " + std::to_string(info.channels) + " channels, " +
                     sidecar_name + " lists " + std::to_string(channels));
  }
  // The container stores an integer rate; the sidecar's (possibly measured, fractional) rate
  // must round to it.
  if (!(std::abs(sidecar.sample_rate_hz - info.samplerate) < 0.5)) {
    throw InputError(path + ": the file's sample rate is " + std::to_string(info.samplerate) +
                     " Hz, " + sidecar_name + " says " + number_text(sidecar.sample_rate_hz) +
                     " Hz");
  }
  if (const std::string truncation = truncation_in_log(file.get()); !truncation.empty()) {
    throw InputError(path + ": " + truncation);
  }
  // Integer formats read as their integer counts, not normalised to ±1 (see ChannelInfo).
  sf_command(file.get(), SFC_SET_NORM_DOUBLE, nullptr, SF_FALSE);

  StoredSamples stored;
  constexpr sf_count_t kBlockFrames = 8192;
  std::vector<double> block(static_cast<std::size_t>(kBlockFrames) * channels);
  sf_count_t frames = 0;
  for (;;) {
    const sf_count_t got = sf_readf_double(file.get(), block.data(), kBlockFrames);
    if (got <= 0) break;
    stored.values.insert(stored.values.end(), block.begin(), block.begin() + got * channels);
    frames += got;
  }
  if (sf_error(file.get()) != SF_ERR_NO_ERROR) {
    throw InputError(path + ": cannot read the samples: " + sf_strerror(file.get()));
  }
  if (frames == 0) throw InputError(path + ": no samples (empty recording)");
  if (info.frames != std::numeric_limits<sf_count_t>::max() && frames < info.frames) {
    throw InputError(path + ": truncated: the header promises " + std::to_string(info.frames) +
                     " samples per channel, the file holds " + std::to_string(frames));
  }

  Recording recording;
  recording.sidecar = sidecar;
  recording.samples_si = calibrate(stored, sidecar, path);
  recording.samples_stored = as_matrix(stored, recording.samples_si.cols());
  recording.source_path = path;
  recording.container = container_name(info.format);
  return recording;
}

// --- CSV -----------------------------------------------------------------------------------

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
  explicit CsvLineReader(const std::string& path) : in_(path, std::ios::binary) {}
  bool is_open() const { return static_cast<bool>(in_); }
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
};

Recording read_csv(const std::string& path, const Sidecar& sidecar,
                   const std::string& sidecar_name) {
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

  const std::size_t channel_count = sidecar.channels.size();
  std::vector<std::size_t> column(channel_count, 0);
  long time_column = layout.time_column;
  std::size_t expected_cells = 0;  // 0: set by the first data row
  std::vector<std::string_view> cells;
  std::string where;  // "line N" of the header, for messages about columns

  auto check_columns = [&](std::size_t available, const std::string& what) {
    for (std::size_t c = 0; c < channel_count; ++c) {
      const ChannelInfo& channel = sidecar.channels[c];
      if (channel.column >= 0 && static_cast<std::size_t>(channel.column) >= available) {
        throw InputError(path + ": " + what + ": channel " + in_quotes(channel.name) +
                         " reads column " + std::to_string(channel.column) +
                         " (0-based), but there are only " + std::to_string(available));
      }
      if (channel.column >= 0) column[c] = static_cast<std::size_t>(channel.column);
    }
    if (time_column >= 0 && static_cast<std::size_t>(time_column) >= available) {
      throw InputError(path + ": " + what + ": csv.time_column is " + std::to_string(time_column) +
                       " (0-based), but there are only " + std::to_string(available) + " columns");
    }
  };

  if (layout.header) {
    bool found = false;
    while (reader.next()) {
      if (!blank_line(reader.line())) {
        found = true;
        break;
      }
    }
    if (!found) throw InputError(path + ": no samples (empty file: no header line)");
    where = "line " + std::to_string(reader.line_number());
    split(reader.line(), layout.delimiter, cells);
    std::vector<std::string> names;
    for (const std::string_view cell : cells) names.emplace_back(clean_cell(cell));
    expected_cells = names.size();
    check_columns(expected_cells, where + " (header)");
    for (std::size_t c = 0; c < channel_count; ++c) {
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
      column[c] = static_cast<std::size_t>(std::find(names.begin(), names.end(), channel.name) -
                                           names.begin());
    }
    if (time_column < 0) {
      const auto it = std::find(names.begin(), names.end(), "t_s");
      if (it != names.end()) time_column = it - names.begin();
    }
    for (std::size_t c = 0; c < channel_count; ++c) {
      if (static_cast<long>(column[c]) == time_column) time_column = -1;  // read as a channel
    }
  }

  StoredSamples stored;
  const double rate_hz = sidecar.sample_rate_hz;
  double t0_s = 0.0;
  double previous_t_s = 0.0;
  long row = 0;
  auto cell_error = [&](std::size_t index, const std::string& what, const std::string& problem) {
    throw InputError(path + ": line " + std::to_string(reader.line_number()) + ", column " +
                     std::to_string(index + 1) + " (" + what + "): " + problem);
  };
  while (reader.next()) {
    if (blank_line(reader.line())) continue;
    split(reader.line(), layout.delimiter, cells);
    if (expected_cells == 0) {
      expected_cells = cells.size();
      check_columns(expected_cells, "line " + std::to_string(reader.line_number()));
    }
    if (cells.size() != expected_cells) {
      throw InputError(path + ": line " + std::to_string(reader.line_number()) + ": expected " +
                       std::to_string(expected_cells) + " columns, found " +
                       std::to_string(cells.size()) + " (truncated or malformed row)");
    }
    for (std::size_t c = 0; c < channel_count; ++c) {
      double value = 0.0;
      const std::string problem = parse_number(cells[column[c]], value);
      if (!problem.empty())
        cell_error(column[c], "channel " + in_quotes(sidecar.channels[c].name), problem);
      stored.values.push_back(value);
    }
    stored.lines.push_back(reader.line_number());
    if (time_column >= 0) {
      const auto index = static_cast<std::size_t>(time_column);
      double t_s = 0.0;
      const std::string problem = parse_number(cells[index], t_s);
      if (!problem.empty()) cell_error(index, "time", problem);
      if (!std::isfinite(t_s)) cell_error(index, "time", "the time is not finite");
      if (row == 0) t0_s = t_s;
      if (row > 0 && !(t_s > previous_t_s)) {
        cell_error(index, "time",
                   "time " + number_text(t_s) + " s does not increase (previous " +
                       number_text(previous_t_s) + " s)");
      }
      // Half a sample: a skipped or repeated sample, or a rate that differs from the sidecar's
      // by more than 1/(2 n) after n samples, shows; timestamp rounding below that does not.
      const double expected_t_s = t0_s + static_cast<double>(row) / rate_hz;
      if (std::abs(t_s - expected_t_s) > 0.5 / rate_hz) {
        cell_error(index, "time",
                   "time " + number_text(t_s) + " s does not fit " + sidecar_name +
                       "'s sample_rate_hz " + number_text(rate_hz) + " (sample " +
                       std::to_string(row) + " should be at " + number_text(expected_t_s) + " s)");
      }
      previous_t_s = t_s;
    }
    ++row;
  }
  if (reader.bad()) throw InputError(path + ": cannot read: " + std::strerror(errno));
  if (row == 0) throw InputError(path + ": no samples (the file holds no data rows)");

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
  return recording;
}

// --- writing -------------------------------------------------------------------------------

int sound_format_for(const std::string& extension) {
  if (extension == ".wav") return SF_FORMAT_WAV | SF_FORMAT_DOUBLE;
  if (extension == ".w64") return SF_FORMAT_W64 | SF_FORMAT_DOUBLE;
  if (extension == ".rf64") return SF_FORMAT_RF64 | SF_FORMAT_DOUBLE;
  if (extension == ".aif" || extension == ".aiff" || extension == ".aifc") {
    return SF_FORMAT_AIFF | SF_FORMAT_DOUBLE;
  }
  if (extension == ".caf") return SF_FORMAT_CAF | SF_FORMAT_DOUBLE;
  if (extension == ".flac") return SF_FORMAT_FLAC | SF_FORMAT_PCM_24;
  return 0;
}

// FLAC holds 24-bit integers.
constexpr double kFlacMin = -8388608.0;  // -2^23
constexpr double kFlacMax = 8388607.0;   // 2^23 - 1

void write_sound(const std::vector<double>& stored, const Sidecar& sidecar, int format,
                 const std::string& file_path, const std::string& path) {
  const auto channels = static_cast<int>(sidecar.channels.size());
  const double rate_hz = std::round(sidecar.sample_rate_hz);
  if (!(rate_hz >= 1.0 && rate_hz <= std::numeric_limits<int>::max())) {
    throw InputError(path + ": a sound container cannot store the sample rate " +
                     number_text(sidecar.sample_rate_hz) + " Hz");
  }
  SF_INFO info{};
  info.samplerate = static_cast<int>(rate_hz);
  info.channels = channels;
  info.format = format;
  if (sf_format_check(&info) == SF_FALSE) {
    throw InputError(path + ": " + container_name(format) + " cannot store " +
                     std::to_string(channels) + " channels at " + number_text(rate_hz) + " Hz");
  }
  SndfileHandle file(sf_open(file_path.c_str(), SFM_WRITE, &info));
  if (!file) throw InputError(path + ": cannot write: " + sf_strerror(nullptr));
  sf_command(file.get(), SFC_SET_NORM_DOUBLE, nullptr, SF_FALSE);  // integers are counts
  const auto frames = static_cast<sf_count_t>(stored.size() / channels);
  if (sf_writef_double(file.get(), stored.data(), frames) != frames) {
    throw InputError(path + ": cannot write: " + sf_strerror(file.get()));
  }
  const int closed = sf_close(file.release());
  if (closed != 0) throw InputError(path + ": cannot write: " + sf_error_number(closed));
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

}  // namespace

double Recording::duration_s() const {
  if (!(sidecar.sample_rate_hz > 0.0)) return 0.0;
  return static_cast<double>(sample_count()) / sidecar.sample_rate_hz;
}

int Recording::channel_index(ChannelRole role) const {
  for (std::size_t i = 0; i < sidecar.channels.size(); ++i) {
    if (sidecar.channels[i].role == role) return static_cast<int>(i);
  }
  return -1;
}

int Recording::channel_index(const std::string& name) const {
  for (std::size_t i = 0; i < sidecar.channels.size(); ++i) {
    if (sidecar.channels[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

Recording read_recording(const std::string& path) {
  check_data_file(path);
  if (lower_extension(path) == ".json") {
    throw InputError(path + ": a recording is a sound or CSV file; .json is its sidecar");
  }
  const std::string sidecar_path = sidecar_path_for(path);
  std::error_code error;
  if (!fs::exists(sidecar_path, error)) {
    throw InputError(path + ": sidecar " + sidecar_path +
                     " not found (it says what the channels are and the sample rate)");
  }
  const Sidecar sidecar = read_sidecar(sidecar_path);
  if (is_text_extension(lower_extension(path))) return read_csv(path, sidecar, sidecar_path);
  return read_sound(path, sidecar, sidecar_path);
}

Recording read_recording(const std::string& path, const Sidecar& sidecar) {
  check_data_file(path);
  const std::string name = "the sidecar given";
  const Sidecar checked = parse_sidecar(sidecar_to_json(sidecar), path + ": " + name);
  if (is_text_extension(lower_extension(path))) return read_csv(path, checked, name);
  return read_sound(path, checked, name);
}

void write_recording(const Recording& recording, const std::string& path) {
  const std::string extension = lower_extension(path);
  const bool csv = extension == ".csv";
  const int sound_format = sound_format_for(extension);
  if (!csv && sound_format == 0) {
    throw InputError(path + ": unknown container " + in_quotes(extension) +
                     " (expected .wav, .flac, .w64, .rf64, .aiff, .caf or .csv)");
  }
  const std::string sidecar_path = sidecar_path_for(path);

  // What the sidecar says about a CSV layout or columns does not apply to the file written.
  Sidecar sidecar = recording.sidecar;
  sidecar.csv.reset();
  for (ChannelInfo& channel : sidecar.channels) channel.column = -1;
  parse_sidecar(sidecar_to_json(sidecar), sidecar_path);

  const Eigen::MatrixXd& samples = recording.samples_si;
  const auto channels = static_cast<Eigen::Index>(sidecar.channels.size());
  if (samples.cols() != channels) {
    throw InputError(path + ": the recording holds " + std::to_string(samples.cols()) +
                     " sample columns, its sidecar lists " + std::to_string(channels) +
                     " channels");
  }
  if (samples.rows() == 0) throw InputError(path + ": no samples to write");

  // Stored value = (SI / unit factor − offset) / scale, the inverse of the reader's calibration.
  std::vector<double> stored(static_cast<std::size_t>(samples.rows() * channels));
  const StoredSamples no_lines;
  for (Eigen::Index c = 0; c < channels; ++c) {
    const ChannelInfo& channel = sidecar.channels[c];
    const double factor = unit_to_si(channel.unit, channel.quantity, sidecar_path);
    for (Eigen::Index r = 0; r < samples.rows(); ++r) {
      const double si = samples(r, c);
      double value = (si / factor - channel.offset) / channel.scale;
      const std::string place = path + ": channel " + in_quotes(channel.name) + ": " +
                                sample_place(r, sidecar.sample_rate_hz, no_lines);
      const bool integer_container = (sound_format & SF_FORMAT_SUBMASK) == SF_FORMAT_PCM_24;
      if (!std::isfinite(si)) {
        if (integer_container || !declared_invalid(sidecar, r)) {
          throw InputError(place + " is not finite" +
                           (integer_container ? " (an integer container cannot hold it)" : ""));
        }
        stored[static_cast<std::size_t>(r * channels + c)] = si;  // what was recorded
        continue;
      }
      if (!std::isfinite(value)) {
        throw InputError(place + ": " + number_text(si) + " overflows with scale " +
                         number_text(channel.scale));
      }
      // Samples that were integer counts times the scale come back as counts to a few ulps;
      // store the count itself (a change of at most 4 ulps) so that files read as counts.
      const double count = std::nearbyint(value);
      if (std::abs(value - count) <=
          4.0 * std::numeric_limits<double>::epsilon() * std::abs(count)) {
        value = count;
      }
      if ((sound_format & SF_FORMAT_SUBMASK) == SF_FORMAT_PCM_24) {
        value = std::nearbyint(value);
        if (value < kFlacMin || value > kFlacMax) {
          throw InputError(place + ": " + number_text(si) + " " + si_unit(channel.quantity) +
                           " is " + number_text(value) + " counts at scale " +
                           number_text(channel.scale) + " " + channel.unit +
                           ", beyond 24-bit FLAC's ±8388607; use a coarser scale or a float64 "
                           "container (.wav, .w64, .caf)");
        }
      }
      stored[static_cast<std::size_t>(r * channels + c)] = value;
    }
  }

  TemporaryFile data_file(path);
  if (csv) {
    write_csv(stored, sidecar, data_file.path(), path);
  } else {
    write_sound(stored, sidecar, sound_format, data_file.path(), path);
  }
  TemporaryFile sidecar_file(sidecar_path);
  write_sidecar(sidecar, sidecar_file.path());
  data_file.commit();
  sidecar_file.commit();
}

}  // namespace oscilab::daq
