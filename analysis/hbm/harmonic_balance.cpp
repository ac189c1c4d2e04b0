#include "analysis/hbm/harmonic_balance.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/LU>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The normalised DFT bin w_m for any integer m, from the one-sided spectrum of a real signal of
// N samples: w_{m+N} = w_m and w_{−m} = conj(w_m).
std::complex<double> bin(const std::vector<std::complex<double>>& w, int n, int m) {
  int k = m % n;
  if (k < 0) k += n;
  return k <= n / 2 ? w[static_cast<std::size_t>(k)]
                    : std::conj(w[static_cast<std::size_t>(n - k)]);
}

enum Trig { kCos = 0, kSin = 1 };

// (1/N) Σ_n x_n u(pτ_n) v(qτ_n) for u, v ∈ {cos, sin}, from the DFT w of x by the product-to-sum
// identities; (1/N) Σ x cos mτ = Re w_m and (1/N) Σ x sin mτ = −Im w_m.
double mean_product(const std::vector<std::complex<double>>& w, int n, Trig u, int p, Trig v,
                    int q) {
  const std::complex<double> sum = bin(w, n, p + q), difference = bin(w, n, p - q);
  if (u == kCos && v == kCos) return 0.5 * (difference.real() + sum.real());
  if (u == kSin && v == kSin) return 0.5 * (difference.real() - sum.real());
  if (u == kSin) return 0.5 * (-sum.imag() - difference.imag());  // sin p · cos q
  return 0.5 * (-sum.imag() + difference.imag());                 // cos p · sin q
}

}  // namespace

int HbmOptions::default_samples(int harmonics, int subharmonic) {
  return std::max(32, next_power_of_two(16 * harmonics * subharmonic));
}

int HbmOptions::resolved_samples() const {
  return samples > 0 ? samples : default_samples(harmonics, subharmonic);
}

namespace {

HbmOptions checked(const HbmOptions& options) {
  if (options.harmonics < 1) {
    throw InputError("harmonic balance: harmonics: " + std::to_string(options.harmonics) +
                     " must be at least 1");
  }
  if (options.subharmonic < 1 || options.subharmonic > 64) {
    throw InputError("harmonic balance: subharmonic: " + std::to_string(options.subharmonic) +
                     " must be in 1 … 64");
  }
  // N = 0 picks the default; a negative N is a mistake, not a request for it. 2^20 samples a
  // period is 64 times the default of the largest ansatz (νH = 64 × 63): more only costs time.
  constexpr int kMaxSamples = 1 << 20;
  if (options.samples < 0 || options.samples > kMaxSamples) {
    throw InputError("harmonic balance: samples: " + std::to_string(options.samples) +
                     " must be 0 (the default) or at most " + std::to_string(kMaxSamples));
  }
  return options;
}

}  // namespace

HarmonicBalance::HarmonicBalance(Model model, double freq_hz, const HbmOptions& options)
    : model_(std::move(model)),
      options_(checked(options)),
      march_(model_),
      grid_(options.harmonics * options.subharmonic, options.resolved_samples()) {
  set_frequency(freq_hz);
  const int n = grid_.samples();
  z_.resize(n);
  z_tau_.resize(n);
  z_dot_.resize(n);
  force_.resize(n);
  stiffness_.resize(n);
  damping_.resize(n);
  hysteretic_.setZero(n);
}

void HarmonicBalance::set_frequency(double freq_hz) {
  if (!std::isfinite(freq_hz) || freq_hz <= 0.0) {
    throw InputError("harmonic balance: frequency: " + std::to_string(freq_hz) +
                     " Hz must be positive");
  }
  freq_hz_ = freq_hz;
}

double HarmonicBalance::omega() const { return kTwoPi * freq_hz_; }
double HarmonicBalance::base_omega() const { return omega() / options_.subharmonic; }

void HarmonicBalance::evaluate_samples(const Eigen::VectorXd& x) {
  grid_.synthesise(x, z_, z_tau_);
  z_dot_ = base_omega() * z_tau_;  // ż = Ω dz/dτ
}

void HarmonicBalance::march_hysteresis(const Eigen::VectorXd& x) {
  if (!march_.active()) return;
  evaluate_samples(x);
  march_.forces(model_, z_, z_dot_, kTwoPi / base_omega(), hysteretic_);
}

