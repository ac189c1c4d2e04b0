#include "analysis/pipeline/table_column.h"

#include <cassert>
#include <cstdio>

namespace oscilab::analysis {

const char* to_string(ColumnKind kind) {
  switch (kind) {
    case ColumnKind::Real:
      return "real";
    case ColumnKind::Integer:
      return "integer";
    case ColumnKind::Flag:
      return "flag";
    case ColumnKind::Text:
      return "text";
  }
  return "";
}

std::string csv_field(const CellValue& value, const char* csv_format) {
  if (const auto* text = std::get_if<std::string>(&value)) return *text;
  if (const auto* flag = std::get_if<bool>(&value)) return *flag ? "1" : "0";
  if (const auto* integer = std::get_if<std::int64_t>(&value)) return std::to_string(*integer);
  assert(csv_format != nullptr);
  const double real = std::get<double>(value);
  char field[64];
  const int length = std::snprintf(field, sizeof field, csv_format, real);
  assert(length >= 0);
  if (static_cast<std::size_t>(length) < sizeof field) {
    return std::string(field, static_cast<std::size_t>(length));
  }
  // "%.6f" of a huge value: written again at its full length.
  std::string long_field(static_cast<std::size_t>(length) + 1, '\0');
  std::snprintf(long_field.data(), long_field.size(), csv_format, real);
  long_field.pop_back();
  return long_field;
}

}  // namespace oscilab::analysis
