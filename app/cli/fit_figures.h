#pragma once

#include <string>
#include <vector>

#include "analysis/identification/edc_fit.h"
#include "analysis/identification/edc_sensitivity.h"
#include "ui/figure.h"

namespace oscilab::cli {

/// 1-D cuts of the cost through θ̄, one per parameter (the paper's Fig. 13 shows the cost
/// against each parameter): χ² and eq. (8) at `factors` × θ̄_i, the others at θ̄.
struct CostSlice {
  std::string parameter;
  std::vector<double> value;
  std::vector<double> weighted_cost;
  std::vector<double> cost_j;
};
std::vector<CostSlice> cost_slices(const analysis::EdcObjective& objective,
                                   const Eigen::VectorXd& theta, int points, int threads);

/// Fig. 15: measured EDC ± 3σ and the fitted model per well, and the deviation in %.
ui::Figure edc_fit_figure(const analysis::FitResult& fit, const analysis::EdcObjective& objective);
/// Fig. 14: best cost against model evaluations.
ui::Figure convergence_figure(const analysis::FitResult& fit);
/// f_d(z) of eq. (6) between and beyond the wells, with the three fitted values of eq. (9).
ui::Figure friction_figure(const analysis::FitResult& fit, const analysis::EdcObjective& objective);
/// Fig. 13: the cost along each parameter through θ̄.
ui::Figure cost_slice_figure(const std::vector<CostSlice>& slices);
/// Fig. 16: the EDC of one well with each parameter at 20 … 150 %.
ui::Figure sensitivity_figure(const std::vector<analysis::SensitivityCurve>& curves,
                              bool positive_well);

/// The same data as CSV files in `dir`: edc_fit.csv, convergence.csv, friction.csv,
/// cost_slices.csv, sensitivity.csv. Throws InputError when a file cannot be written.
void write_fit_tables(const std::string& dir, const analysis::FitResult& fit,
                      const analysis::EdcObjective& objective, const std::vector<CostSlice>& slices,
                      const std::vector<analysis::SensitivityCurve>& curves);

}  // namespace oscilab::cli
