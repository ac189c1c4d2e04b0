#include "daq/recording/formats/uff_values.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>
#include <system_error>

#include "analysis/common/input_error.h"
#include "daq/recording/formats/uff_fields.h"

namespace oscilab::daq::uff {
namespace {

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

}  // namespace

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

std::vector<double> decode_binary_values(const std::string& bytes, bool float32, bool big_endian) {
  const bool swap = big_endian != (std::endian::native == std::endian::big);
  std::vector<double> values;
  if (float32) {
    decode_binary<float, std::uint32_t>(bytes, swap, values);
  } else {
    decode_binary<double, std::uint64_t>(bytes, swap, values);
  }
  return values;
}

}  // namespace oscilab::daq::uff
