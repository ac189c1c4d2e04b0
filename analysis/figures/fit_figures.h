#pragma once

#include <string>
#include <vector>

#include "analysis/common/job.h"
#include "analysis/figures/figure.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/identification/edc_sensitivity.h"

namespace oscilab::figures {

/// The figures of a fit (Figs. 13–16) as data, and their tables: Qt-free, shared by
/// `oscilab-cli fit --figures` and the fit panel of the desktop app (rendered by figure_renderer).

/// 1-D cuts of the cost through θ̄, one per parameter (the paper's Fig. 13 shows the cost
/// against each parameter): χ² and eq. (8) at 50 … 150 % of θ̄_i (k_s: of its excess over 1),
/// the others at θ̄. The evaluations run on `threads` threads; after `cancel` the remaining
/// points are skipped (NaN).
struct CostSlice {
  std::string parameter;
  std::vector<double> value;
  std::vector<double> weighted_cost;
  std::vector<double> cost_j;
};
std::vector<CostSlice> cost_slices(const analysis::EdcObjective& objective,
                                   const Eigen::VectorXd& theta, int points, int threads,
                                   const CancelToken& cancel = {});

/// Fig. 15: measured EDC ± 3σ and the fitted model per well, and the deviation in %.
Figure edc_fit_figure(const analysis::FitResult& fit, const analysis::EdcObjective& objective);
/// Fig. 14: best cost against model evaluations.
Figure convergence_figure(const analysis::FitResult& fit);
/// f_d(z) of eq. (6) between and beyond the wells, with the three fitted values of eq. (9).
Figure friction_figure(const analysis::FitResult& fit, const analysis::EdcObjective& objective);
/// Fig. 13: the cost along each parameter through θ̄.
Figure cost_slice_figure(const std::vector<CostSlice>& slices);
/// Fig. 16: the EDC of one well with each parameter at 20 … 150 %.
Figure sensitivity_figure(const std::vector<analysis::SensitivityCurve>& curves,
                          bool positive_well);

/// What Figs. 13 and 16 need beyond the fit itself: the cost slices (21 points per parameter)
/// and the sensitivity curves (each parameter at 20, 50, 70, 100, 120, 150 %), about 200 model
/// evaluations. After `cancel` the slices stop early (the sensitivity curves, ~70 level
/// responses, run to their end).
struct FitFigureData {
  std::vector<CostSlice> slices;
  std::vector<analysis::SensitivityCurve> curves;
};
FitFigureData fit_figure_data(const analysis::EdcObjective& objective, const Eigen::VectorXd& theta,
                              int threads, const CancelToken& cancel = {});

/// A figure with the stem of its file name ("edc_fit" is written as edc_fit.png).
struct NamedFigure {
  std::string stem;
  Figure figure;
};
/// Every figure of a fit: edc_fit (Fig. 15), convergence (Fig. 14), friction (f_d(z)),
/// cost_slices (Fig. 13), sensitivity_positive and sensitivity_negative (Fig. 16, for the wells
/// the data has).
std::vector<NamedFigure> fit_figures(const analysis::FitResult& fit,
                                     const analysis::EdcObjective& objective,
                                     const FitFigureData& data);

/// The same data as CSV files in `dir`: edc_fit.csv, convergence.csv, friction.csv,
/// cost_slices.csv, sensitivity.csv. Throws InputError when a file cannot be written.
void write_fit_tables(const std::string& dir, const analysis::FitResult& fit,
                      const analysis::EdcObjective& objective, const std::vector<CostSlice>& slices,
                      const std::vector<analysis::SensitivityCurve>& curves);

/// What `fit --figures DIR` and the app's "Export results" write besides fit.json: the tables
/// (write_fit_tables) and, unless `png` is false, every figure of fit_figures as STEM.png
/// (write_figure_png). Returns how many figures were written. Throws InputError naming the file
/// that cannot be written.
int write_fit_figures(const std::string& dir, const analysis::FitResult& fit,
                      const analysis::EdcObjective& objective, const FitFigureData& data, bool png);

}  // namespace oscilab::figures
