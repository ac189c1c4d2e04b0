#include "analysis/identification/fit_uncertainty.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include <Eigen/Dense>
#include <boost/math/distributions/students_t.hpp>

#include "analysis/common/parallel_for.h"
#include "analysis/common/quantile.h"
#include "analysis/identification/local_polish.h"

namespace oscilab::analysis {
namespace {

constexpr double kWeakRelativeError = 0.25;  // relative standard error that flags a parameter
constexpr double kStrongCorrelation = 0.95;
// Singular values below this fraction of the largest are treated as zero: the residuals are
// computed to ~1e-8 (Newton tolerance 1e-11 N over σ ≈ 1e-3 S), so J is known to ~1e-5
// relative after central differences with step 1e-3.
constexpr double kRankTolerance = 1e-7;

// Central differences of the whitened residuals in unit coordinates (one-sided at a bound), the
// 2p evaluations in parallel.
Eigen::MatrixXd unit_jacobian(const EdcObjective& objective, const Eigen::VectorXd& u0,
                              const UncertaintyOptions& options) {
  const ModelForm& form = objective.form();
  const int p = form.size();
  Eigen::MatrixXd jacobian_unit(objective.level_count(), p);
  std::vector<double> width(p);
  std::vector<Eigen::VectorXd> points;
  for (int i = 0; i < p; ++i) {
    Eigen::VectorXd up = u0, down = u0;
    up(i) = std::min(1.0, u0(i) + options.difference_step);
    down(i) = std::max(0.0, u0(i) - options.difference_step);
    width[i] = up(i) - down(i);
    points.push_back(up);
    points.push_back(down);
  }
  std::vector<Eigen::VectorXd> residuals(points.size());
  parallel_for(points.size(), options.threads, [&](std::size_t k) {
    residuals[k] = objective.evaluate(form.from_unit(points[k])).residuals;
  });
  for (int i = 0; i < p; ++i) {
    jacobian_unit.col(i) = (residuals[2 * i] - residuals[2 * i + 1]) / width[i];
  }
  return jacobian_unit;
}

// The covariance of u from the Jacobian's SVD, singular directions left out; `identifiable[i]`
// false for a parameter with a share in a singular direction.
Eigen::MatrixXd unit_covariance_of(const Eigen::MatrixXd& jacobian_unit,
                                   std::vector<bool>& identifiable) {
  const auto p = jacobian_unit.cols();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian_unit, Eigen::ComputeThinV);
  const Eigen::VectorXd singular = svd.singularValues();
  const double largest = singular.size() ? singular(0) : 0.0;
  Eigen::MatrixXd cov_unit = Eigen::MatrixXd::Zero(p, p);
  identifiable.assign(static_cast<std::size_t>(p), true);
  for (int j = 0; j < static_cast<int>(singular.size()); ++j) {
    const Eigen::VectorXd v = svd.matrixV().col(j);
    if (singular(j) > kRankTolerance * largest && largest > 0.0) {
      cov_unit += v * v.transpose() / (singular(j) * singular(j));
    } else {
      for (int i = 0; i < p; ++i) {
        if (std::abs(v(i)) > 1e-3) identifiable[i] = false;
      }
    }
  }
  return cov_unit;
}

// Parameter i's standard error, its t interval and a note on what limits it (not identifiable, a
// large relative error, a strong correlation, a search bound).
ParameterUncertainty parameter_uncertainty(const FitUncertainty& out, const ModelForm& form,
                                           const Eigen::VectorXd& theta, const Eigen::VectorXd& u0,
                                           int i, bool identifiable) {
  const double inf = std::numeric_limits<double>::infinity();
  ParameterUncertainty q;
  q.name = form.parameters()[i].name;
  q.value = theta(i);
  q.standard_error = identifiable ? std::sqrt(std::max(0.0, out.covariance(i, i))) : inf;
  const double half = (std::isfinite(out.t_quantile) ? out.t_quantile : 1.96) * q.standard_error;
  q.lower_95 = q.value - half;
  q.upper_95 = q.value + half;
  q.at_bound = u0(i) <= 1e-6 || u0(i) >= 1.0 - 1e-6;
  std::ostringstream note;
  note.precision(2);
  if (!identifiable) note << "not identifiable from these EDCs (singular direction); ";
  const double relative = q.standard_error / std::abs(q.value);
  if (identifiable && relative > kWeakRelativeError) {
    note << "relative standard error " << std::fixed << 100.0 * relative << " %; ";
  }
  for (int j = 0; j < form.size(); ++j) {
    if (j != i && std::abs(out.correlation(i, j)) > kStrongCorrelation) {
      note << "correlation " << std::fixed << out.correlation(i, j) << " with "
           << form.parameters()[j].name << "; ";
    }
  }
  if (q.at_bound) note << "at a search bound; ";
  q.note = note.str();
  if (!q.note.empty()) q.note.resize(q.note.size() - 2);
  q.weakly_identified = !q.note.empty();
  q.bootstrap_std = q.bootstrap_lower_95 = q.bootstrap_upper_95 =
      std::numeric_limits<double>::quiet_NaN();
  return q;
}

// Bootstrap over levels: each replicate redraws every well's levels with replacement (as
// weights), polishes θ from the optimum, and the replicates' spread and 95 % quantiles are set
// on out.parameters. Nothing is set when cancelled.
void bootstrap_over_levels(const EdcObjective& objective, const Eigen::VectorXd& u0,
                           const UncertaintyOptions& options, const CancelToken& cancel,
                           FitUncertainty& out) {
  const ModelForm& form = objective.form();
  const int n = objective.level_count();
  std::mt19937_64 rng(options.seed);
  std::vector<std::vector<double>> weights(options.bootstrap_replicates,
                                           std::vector<double>(n, 0.0));
  for (auto& w : weights) {
    int first = 0;
    for (const EdcGroup& g : objective.data().groups) {
      const int size = static_cast<int>(g.levels.size());
      std::uniform_int_distribution<int> pick(0, size - 1);
      for (int k = 0; k < size; ++k) w[first + pick(rng)] += 1.0;
      first += size;
    }
  }
  std::vector<Eigen::VectorXd> replicate_theta(options.bootstrap_replicates);
  PolishOptions polish;
  polish.max_evaluations = options.bootstrap_polish_evaluations;
  polish.initial_step = 0.01;
  parallel_for(weights.size(), options.threads, [&](std::size_t b) {
    const UnitCost cost = [&](const Eigen::VectorXd& u) {
      return objective.evaluate(form.from_unit(u), &weights[b]).weighted_cost;
    };
    replicate_theta[b] = form.from_unit(local_polish(u0, cost, polish, {}, cancel).best_unit);
  });
  if (cancel.cancelled()) return;
  out.bootstrap_replicates = options.bootstrap_replicates;
  for (int i = 0; i < form.size(); ++i) {
    std::vector<double> values;
    for (const auto& t : replicate_theta) values.push_back(t(i));
    double mean = 0.0, var = 0.0;
    for (double v : values) mean += v / values.size();
    for (double v : values) var += (v - mean) * (v - mean);
    out.parameters[i].bootstrap_std =
        values.size() > 1 ? std::sqrt(var / (values.size() - 1)) : 0.0;
    const std::vector<double> interval = quantiles(values, {0.025, 0.975});
    out.parameters[i].bootstrap_lower_95 = interval[0];
    out.parameters[i].bootstrap_upper_95 = interval[1];
  }
}

}  // namespace

