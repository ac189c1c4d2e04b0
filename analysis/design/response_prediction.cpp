#include "analysis/design/response_prediction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Dense>

#include "analysis/diagnosis/response_fingerprints.h"
#include "analysis/hbm/level_response.h"

namespace oscilab::analysis {
namespace {

// The whitened residuals: the EDC's, then the fingerprints' that were measured.
Eigen::VectorXd whitened(const EdcObjective& objective, const Eigen::VectorXd& theta,
                         bool fingerprints, double& chi2) {
  const EdcEvaluation e = objective.evaluate(theta);
  std::vector<double> r(e.residuals.data(), e.residuals.data() + e.residuals.size());
  chi2 = e.weighted_cost;
  if (fingerprints) {
    const ResponseFingerprints fp = response_fingerprints(objective.data(), e);
    for (const ResponseFingerprint& item : fp.items) {
      for (double value : item.residual_sigma) r.push_back(std::isfinite(value) ? value : 0.0);
    }
    chi2 += fp.chi2;
  }
  return Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
}

// Step of coordinate i of u inside [0, 1]: forward, or backward at the upper bound.
double signed_step(double u, double step) { return u + step <= 1.0 ? step : -step; }

// Group corrections of one well and frequency, interpolated in f0 as EdcObjective::edc_at does.
std::vector<double> interpolated(const EdcObjective& objective, bool positive_well, double freq_hz,
                                 const std::vector<double>& per_level,
                                 const std::vector<double>& f0_n) {
  std::vector<double> out(f0_n.size(), 0.0);
  if (per_level.size() != static_cast<std::size_t>(objective.level_count())) return out;
  std::vector<double> level_f0, correction;
  std::size_t k = 0;
  for (const EdcGroup& group : objective.data().groups) {
    const bool same = group.positive_well == positive_well &&
                      std::abs(group.freq_hz - freq_hz) <= 1e-9 * std::abs(freq_hz);
    for (const MeasuredLevel& level : group.levels) {
      if (same) {
        level_f0.push_back(level.f0_n);
        correction.push_back(per_level[k]);
      }
      ++k;
    }
  }
  if (level_f0.empty()) return out;
  for (std::size_t i = 0; i < f0_n.size(); ++i) {
    const auto upper = std::lower_bound(level_f0.begin(), level_f0.end(), f0_n[i]);
    if (upper == level_f0.begin()) {
      out[i] = correction.front();
    } else if (upper == level_f0.end()) {
      out[i] = correction.back();
    } else {
      const std::size_t j = static_cast<std::size_t>(upper - level_f0.begin());
      const double w = (f0_n[i] - level_f0[j - 1]) / (level_f0[j] - level_f0[j - 1]);
      out[i] = (1.0 - w) * correction[j - 1] + w * correction[j];
    }
  }
  return out;
}

// The saddle between the wells: the unstable equilibrium between z₋* and z₊* (NaN for a model
// with one well).
double saddle_m(const Model& model) {
  try {
    const double lo = model.well(false).z_m, hi = model.well(true).z_m;
    for (const Equilibrium& e : model.equilibria()) {
      if (!e.stable && e.z_m > lo && e.z_m < hi) return e.z_m;
    }
  } catch (const std::exception&) {
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// The orbit z(τ) = a0 + Σ a_h cos hτ + b_h sin hτ (harmonic_balance.h) reaches the saddle.
bool reaches_saddle(const Eigen::VectorXd& x, double saddle, bool positive_well) {
  if (!std::isfinite(saddle)) return false;
  constexpr int kSamples = 128;  // ≥ 16 per period of the 7th harmonic
  const Eigen::Index harmonics = (x.size() - 1) / 2;
  for (int n = 0; n < kSamples; ++n) {
    const double tau = 2.0 * M_PI * n / kSamples;
    double z = x[0];
    for (Eigen::Index h = 1; h <= harmonics; ++h) {
      z += x[2 * h - 1] * std::cos(h * tau) + x[2 * h] * std::sin(h * tau);
    }
    if (positive_well ? z <= saddle : z >= saddle) return true;
  }
  return false;
}

struct Raw {
  std::vector<double> edc_j, z1_m;
  std::vector<Eigen::VectorXd> coefficients;
  std::size_t solved = 0;
};

std::optional<Raw> respond(const EdcObjective& objective, const Eigen::VectorXd& theta,
                           bool positive_well, double freq_hz, const std::vector<double>& f0_n) {
  Raw out;
  try {
    const Model model = objective.form().build(objective.form().clamp(theta));
    const LevelResponse r =
        level_response(model, freq_hz, positive_well, f0_n, objective.settings().hbm);
    out.solved = std::min({r.edc_j.size(), r.coefficients.size(), f0_n.size()});
    out.edc_j = r.edc_j;
    out.coefficients = r.coefficients;
    for (std::size_t k = 0; k < out.solved; ++k) {
      const Eigen::VectorXd& x = r.coefficients[k];
      out.z1_m.push_back(harmonic_amplitude(x, 1));
    }
  } catch (const std::exception&) {
    return std::nullopt;  // θ outside a term's domain, or a model harmonic balance cannot take
  }
  return out;
}

}  // namespace

Eigen::MatrixXd unit_covariance(const EdcObjective& objective, const Eigen::VectorXd& theta,
                                bool fingerprints, double step, const CancelToken& cancel) {
  const ModelForm& form = objective.form();
  const int p = form.size();
  const Eigen::VectorXd u = form.to_unit(form.clamp(theta));
  double chi2 = 0.0;
  const Eigen::VectorXd r0 = whitened(objective, form.from_unit(u), fingerprints, chi2);
  Eigen::MatrixXd jacobian(r0.size(), p);
  for (int i = 0; i < p; ++i) {
    if (cancel.cancelled()) break;
    Eigen::VectorXd ui = u;
    const double h = signed_step(u[i], step);
    ui[i] += h;
    double unused = 0.0;
    jacobian.col(i) = (whitened(objective, form.from_unit(ui), fingerprints, unused) - r0) / h;
  }
  const int n = static_cast<int>(r0.size());
  const double s2 = n > p ? std::max(1.0, chi2 / (n - p)) : 1.0;
  const Eigen::MatrixXd information =
      jacobian.transpose() * jacobian + 12.0 * Eigen::MatrixXd::Identity(p, p);
  return s2 * information.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
}

PredictedLevels predict_levels(const EdcObjective& objective, const Eigen::VectorXd& theta,
                               const Eigen::MatrixXd& unit_cov, bool positive_well, double freq_hz,
                               const std::vector<double>& f0_n, double step,
                               const CancelToken& cancel) {
  PredictedLevels out;
  out.positive_well = positive_well;
  out.freq_hz = freq_hz;
  out.f0_n = f0_n;
  const std::size_t m = f0_n.size();
  out.edc_j.assign(m, 0.0);
  out.z1_m.assign(m, 0.0);
  out.edc_sigma_j.assign(m, std::numeric_limits<double>::infinity());
  out.z1_sigma_m.assign(m, std::numeric_limits<double>::infinity());
  out.valid.assign(m, 0);
  const ModelForm& form = objective.form();
  const std::optional<Raw> base = respond(objective, theta, positive_well, freq_hz, f0_n);
  if (!base) return out;
  const double saddle = saddle_m(form.build(form.clamp(theta)));
  std::size_t usable = base->solved;
  for (std::size_t k = 0; k < base->solved; ++k) {
    if (reaches_saddle(base->coefficients[k], saddle, positive_well)) {
      out.first_well_jump = static_cast<int>(k);
      usable = k;
      break;
    }
  }
  const std::vector<double> edc_correction =
      interpolated(objective, positive_well, freq_hz, objective.budget().correction_j, f0_n);
  const std::vector<double> z1_correction =
      interpolated(objective, positive_well, freq_hz, objective.budget().correction_z1_m, f0_n);
  for (std::size_t k = 0; k < base->solved; ++k) {
    out.edc_j[k] = base->edc_j[k] + edc_correction[k];
    out.z1_m[k] = base->z1_m[k] + z1_correction[k];
  }
  // g = ∂prediction/∂u, one column per parameter (the correction does not depend on θ here).
  const int p = form.size();
  const Eigen::VectorXd u = form.to_unit(form.clamp(theta));
  Eigen::MatrixXd g_edc = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m), p);
  Eigen::MatrixXd g_z1 = g_edc;
  for (int i = 0; i < p && usable > 0; ++i) {
    if (cancel.cancelled()) return out;
    Eigen::VectorXd ui = u;
    const double h = signed_step(u[i], step);
    ui[i] += h;
    const std::optional<Raw> moved =
        respond(objective, form.from_unit(ui), positive_well, freq_hz, f0_n);
    const std::size_t solved = moved ? moved->solved : 0;
    usable = std::min(usable, solved);  // a level whose derivative is unknown is not predicted
    for (std::size_t k = 0; k < usable; ++k) {
      g_edc(static_cast<Eigen::Index>(k), i) = (moved->edc_j[k] - base->edc_j[k]) / h;
      g_z1(static_cast<Eigen::Index>(k), i) = (moved->z1_m[k] - base->z1_m[k]) / h;
    }
  }
  for (std::size_t k = 0; k < usable; ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    const Eigen::VectorXd ge = g_edc.row(row).transpose(), gz = g_z1.row(row).transpose();
    out.edc_sigma_j[k] = std::sqrt(std::max(0.0, ge.dot(unit_cov * ge)));
    out.z1_sigma_m[k] = std::sqrt(std::max(0.0, gz.dot(unit_cov * gz)));
    out.valid[k] = 1;
  }
  return out;
}

}  // namespace oscilab::analysis
