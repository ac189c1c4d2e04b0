#include "analysis/identification/fit_table.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

namespace oscilab::analysis {
namespace {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string value_or_empty(double value) {
  if (!std::isfinite(value)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

double named_value(const std::vector<std::pair<std::string, double>>& values,
                   const std::string& name) {
  for (const auto& [n, v] : values) {
    if (n == name) return v;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::vector<std::string> FitTable::columns() const {
  std::vector<std::string> out = {"fit",
                                  "records",
                                  "method",
                                  "cost_j",
                                  "mean_deviation_pct_positive",
                                  "mean_deviation_pct_negative",
                                  "evaluations",
                                  "seconds"};
  for (const std::string& p : parameters) {
    out.push_back(p);
    out.push_back(p + "_std");
  }
  return out;
}

double FitTable::parameter(std::size_t row, const std::string& name) const {
  return named_value(rows.at(row).parameters, name);
}

double FitTable::standard_error(std::size_t row, const std::string& name) const {
  return named_value(rows.at(row).standard_errors, name);
}

FitTable fit_table(std::vector<FitSummary> rows) {
  FitTable table;
  std::set<std::string> seen;
  for (const FitSummary& row : rows) {
    for (const auto& [name, value] : row.parameters) {
      if (seen.insert(name).second) table.parameters.push_back(name);
    }
  }
  table.rows = std::move(rows);
  return table;
}

void write_fit_table_csv(std::ostream& out, const FitTable& table) {
  const std::vector<std::string> columns = table.columns();
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << '\n';
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    const FitSummary& r = table.rows[k];
    out << csv_field(r.source) << ',' << csv_field(r.records) << ',' << csv_field(r.method) << ','
        << value_or_empty(r.cost_j) << ',' << value_or_empty(r.mean_deviation_pct_positive) << ','
        << value_or_empty(r.mean_deviation_pct_negative) << ',' << r.evaluations << ','
        << value_or_empty(r.seconds);
    for (const std::string& p : table.parameters) {
      out << ',' << value_or_empty(table.parameter(k, p)) << ','
          << value_or_empty(table.standard_error(k, p));
    }
    out << '\n';
  }
}

}  // namespace oscilab::analysis
