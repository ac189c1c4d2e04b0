#include "daq/recording/formats/uff_fields.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <system_error>

#include "daq/recording/stored_samples.h"

namespace oscilab::daq::uff {

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

std::size_t advance_characters(std::string_view line, std::size_t from, std::size_t count) {
  std::size_t i = from;
  for (std::size_t k = 0; k < count && i < line.size(); ++k) {
    ++i;
    while (i < line.size() && (static_cast<unsigned char>(line[i]) & 0xC0) == 0x80) ++i;
  }
  return i;
}

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

std::optional<long long> integer_field(std::string_view field) {
  field = trim(field);
  if (field.empty()) return 0;
  if (field.front() == '+') field.remove_prefix(1);
  long long value = 0;
  const auto result = std::from_chars(field.data(), field.data() + field.size(), value);
  if (result.ec != std::errc() || result.ptr != field.data() + field.size()) return std::nullopt;
  return value;
}

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

bool unused_text(std::string_view text) {
  text = trim(text);
  return text.empty() || text == "NONE";
}

std::string shown(std::string_view text) { return in_quotes(clean_text(text.substr(0, 40))); }

}  // namespace oscilab::daq::uff