FitUncertainty fit_uncertainty(const EdcObjective& objective, const Eigen::VectorXd& theta,
                               const UncertaintyOptions& options, const CancelToken& cancel) {
  const ModelForm& form = objective.form();
  const int p = form.size();
  const int n = objective.level_count();
  FitUncertainty out;
  out.levels = n;
  out.dof = n - p;
  const long evaluations_before = objective.evaluations();
  const Eigen::VectorXd u0 = form.to_unit(theta);
  const EdcEvaluation at_optimum = objective.evaluate(theta);
  const Eigen::MatrixXd jacobian_unit = unit_jacobian(objective, u0, options);
  // dθ/du of each coordinate (linear or logarithmic map).
  Eigen::VectorXd dtheta_du(p);
  for (int i = 0; i < p; ++i) {
    const FreeParameter& fp = form.parameters()[i];
    dtheta_du(i) = fp.log_scale ? theta(i) * std::log(fp.upper / fp.lower) : fp.upper - fp.lower;
  }

  out.reduced_chi2 =
      out.dof > 0 ? at_optimum.weighted_cost / out.dof : std::numeric_limits<double>::quiet_NaN();
  out.t_quantile = out.dof > 0 ? boost::math::quantile(boost::math::students_t(out.dof), 0.975)
                               : std::numeric_limits<double>::quiet_NaN();
  std::vector<bool> identifiable;
  const Eigen::MatrixXd cov_unit = unit_covariance_of(jacobian_unit, identifiable);
  // Scaled up when the misfit exceeds the stated σ, never down: the σ floor is a stated
  // systematic uncertainty (model discretisation, calibration) that does not average out
  // over levels, so a fit closer than the floor does not make θ̂ more certain than it allows.
  const double scale = std::isfinite(out.reduced_chi2) ? std::max(1.0, out.reduced_chi2) : 1.0;
  out.covariance = scale * dtheta_du.asDiagonal() * cov_unit * dtheta_du.asDiagonal();
  out.correlation = Eigen::MatrixXd::Identity(p, p);
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j < p; ++j) {
      const double d = std::sqrt(out.covariance(i, i) * out.covariance(j, j));
      if (i != j && d > 0.0) out.correlation(i, j) = out.covariance(i, j) / d;
    }
  }
  for (int i = 0; i < p; ++i) {
    out.parameters.push_back(parameter_uncertainty(out, form, theta, u0, i, identifiable[i]));
  }
  if (options.bootstrap_replicates > 0 && !cancel.cancelled()) {
    bootstrap_over_levels(objective, u0, options, cancel, out);
  }
  out.evaluations = objective.evaluations() - evaluations_before;
  out.ok = out.dof > 0;
  out.message = out.dof > 0 ? "" : "fewer levels than parameters: no covariance";
  return out;
}

}  // namespace oscilab::analysis