void HarmonicBalance::residual(const Eigen::VectorXd& x, double f0_n, Eigen::VectorXd& r) {
  evaluate_samples(x);
  if (march_.active()) march_.forces(model_, z_, z_dot_, kTwoPi / base_omega(), hysteretic_);
  // Stateless terms at each instant (stateful ones give 0 without a state) plus the marched
  // force of the stateful ones.
  for (int n = 0; n < grid_.samples(); ++n)
    force_[n] = model_.restoring_force(z_[n], z_dot_[n], nullptr) + hysteretic_[n];
  grid_.analyse(force_, r);
  const double m = model_.mass_kg(), w = base_omega();
  for (int h = 1; h <= grid_.harmonics(); ++h) {
    const double inertia = -m * (h * w) * (h * w);  // m z̈ of a_h cos hτ + b_h sin hτ
    r[2 * h - 1] += inertia * x[2 * h - 1];
    r[2 * h] += inertia * x[2 * h];
  }
  r[forcing_sin_index()] -= f0_n;  // f = f0 sin ωt = f0 sin ντ
}

void HarmonicBalance::residual_and_jacobian(const Eigen::VectorXd& x, double f0_n,
                                            Eigen::VectorXd& r, Eigen::MatrixXd& jacobian) {
  residual(x, f0_n, r);  // leaves z_, z_dot_ and the stateful terms' march at the samples of x
  jacobian_after_residual(x, jacobian);
}

void HarmonicBalance::jacobian_after_residual(const Eigen::VectorXd& x, Eigen::MatrixXd& jacobian) {
  const int n = grid_.samples();
  for (int i = 0; i < n; ++i) {
    const TermPartials p = model_.partials(z_[i], z_dot_[i], nullptr);
    stiffness_[i] = p.d_dz;
    damping_[i] = p.d_dz_dot;
  }
  grid_.spectrum(stiffness_, stiffness_dft_);
  grid_.spectrum(damping_, damping_dft_);

  // J_ij = c_i (1/N) Σ_n u_i(τ_n) [K_n φ_j(τ_n) + C_n Ω φ_j'(τ_n)] + inertia, with c_0 = 1,
  // c_i = 2 otherwise; φ for a_q is cos qτ (φ' = −q sin qτ), for b_q sin qτ (φ' = q cos qτ).
  const int size = grid_.coefficient_count();
  jacobian.resize(size, size);
  const double w = base_omega(), m = model_.mass_kg();
  for (int i = 0; i < size; ++i) {
    const Trig u = (i == 0 || i % 2 == 1) ? kCos : kSin;
    const int p = (i + 1) / 2;
    const double weight = i == 0 ? 1.0 : 2.0;
    for (int j = 0; j < size; ++j) {
      const bool cosine = j == 0 || j % 2 == 1;
      const int q = (j + 1) / 2;
      double entry = mean_product(stiffness_dft_, n, u, p, cosine ? kCos : kSin, q);
      if (q > 0) {
        const double slope = w * q;
        entry += cosine ? -slope * mean_product(damping_dft_, n, u, p, kSin, q)
                        : slope * mean_product(damping_dft_, n, u, p, kCos, q);
      }
      jacobian(i, j) = weight * entry;
    }
  }
  for (int h = 1; h <= grid_.harmonics(); ++h) {
    const double inertia = -m * (h * w) * (h * w);
    jacobian(2 * h - 1, 2 * h - 1) += inertia;
    jacobian(2 * h, 2 * h) += inertia;
  }
  if (!march_.active()) return;
  if (march_.exact()) {
    // Stateful terms with the exact periodic solve: column j is the projection of δF for the
    // orbit perturbation φ_j (HysteresisMarch::sensitivity), the march's exact derivative,
    // projected by one forward FFT per column. The sampled basis is fixed by the grid: made once.
    if (basis_.cols() != n || basis_omega_ != w) {
      basis_.resize(size, n);
      basis_dot_.resize(size, n);
      Eigen::VectorXd unit = Eigen::VectorXd::Zero(size), value, derivative;
      for (int j = 0; j < size; ++j) {
        unit[j] = 1.0;
        grid_.synthesise(unit, value, derivative);
        basis_.row(j) = value.transpose();
        basis_dot_.row(j) = w * derivative.transpose();  // ż = Ω dz/dτ
        unit[j] = 0.0;
      }
      basis_omega_ = w;
    }
    march_.sensitivity(basis_, basis_dot_, basis_force_);
    Eigen::VectorXd samples(n);
    for (int j = 0; j < size; ++j) {
      samples = basis_force_.row(j).transpose();
      grid_.analyse(samples, projection_plus_);
      jacobian.col(j) += projection_plus_;
    }
    return;
  }
  // Other stateful terms: forward differences of the projected marched force, column by column.
  // The step is 1e-7 of the orbit's size (‖x‖∞, at least 1 µm): the marched force is smooth in x
  // between changes of the turning-point sample, and its rounding (~1e-16 relative) stays far
  // below the step's truncation error.
  grid_.analyse(hysteretic_, projection_);
  const Eigen::VectorXd base_force = hysteretic_;
  const double step = 1e-7 * std::max(x.cwiseAbs().maxCoeff(), 1e-6);
  Eigen::VectorXd shifted = x;
  for (int j = 0; j < size; ++j) {
    shifted[j] = x[j] + step;
    march_hysteresis(shifted);
    grid_.analyse(hysteretic_, projection_plus_);
    jacobian.col(j) += (projection_plus_ - projection_) / step;
    shifted[j] = x[j];
  }
  hysteretic_ = base_force;
  evaluate_samples(x);  // leave z_, z_dot_ at x, as residual() does
}

