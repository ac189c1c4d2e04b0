#include "analysis/diagnosis/discrepancy_maps.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <boost/math/distributions/fisher_f.hpp>

namespace oscilab::analysis {
namespace {

// Slopes of y against x over the lower and upper halves of x (the median splits them; the middle
// point joins both halves when the count is odd).
void split_slopes(std::vector<double> x, std::vector<double> y, LogSlope& low, LogSlope& high) {
  std::vector<std::size_t> order(x.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  const std::size_t half = (order.size() + 1) / 2;
  std::vector<double> xl, yl, xh, yh;
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i < half) {
      xl.push_back(x[order[i]]);
      yl.push_back(y[order[i]]);
    }
    if (i + half >= order.size()) {
      xh.push_back(x[order[i]]);
      yh.push_back(y[order[i]]);
    }
  }
  low = log_slope(xl, yl);
  high = log_slope(xh, yh);
}

StiffnessResidual stiffness_residual(const Model& model, const CampaignAnalysis& campaign) {
  StiffnessResidual out;
  if (!campaign.stiffness || campaign.stiffness->bins.size() < 6) return out;
  out.available = true;
  for (const auto& bin : campaign.stiffness->bins) {
    out.z_m.push_back(bin.x);
    out.residual_n.push_back(bin.force_n - model.elastic_force(bin.x));
  }
  const Eigen::Index n = static_cast<Eigen::Index>(out.z_m.size());
  Eigen::VectorXd r = Eigen::Map<const Eigen::VectorXd>(out.residual_n.data(), n);
  out.rms_n = std::sqrt(r.squaredNorm() / static_cast<double>(n));
  // Reduced design: offset and slope.
  Eigen::MatrixXd reduced(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) reduced.row(i) << 1.0, out.z_m[i];
  const Eigen::VectorXd fit2 = reduced.colPivHouseholderQr().solve(r);
  const double sse2 = (r - reduced * fit2).squaredNorm();
  for (int power : {2, 3, 5}) {
    Eigen::MatrixXd full(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
      full.row(i) << 1.0, out.z_m[i], std::pow(out.z_m[i], power);
    }
    const Eigen::VectorXd fit3 = full.colPivHouseholderQr().solve(r);
    const double sse3 = (r - full * fit3).squaredNorm();
    StiffnessResidual::PowerTest test;
    test.power = power;
    test.coefficient = fit3[2];
    const double dof = static_cast<double>(n - 3);
    test.f_statistic = sse3 > 0.0 ? (sse2 - sse3) / (sse3 / dof) : 0.0;
    test.p_value = test.f_statistic > 0.0 ? boost::math::cdf(boost::math::complement(
                                                boost::math::fisher_f(1.0, dof), test.f_statistic))
                                          : 1.0;
    out.tests.push_back(test);
  }
  return out;
}

}  // namespace

DiscrepancyMaps discrepancy_maps(const EdcObjective& objective, const Eigen::VectorXd& theta,
                                 const EdcEvaluation& evaluation,
                                 const CampaignAnalysis& campaign) {
  DiscrepancyMaps maps;
  std::vector<double> amplitude, measured, missing_amplitude, missing;
  int k = 0;
  const auto& groups = objective.data().groups;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (std::size_t i = 0; i < groups[g].levels.size(); ++i, ++k) {
      const MeasuredLevel& m = groups[g].levels[i];
      LevelDiscrepancy d;
      d.positive_well = groups[g].positive_well;
      d.f0_n = m.f0_n;
      d.amplitude_m = m.amplitude_m;
      d.edc_mes_j = m.edc_j;
      d.edc_mod_j = evaluation.edc_mod_j[g][i];
      d.sigma_j = objective.sigma_j()[k];
      d.sigma_cycles_j = m.sigma_of_mean_j();
      const double difference = d.edc_mes_j - d.edc_mod_j;
      d.residual_sigma = difference / d.sigma_j;
      d.residual_cycles = d.sigma_cycles_j > 0.0 ? difference / d.sigma_cycles_j
                                                 : std::numeric_limits<double>::infinity();
      maps.max_abs_residual_sigma =
          std::max(maps.max_abs_residual_sigma, std::abs(d.residual_sigma));
      amplitude.push_back(d.amplitude_m);
      measured.push_back(d.edc_mes_j);
      if (difference > 2.0 * d.sigma_j) {
        ++maps.slopes.missing_levels;
        missing_amplitude.push_back(d.amplitude_m);
        missing.push_back(difference);
      } else if (difference < -2.0 * d.sigma_j) {
        ++maps.slopes.excess_levels;
      }
      maps.levels.push_back(d);
    }
  }
  const int dof = objective.level_count() - objective.form().size();
  maps.reduced_chi2 = dof > 0 ? evaluation.weighted_cost / dof : std::nan("");
  split_slopes(amplitude, measured, maps.slopes.measured_low, maps.slopes.measured_high);
  split_slopes(missing_amplitude, missing, maps.slopes.missing_low, maps.slopes.missing_high);
  maps.slopes.missing_all = log_slope(missing_amplitude, missing);
  maps.stiffness = stiffness_residual(objective.form().build(theta), campaign);
  maps.response = response_fingerprints(objective.data(), evaluation);
  return maps;
}

}  // namespace oscilab::analysis
