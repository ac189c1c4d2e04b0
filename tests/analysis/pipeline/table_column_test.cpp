// A table's cells as CSV fields: reals by their column's format, counts in decimal, flags 1/0,
// text as it is.
#include "analysis/pipeline/table_column.h"

#include <cstdint>
#include <string>

#include <gtest/gtest.h>

namespace oscilab::analysis {
namespace {

TEST(TableColumn, CsvFieldWritesEachKindAsTheCsvFilesAlwaysHave) {
  EXPECT_EQ(csv_field(1.0 / 3.0, "%.6g"), "0.333333");
  EXPECT_EQ(csv_field(1.0 / 3.0, "%.9g"), "0.333333333");
  EXPECT_EQ(csv_field(12.4444444444, "%.6f"), "12.444444");
  EXPECT_EQ(csv_field(std::int64_t{-42}, nullptr), "-42");
  EXPECT_EQ(csv_field(true, nullptr), "1");
  EXPECT_EQ(csv_field(false, nullptr), "0");
  EXPECT_EQ(csv_field(std::string("few-cycles;per-unit-mass"), nullptr),
            "few-cycles;per-unit-mass");
}

TEST(TableColumn, CsvFieldWritesAHugeFixedPointValueWhole) {
  // 1e300 in %.6f: 301 digits, the point and 6 decimals, past any fixed buffer.
  const std::string field = csv_field(1e300, "%.6f");
  EXPECT_EQ(field.size(), 301u + 1u + 6u);
  EXPECT_EQ(field.substr(0, 2), "10");
  EXPECT_EQ(field.substr(field.size() - 7), ".000000");
}

TEST(TableColumn, KindsAreNamedAsTheContractTablesNameThem) {
  EXPECT_STREQ(to_string(ColumnKind::Real), "real");
  EXPECT_STREQ(to_string(ColumnKind::Integer), "integer");
  EXPECT_STREQ(to_string(ColumnKind::Flag), "flag");
  EXPECT_STREQ(to_string(ColumnKind::Text), "text");
}

TEST(TableColumn, CsvLineAndHeaderFollowTheColumnsOrder) {
  struct Row {
    double x;
    std::string name;
  };
  const std::vector<TableColumn<Row>> columns = {
      {"name", "", ColumnKind::Text, nullptr, "a name",
       [](const Row& r) -> CellValue { return r.name; }},
      {"x_m", "m", ColumnKind::Real, "%.3g", "a length",
       [](const Row& r) -> CellValue { return r.x; }},
  };
  EXPECT_EQ(csv_header(columns), "name,x_m");
  EXPECT_EQ(csv_line(columns, Row{0.123456, "a"}), "a,0.123");
}

}  // namespace
}  // namespace oscilab::analysis