void HarmonicBalance::d_residual_d_f0(Eigen::VectorXd& out) const {
  out = Eigen::VectorXd::Zero(size());
  out[forcing_sin_index()] = -1.0;
}

void HarmonicBalance::d_residual_d_omega(const Eigen::VectorXd& x, Eigen::VectorXd& out) {
  // Ω = ω/ν. ∂/∂Ω of P[R(z, Ω z_τ)] is P[C z_τ]; of the inertia −m h²Ω² x_h it is −2 m h² Ω x_h.
  evaluate_samples(x);
  for (int n = 0; n < grid_.samples(); ++n) {
    force_[n] = model_.partials(z_[n], z_dot_[n], nullptr).d_dz_dot * z_tau_[n];
  }
  grid_.analyse(force_, out);
  const double m = model_.mass_kg(), w = base_omega();
  for (int h = 1; h <= grid_.harmonics(); ++h) {
    out[2 * h - 1] += -2.0 * m * h * h * w * x[2 * h - 1];
    out[2 * h] += -2.0 * m * h * h * w * x[2 * h];
  }
  out /= options_.subharmonic;  // dΩ/dω
}

Eigen::VectorXd HarmonicBalance::linear_guess(double z_star_m, double f0_n) const {
  // m z̈ + C ż + K (z − z*) = f0 sin ωt = Re(−i f0 e^{iωt}): Z = −i f0 / (K − mω² + iωC).
  TermPartials p = model_.partials(z_star_m, 0.0, nullptr);
  // A small loop of a rate-independent hysteresis is a spring: without it the guess for a stiff
  // presliding contact is a sliding orbit orders of magnitude too large.
  p.d_dz += small_loop_stiffness_n_m(model_, z_star_m);
  const double w = omega();
  const std::complex<double> z1 =
      std::complex<double>(0.0, -f0_n) /
      std::complex<double>(p.d_dz - model_.mass_kg() * w * w, w * p.d_dz_dot);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(size());
  x[0] = z_star_m;
  x[forcing_cos_index()] = z1.real();   // a = Re Z
  x[forcing_sin_index()] = -z1.imag();  // b = −Im Z
  return x;
}

