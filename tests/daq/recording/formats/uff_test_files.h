#pragma once

// Universal files built field by field from "Universal Dataset Number 58, Function at Nodal DOF"
// (SDRC / Siemens I-DEAS universal file format documentation), for the UFF 58 reader's tests and
// fuzz test. Every record says which fields it holds; the values are the caller's.

#include <bit>
#include <cstdint>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

namespace oscilab::daq::testing {

/// Fortran I field: `value` right-aligned in `width` columns.
inline std::string i_field(long long value, std::size_t width) {
  const std::string digits = std::to_string(value);
  return std::string(width > digits.size() ? width - digits.size() : 0, ' ') + digits;
}

/// Fortran A field: `text` left-aligned in `width` columns.
inline std::string a_field(const std::string& text, std::size_t width) {
  return text + std::string(width > text.size() ? width - text.size() : 0, ' ');
}

/// Right-aligns already formatted text in `width` columns (an E field written by hand).
inline std::string r_field(const std::string& text, std::size_t width) {
  return std::string(width > text.size() ? width - text.size() : 0, ' ') + text;
}

/// The fields of records 1-11 of one dataset 58 (text as it goes into the file, so a test can put
/// any spelling into a numeric field).
struct Uff58Header {
  std::string id1 = "Pressure at the mass";  // record 1: ID line 1
  std::string id2 = "NONE";                  // record 2: ID line 2
  std::string id3 = "25-NOV-26 08:00:00";    // record 3: ID line 3, date and time
  std::string id4 = "NONE";                  // record 4: ID line 4
  std::string id5 = "NONE";                  // record 5: ID line 5
  std::string function_type = "1";           // record 6 field 1: 1 time response
  std::string response_entity = "mic";       // record 6 field 5
  std::string response_node = "3";           // record 6 field 6
  std::string response_direction = "-2";     // record 6 field 7: -Y translation
  std::string ordinate_type = "2";           // record 7 field 1: 2 real single, 4 real double
  std::string count = "0";                   // record 7 field 2: number of values
  std::string spacing = "1";                 // record 7 field 3: 1 even
  std::string abscissa_min = "0.00000E+00";  // record 7 field 4: s
  std::string increment = "1.00000E-03";     // record 7 field 5: s
  std::string abscissa_units = "s";          // record 8 field 6
  std::string ordinate_units = "Pa";         // record 9 field 6
  std::string eol = "\n";                    // "\r\n" for CRLF files
};

/// Records 1-11.
inline std::string uff58_records(const Uff58Header& h) {
  const std::string& n = h.eol;
  std::string text;
  // Records 1-5: Format(80A1), the five ID lines.
  text += a_field(h.id1, 80) + n + a_field(h.id2, 80) + n + a_field(h.id3, 80) + n +
          a_field(h.id4, 80) + n + a_field(h.id5, 80) + n;
  // Record 6: Format(2(I5,I10),2(1X,10A1,I10,I4)), DOF identification.
  text += r_field(h.function_type, 5)             // function type
          + i_field(7, 10)                        // function identification number
          + i_field(0, 5)                         // version or sequence number
          + i_field(0, 10)                        // load case identification number
          + " " + a_field(h.response_entity, 10)  // 1X, response entity name
          + r_field(h.response_node, 10)          // response node
          + r_field(h.response_direction, 4)      // response direction
          + " " + a_field("NONE", 10)             // 1X, reference entity name
          + i_field(0, 10)                        // reference node
          + i_field(0, 4)                         // reference direction
          + n;
  // Record 7: Format(3I10,3E13.5), data form.
  text += r_field(h.ordinate_type, 10)   // ordinate data type
          + r_field(h.count, 10)         // number of data values (even spacing)
          + r_field(h.spacing, 10)       // abscissa spacing
          + r_field(h.abscissa_min, 13)  // abscissa minimum
          + r_field(h.increment, 13)     // abscissa increment
          + r_field("0.00000E+00", 13)   // z-axis value
          + n;
  // Records 8-11: Format(I10,3I5,2(1X,20A1)): specific data type, length, force and temperature
  // unit exponents, axis label, axis units label.
  text += i_field(17, 10) + i_field(0, 5) + i_field(0, 5) + i_field(0, 5) + " " +
          a_field("Time", 20) + " " + a_field(h.abscissa_units, 20) + n;  // 8: abscissa, time
  text += i_field(15, 10) + i_field(0, 5) + i_field(0, 5) + i_field(0, 5) + " " +
          a_field("Pressure", 20) + " " + a_field(h.ordinate_units, 20) + n;  // 9: ordinate
  text += i_field(0, 10) + i_field(0, 5) + i_field(0, 5) + i_field(0, 5) + " " +
          a_field("NONE", 20) + " " + a_field("NONE", 20) + n;  // 10: ordinate denominator
  text += i_field(0, 10) + i_field(0, 5) + i_field(0, 5) + i_field(0, 5) + " " +
          a_field("NONE", 20) + " " + a_field("NONE", 20) + n;  // 11: z axis
  return text;
}

/// An ASCII dataset 58: "-1", "58", records 1-11, the value lines as given, "-1".
inline std::string ascii_uff58(const Uff58Header& h, const std::string& value_lines) {
  return "    -1" + h.eol + "    58" + h.eol + uff58_records(h) + value_lines + "    -1" + h.eol;
}

/// Value lines in Format(6E13.5), six to a line, the last one short.
inline std::string e13_lines(const std::vector<double>& values, const std::string& eol = "\n") {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) {
    char field[32];
    std::snprintf(field, sizeof field, "%13.5E", values[i]);
    text += field;
    if (i % 6 == 5 || i + 1 == values.size()) text += eol;
  }
  return text;
}

/// IEEE 754 bytes of `value` in the byte order `byte_order` (1 little-endian, 2 big-endian).
template <typename Float>
std::string ieee_bytes(Float value, int byte_order) {
  using Word = std::conditional_t<sizeof(Float) == 4, std::uint32_t, std::uint64_t>;
  const auto word = std::bit_cast<Word>(value);
  std::string bytes;
  for (std::size_t i = 0; i < sizeof(Word); ++i) {
    const std::size_t shift = byte_order == 1 ? 8 * i : 8 * (sizeof(Word) - 1 - i);
    bytes.push_back(static_cast<char>((word >> shift) & 0xFF));
  }
  return bytes;
}

/// A binary dataset 58b: "-1", the binary header, records 1-11, `data`, "-1". `declared_bytes`
/// < 0: the size of `data`.
inline std::string binary_uff58(const Uff58Header& h, int byte_order, const std::string& data,
                                long long declared_bytes = -1, const std::string& order_field = "",
                                const std::string& format_field = "2",
                                const std::string& lines_field = "11") {
  const long long bytes = declared_bytes < 0 ? static_cast<long long>(data.size()) : declared_bytes;
  // Record 1: Format(I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12).
  const std::string header =
      i_field(58, 6)  // dataset number
      + "b"           // binary
      + r_field(order_field.empty() ? std::to_string(byte_order) : order_field, 6)  // byte order
      + r_field(format_field, 6)                                                    // 2: IEEE 754
      + r_field(lines_field, 12)                                         // ASCII lines after
      + i_field(bytes, 12)                                               // bytes of data
      + i_field(0, 6) + i_field(0, 6) + i_field(0, 12) + i_field(0, 12)  // unused
      + h.eol;
  return "    -1" + h.eol + header + uff58_records(h) + data + "    -1" + h.eol;
}

}  // namespace oscilab::daq::testing
