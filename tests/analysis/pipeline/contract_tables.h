#pragma once

// The column tables of docs/contracts.md §3, read as a person writes them: the first Markdown
// table after a heading, one row per column, `| `name` | unit | kind | meaning |`.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/pipeline/table_column.h"

namespace oscilab::analysis::testing {

struct DocumentedColumn {
  std::string name;
  std::string unit;  // "" where the document writes "—"
  std::string kind;
};

inline std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// The cells of a table line "| a | b |" (a `\|` inside a cell is not a separator).
inline std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      cells.push_back(trimmed(cell));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return cells;
}

// The rows of the first table after the line `heading` of docs/contracts.md; fails the test
// when the heading, the table or its header `column | unit | kind | meaning` is missing.
inline std::vector<DocumentedColumn> documented_columns(const std::string& heading) {
  std::ifstream file(std::string(OSCILAB_SOURCE_DIR) + "/docs/contracts.md");
  EXPECT_TRUE(file.good()) << "docs/contracts.md";
  std::vector<DocumentedColumn> columns;
  std::string line;
  bool in_section = false;
  bool in_table = false;
  while (std::getline(file, line)) {
    if (!in_section) {
      in_section = line == heading;
      continue;
    }
    const bool table_line = !line.empty() && line[0] == '|';
    if (!in_table) {
      if (line.rfind("#", 0) == 0) break;  // the next section, before any table
      if (!table_line) continue;
      EXPECT_EQ(table_cells(line), (std::vector<std::string>{"column", "unit", "kind", "meaning"}))
          << heading;
      std::getline(file, line);  // | --- | --- | ...
      in_table = true;
      continue;
    }
    if (!table_line) break;
    const std::vector<std::string> cells = table_cells(line);
    EXPECT_EQ(cells.size(), 4u) << line;
    if (cells.size() < 3) continue;
    std::string name = cells[0];
    EXPECT_TRUE(name.size() > 2 && name.front() == '`' && name.back() == '`') << line;
    if (name.size() > 2) name = name.substr(1, name.size() - 2);
    columns.push_back({name, cells[1] == "—" ? "" : cells[1], cells[2]});
  }
  EXPECT_TRUE(in_section) << "docs/contracts.md has no heading " << heading;
  EXPECT_FALSE(columns.empty()) << "docs/contracts.md: no column table under " << heading;
  return columns;
}

// The schema's columns in the document's form, to compare with documented_columns.
template <class Row>
std::vector<DocumentedColumn> schema_columns(const std::vector<TableColumn<Row>>& columns) {
  std::vector<DocumentedColumn> out;
  for (const TableColumn<Row>& column : columns) {
    out.push_back({column.name, column.unit, to_string(column.kind)});
  }
  return out;
}

inline bool operator==(const DocumentedColumn& a, const DocumentedColumn& b) {
  return a.name == b.name && a.unit == b.unit && a.kind == b.kind;
}

inline std::ostream& operator<<(std::ostream& out, const DocumentedColumn& c) {
  return out << c.name << " [" << c.unit << "] " << c.kind;
}

// Each column's value() gives the alternative of CellValue its kind names, and a Real has a
// CSV format.
template <class Row>
void expect_values_match_kinds(const std::vector<TableColumn<Row>>& columns, const Row& row) {
  for (const TableColumn<Row>& column : columns) {
    const CellValue value = column.value(row);
    EXPECT_EQ(value.index(), static_cast<std::size_t>(column.kind)) << column.name;
    EXPECT_EQ(column.csv_format != nullptr, column.kind == ColumnKind::Real) << column.name;
    EXPECT_NE(std::string(column.description), "") << column.name;
  }
}

}  // namespace oscilab::analysis::testing