NewtonReport HarmonicBalance::solve(Eigen::VectorXd& x, double f0_n, const NewtonOptions& options) {
  NewtonReport report;
  Eigen::VectorXd r(size()), trial_r(size()), step(size());
  Eigen::MatrixXd jacobian(size(), size());
  residual_and_jacobian(x, f0_n, r, jacobian);
  report.residual_norm_n = r.norm();
  for (report.iterations = 0; report.iterations < options.max_iterations; ++report.iterations) {
    if (!std::isfinite(report.residual_norm_n)) {
      report.status = NewtonReport::Status::NumericalIssue;
      report.message = "residual is not finite";
      return report;
    }
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(jacobian);
    const double det = lu.determinant();
    report.jacobian_sign = det > 0.0 ? 1 : (det < 0.0 ? -1 : 0);
    if (report.residual_norm_n <= options.residual_tolerance_n) {
      report.status = NewtonReport::Status::Converged;
      return report;
    }
    step = -lu.solve(r);
    if (!step.allFinite()) {
      report.status = NewtonReport::Status::NumericalIssue;
      report.message = "singular Jacobian";
      return report;
    }
    // Backtracking: halve the step while the residual grows (globalises Newton from a rough
    // linear guess; a full step is always taken near the solution).
    double scale = 1.0;
    Eigen::VectorXd trial = x + step;
    residual(trial, f0_n, trial_r);
    for (int k = 0; k < 8 && !(trial_r.norm() < report.residual_norm_n); ++k) {
      scale *= 0.5;
      trial = x + scale * step;
      residual(trial, f0_n, trial_r);
    }
    x = trial;
    report.step_norm = scale * step.norm();
    // The last residual evaluated was the accepted trial's: its samples and march stand.
    r = trial_r;
    jacobian_after_residual(x, jacobian);
    report.residual_norm_n = r.norm();
  }
  if (report.residual_norm_n <= options.residual_tolerance_n) {
    const double det = Eigen::PartialPivLU<Eigen::MatrixXd>(jacobian).determinant();
    report.jacobian_sign = det > 0.0 ? 1 : (det < 0.0 ? -1 : 0);
    report.status = NewtonReport::Status::Converged;
  } else {
    report.status = NewtonReport::Status::NoConvergence;
    report.message = "no convergence in " + std::to_string(options.max_iterations) +
                     " iterations (|r| = " + std::to_string(report.residual_norm_n) + " N)";
  }
  return report;
}

HbmMeasures HarmonicBalance::measure(const Eigen::VectorXd& x, double f0_n) {
  HbmMeasures out;
  evaluate_samples(x);
  const int n = grid_.samples();
  out.amp_m = half_peak_to_peak(x);
  out.mean_m = x[0];
  out.z1_m = {x[forcing_cos_index()], -x[forcing_sin_index()]};
  // Eq. (13) with docs/conventions.md's sign: S = π f0 |Z1| sin θ1, θ1 = −π/2 − arg Z1, which is
  // −π f0 Re Z1. Valid with a sub-harmonic ansatz too: f pairs only with base harmonic ν.
  out.edc_j = -std::numbers::pi * f0_n * out.z1_m.real();
  // ∮ D dz = ∫ D ż dt over the base period 2π/Ω, by the rectangle rule (exact for trigonometric
  // polynomials of degree < N), per forcing cycle (÷ ν).
  double power_sum = 0.0;
  if (march_.active()) march_.forces(model_, z_, z_dot_, kTwoPi / base_omega(), hysteretic_);
  for (int i = 0; i < n; ++i)
    power_sum += (model_.dissipative_force(z_[i], z_dot_[i], nullptr) + hysteretic_[i]) * z_dot_[i];
  const double period_s = kTwoPi / base_omega();
  out.edc_dissipation_j = power_sum * period_s / n / options_.subharmonic;
  return out;
}

double HarmonicBalance::half_peak_to_peak(const Eigen::VectorXd& x) {
  // Extremes of z on a grid of 256 samples per forcing period, each refined by the parabola
  // through it and its neighbours: for a smooth periodic z the vertex error is O(Δτ⁴) ≈ 1e-9
  // relative, where the bare grid maximum would be off by O(Δτ²) ≈ 1e-4.
  const int count =
      std::max(256 * options_.subharmonic, next_power_of_two(4 * base_harmonics() + 1));
  sample(x, count, amp_z_, amp_z_dot_);
  auto refined = [&](Eigen::Index i) {
    const double left = amp_z_[(i + count - 1) % count], mid = amp_z_[i],
                 right = amp_z_[(i + 1) % count];
    const double curvature = left - 2.0 * mid + right;
    if (curvature == 0.0) return mid;
    const double offset = 0.5 * (left - right) / curvature;
    return mid - 0.25 * (left - right) * offset;
  };
  Eigen::Index i_max = 0, i_min = 0;
  amp_z_.maxCoeff(&i_max);
  amp_z_.minCoeff(&i_min);
  return 0.5 * (refined(i_max) - refined(i_min));
}

void HarmonicBalance::sample(const Eigen::VectorXd& x, int count, Eigen::VectorXd& z_m,
                             Eigen::VectorXd& z_dot_m_s) {
  FourierGrid* grid = nullptr;
  for (const auto& g : samplers_) {
    if (g->samples() == count) grid = g.get();
  }
  if (!grid) {
    samplers_.push_back(std::make_unique<FourierGrid>(grid_.harmonics(), count));
    grid = samplers_.back().get();
  }
  grid->synthesise(x, z_m, z_dot_m_s);
  z_dot_m_s *= base_omega();
}

}  // namespace oscilab::analysis
