#pragma once

// The text of universal files: lines, dataset delimiters and the Fortran fields of their records
// (I, E/D and A fields in fixed columns or separated by blanks).
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace oscilab::daq::uff {

// Inline: the scans of the values test every character and every line.
inline bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// `text` without blanks around it (and without a '\r' at its end).
inline std::string_view trim(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && (is_blank(text.back()) || text.back() == '\r')) text.remove_suffix(1);
  return text;
}

/// Whether `line` is "-1", the line that opens and closes a dataset.
inline bool is_delimiter(std::string_view line) { return trim(line) == "-1"; }
inline bool is_blank_line(std::string_view line) { return trim(line).empty(); }

/// Text for names and properties: valid UTF-8 (nlohmann::json refuses anything else), control
/// characters as '?', trimmed.
std::string clean_text(std::string_view text);

/// Byte index of the character `count` characters after byte `from`: Fortran A fields count
/// characters, and writers that emit UTF-8 (HBM catman writes "m/s²") pad by characters.
std::size_t advance_characters(std::string_view line, std::size_t from, std::size_t count);

/// Fixed-column fields of a record: `widths` in characters; a short line gives empty fields.
std::vector<std::string_view> fixed_fields(std::string_view line,
                                           std::initializer_list<std::size_t> widths);

/// The blank-separated tokens of `line`.
std::vector<std::string_view> tokens(std::string_view line);

/// A Fortran I field: blank is 0. Empty optional when it is not an integer.
std::optional<long long> integer_field(std::string_view field);

/// A Fortran E/D field or free-format real: "1.5E-05", "1.5D-05", "0.00000E+000", "+2.0".
/// Empty optional when it is not a number or overflows ("1E999"); "nan" and "inf" are numbers.
std::optional<double> real_field(std::string_view field);

/// How a real field was printed: digits after the point and the exponent ("1.52588E-05": 5, -5).
void printed_precision(std::string_view text, std::string_view::size_type& decimals,
                       long long& exponent);

/// Whether an A field is unused: blank or "NONE".
bool unused_text(std::string_view text);

/// At most 40 characters of `text`, cleaned and quoted, for messages.
std::string shown(std::string_view text);

}  // namespace oscilab::daq::uff
