#include "analysis/diagnosis/joint_refit.h"

#include <cmath>
#include <limits>
#include <vector>

#include <unsupported/Eigen/LevenbergMarquardt>

namespace oscilab::analysis {
namespace {

// A level the model cannot solve, or a fingerprint it cannot show, counts this many σ (finite,
// so that the Gauss–Newton model stays defined; far beyond any real misfit).
constexpr double kMissingResidual = 1e3;

struct Residuals : Eigen::DenseFunctor<double> {
  Residuals(const EdcObjective& objective, bool fingerprints, double cauchy_scale, int values,
            const CancelToken& cancel, JointRefit& best)
      : Eigen::DenseFunctor<double>(objective.form().size(), values),
        objective_(objective),
        fingerprints_(fingerprints),
        cauchy_scale_(cauchy_scale),
        cancel_(cancel),
        best_(best) {}

  // The residual vector at the unit-cube point u; keeps the best point seen.
  int operator()(const Eigen::VectorXd& u, Eigen::VectorXd& r) const {
    if (cancel_.cancelled()) return -1;
    const Eigen::VectorXd theta = objective_.form().from_unit(u.cwiseMax(0.0).cwiseMin(1.0));
    keep(theta, objective_.evaluate(theta), r);
    ++best_.evaluations;
    return 0;
  }

  // Forward differences in the unit cube (step 1e-6, backwards at the upper bound), the shifted
  // points evaluated by one Newton step from u's solutions (EdcObjective::evaluate_nearby), or
  // solved each when that is not possible.
  int df(const Eigen::VectorXd& u, Eigen::MatrixXd& jacobian) const {
    if (cancel_.cancelled()) return -1;
    constexpr double kStep = 1e-6;
    const Eigen::VectorXd at = u.cwiseMax(0.0).cwiseMin(1.0);
    std::vector<double> steps(static_cast<std::size_t>(inputs()));
    std::vector<Eigen::VectorXd> shifted(steps.size(), at);
    for (int j = 0; j < inputs(); ++j) {
      steps[j] = at[j] + kStep > 1.0 ? -kStep : kStep;
      shifted[j][j] += steps[j];
    }
    const ModelForm& form = objective_.form();
    std::vector<Eigen::VectorXd> nearby;
    for (const Eigen::VectorXd& s : shifted) nearby.push_back(form.from_unit(s));
    EdcEvaluation center;
    std::vector<EdcEvaluation> around;
    jacobian.resize(values(), inputs());
    Eigen::VectorXd r0, r1;
    const Eigen::VectorXd theta = form.from_unit(at);
    if (objective_.evaluate_nearby(theta, nearby, center, around)) {
      keep(theta, center, r0);
      best_.evaluations += 2;
      for (int j = 0; j < inputs(); ++j) {
        residual_vector(around[j], response_fingerprints(objective_.data(), around[j]), r1);
        robust(r1);
        jacobian.col(j) = (r1 - r0) / steps[j];
      }
      return 0;
    }
    if ((*this)(at, r0) < 0) return -1;
    for (int j = 0; j < inputs(); ++j) {
      if ((*this)(shifted[j], r1) < 0) return -1;
      jacobian.col(j) = (r1 - r0) / steps[j];
    }
    return 0;
  }

  // The joint residuals: the EDC's, then (if asked) the fingerprints'.
  void residual_vector(const EdcEvaluation& e, const ResponseFingerprints& f,
                       Eigen::VectorXd& r) const {
    r.resize(values());
    Eigen::Index i = 0;
    for (Eigen::Index k = 0; k < e.residuals.size(); ++k) {
      r[i++] = std::isfinite(e.residuals[k]) ? e.residuals[k] : kMissingResidual;
    }
    if (fingerprints_) {
      for (const ResponseFingerprint& item : f.items) {
        for (double value : item.residual_sigma) {
          if (i < r.size()) r[i++] = std::isfinite(value) ? value : 0.0;
        }
      }
    }
  }

  // With a Cauchy scale c > 0, each whitened residual r becomes sign(r)·c·√ln(1 + (r/c)²), so
  // that the least-squares sum is the Cauchy loss Σ c² ln(1 + (r/c)²) (r for |r| ≪ c).
  void robust(Eigen::VectorXd& r) const {
    if (!(cauchy_scale_ > 0.0)) return;
    const double c = cauchy_scale_;
    for (Eigen::Index k = 0; k < r.size(); ++k) {
      r[k] = std::copysign(c * std::sqrt(std::log1p((r[k] / c) * (r[k] / c))), r[k]);
    }
  }

  // r at θ's evaluation (robust when asked); θ becomes the best if the loss minimised (the joint
  // χ², or its Cauchy loss) is the lowest seen.
  void keep(const Eigen::VectorXd& theta, const EdcEvaluation& e, Eigen::VectorXd& r) const {
    const ResponseFingerprints f = response_fingerprints(objective_.data(), e);
    residual_vector(e, f, r);
    robust(r);
    const double loss = cauchy_scale_ > 0.0 ? r.squaredNorm() : joint_chi2(e, f, fingerprints_);
    if (best_.theta.size() == 0 || loss < best_loss_) {
      best_loss_ = loss;
      best_.theta = theta;
      best_.evaluation = e;
      best_.fingerprints = f;
      best_.joint_chi2 = joint_chi2(e, f, fingerprints_);
    }
  }

  const EdcObjective& objective_;
  bool fingerprints_;
  double cauchy_scale_;
  const CancelToken& cancel_;
  JointRefit& best_;
  mutable double best_loss_ = std::numeric_limits<double>::infinity();
};

}  // namespace

double joint_chi2(const EdcEvaluation& evaluation, const ResponseFingerprints& fingerprints,
                  bool use_fingerprints) {
  return evaluation.weighted_cost + (use_fingerprints ? fingerprints.chi2 : 0.0);
}

JointRefit joint_refit(const EdcObjective& objective, const Eigen::VectorXd& start,
                       bool fingerprints, int max_evaluations, const CancelToken& cancel,
                       double cauchy_scale) {
  JointRefit best;
  best.joint_chi2 = std::numeric_limits<double>::infinity();
  int values = objective.level_count();
  if (fingerprints) values += 3 * objective.level_count();
  Residuals residuals(objective, fingerprints, cauchy_scale, values, cancel, best);
  Eigen::VectorXd u = objective.form().to_unit(objective.form().clamp(start));
  Eigen::VectorXd r;
  if (residuals(u, r) < 0) return best;
  Eigen::LevenbergMarquardt<Residuals> lm(residuals);
  // Each Jacobian costs p + 1 evaluations: the budget in function and Jacobian calls.
  lm.setMaxfev(std::max(2, max_evaluations / (objective.form().size() + 2)));
  lm.setXtol(1e-8);
  lm.setFtol(1e-8);
  lm.minimize(u);
  return best;
}

}  // namespace oscilab::analysis
