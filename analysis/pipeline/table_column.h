#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

// The columns of an output table, named once: the CSV files, the Python module's dicts and the
// MAT-file export all write a table from its list of TableColumn, and docs/contracts.md §3
// lists the same names, units and kinds (a test keeps them in step).
namespace oscilab::analysis {

/// What a column holds, and so how each writer stores it: CSV text, a NumPy dtype, a MATLAB
/// class.
enum class ColumnKind {
  Real,     // double; CSV by the column's csv_format, NumPy float64, MATLAB double
  Integer,  // a count; CSV decimal, NumPy int64, MATLAB double (exact below 2⁵³)
  Flag,     // true or false; CSV 1 or 0, NumPy bool, MATLAB logical
  Text,     // CSV as is (no quoting), NumPy unicode (<U…), MATLAB cell array of char
};

/// "real", "integer", "flag", "text": as docs/contracts.md names the kinds.
const char* to_string(ColumnKind kind);

/// One cell: the alternative ColumnKind names, in its order (Real: double, Integer:
/// std::int64_t, Flag: bool, Text: std::string), so that index() == static_cast<int>(kind).
using CellValue = std::variant<double, std::int64_t, bool, std::string>;

/// A column of a table whose rows are `Row`s.
template <class Row>
struct TableColumn {
  const char* name;         // the CSV header's, the Python key, the MAT variable
  const char* unit;         // SI ("N", "J", "m", "rad", "s"); "" for a count, a ratio or text
  ColumnKind kind;          // value() returns this alternative of CellValue
  const char* csv_format;   // printf conversion of a Real's CSV field ("%.9g"); unused otherwise
  const char* description;  // one line, for a reader of the table
  CellValue (*value)(const Row& row);
};

/// The CSV field of a cell: a Real by `csv_format`, an Integer in decimal, a Flag as 1 or 0,
/// Text as it is.
std::string csv_field(const CellValue& value, const char* csv_format);

/// The CSV header of `columns`: their names, comma-separated, without the line's end.
template <class Row>
std::string csv_header(const std::vector<TableColumn<Row>>& columns) {
  std::string header;
  for (const TableColumn<Row>& column : columns) {
    if (!header.empty()) header += ',';
    header += column.name;
  }
  return header;
}

/// The CSV line of `row` in `columns`' order, without the line's end.
template <class Row>
std::string csv_line(const std::vector<TableColumn<Row>>& columns, const Row& row) {
  std::string line;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (c > 0) line += ',';
    line += csv_field(columns[c].value(row), columns[c].csv_format);
  }
  return line;
}

}  // namespace oscilab::analysis
