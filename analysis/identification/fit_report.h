#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/identification/edc_fit.h"

namespace oscilab::analysis {

/// The FIT JSON of docs/contracts.md §3: `parameters` (θ by name: fd_zminus_n, fd_zero_n,
/// fd_zplus_n, ks, c_ns_m, vt_m_s for the paper's form), `cost_j` (eq. (8)), `mean_deviation_pct`
/// {positive, negative}, `evaluations`, `seconds`; and beyond the contract: "format"
/// ("oscilab-fit/1"), the records, the fitted cost (name and value), α, β, γ of f_d(z) (eq. (6)),
/// standard errors, 95 % intervals, the bootstrap, the correlation matrix, the weakly identified
/// parameters with the reason, the method and its settings, every level (measured, modelled,
/// residual in σ), the levels left out, the convergence history and the fitted model.
nlohmann::json fit_report_json(const FitResult& fit, const EdcObjective& objective,
                               const std::vector<std::string>& records);

/// Reads the parameter values, costs and deviations back from a FIT JSON (for `merge`). Throws
/// InputError naming `source` and the missing or malformed key.
struct FitSummary {
  std::string source;
  std::vector<std::pair<std::string, double>> parameters;
  std::vector<std::pair<std::string, double>> standard_errors;  // empty when absent
  double cost_j = 0.0;
  double mean_deviation_pct_positive = 0.0;
  double mean_deviation_pct_negative = 0.0;
  long evaluations = 0;
  double seconds = 0.0;
  std::string method;
  std::string records;  // the record names joined by ';'
};
FitSummary read_fit_summary(const nlohmann::json& fit, const std::string& source);

}  // namespace oscilab::analysis
