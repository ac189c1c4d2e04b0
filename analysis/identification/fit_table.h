#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "analysis/identification/fit_report.h"

namespace oscilab::analysis {

/// Many independent fits (a campaign run by Slurm or GNU parallel) joined into one table, one
/// row per fit: what `oscilab-cli merge` writes as CSV and `oscilab.merge` returns.
struct FitTable {
  /// The fits' parameter names, the union in first-seen order.
  std::vector<std::string> parameters;
  std::vector<FitSummary> rows;

  /// The columns in order: fit, records, method, cost_j, mean_deviation_pct_positive,
  /// mean_deviation_pct_negative, evaluations, seconds, then each parameter p and p_std.
  std::vector<std::string> columns() const;
  /// A row's value (or standard error) of a parameter; NaN when that fit has none.
  double parameter(std::size_t row, const std::string& name) const;
  double standard_error(std::size_t row, const std::string& name) const;
};

/// The table of these fits (their order kept).
FitTable fit_table(std::vector<FitSummary> rows);

/// The table as CSV (a header of columns(), then a row per fit; numbers with 9 significant
/// digits, an absent value empty, text quoted when it holds a comma, a quote or a newline).
void write_fit_table_csv(std::ostream& out, const FitTable& table);

}  // namespace oscilab::analysis
