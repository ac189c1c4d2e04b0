#pragma once

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/hbm/fourier_grid.h"
#include "analysis/hbm/hysteresis_march.h"
#include "analysis/model/model.h"

namespace oscilab::analysis {

/// Size of the harmonic-balance ansatz.
struct HbmOptions {
  /// H: harmonics of the forcing frequency ω kept in the response (eq. (12)).
  int harmonics = 7;
  /// ν: the ansatz has the base frequency Ω = ω/ν (ν = 1, 2, 4 …) and ν·H harmonics of it, so a
  /// period-νT response is resolved as finely as a period-T one with H harmonics. The forcing is
  /// base harmonic ν.
  int subharmonic = 1;
  /// N: time samples per base period for the alternating frequency–time scheme; 0 picks
  /// default_samples(). Must exceed 2νH.
  int samples = 0;

  /// The default N: the power of two ≥ 8νH + 1 (at least 32). A cubic K(z) of a response with
  /// νH harmonics has 3νH harmonics, and N ≥ 4νH + 1 keeps them from aliasing onto the ansatz's
  /// harmonics and makes ∮ K dz vanish exactly on the grid (U(z(τ)) has 4νH harmonics). The
  /// friction force is not a polynomial; its harmonics decay only like 1/h, and the factor 2
  /// above 4νH halves their aliasing error again (see docs/hbm.md for the measured effect).
  static int default_samples(int harmonics, int subharmonic);
  int resolved_samples() const;
};

/// Result of a Newton solve: a status and a message, never an exception.
struct NewtonReport {
  enum class Status { Converged, NoConvergence, NumericalIssue };
  Status status = Status::NoConvergence;
  std::string message;
  int iterations = 0;
  double residual_norm_n = 0.0;  // ‖r‖₂ of the last iterate, N
  double step_norm = 0.0;        // ‖Δx‖₂ of the last step (in the solver's unknowns)
  /// Sign of det ∂r/∂x at the last iterate: it flips across a fold of the branch, so a caller
  /// stepping in the parameter can tell that it has jumped one.
  int jacobian_sign = 0;
  bool converged() const { return status == Status::Converged; }
};

struct NewtonOptions {
  int max_iterations = 30;
  /// ‖r‖₂ below which the balance is met, N. 1e-11 N is ~1e-11 of the forces at play here (order
  /// 1 N), a few hundred times double rounding of the FFT sums.
  double residual_tolerance_n = 1e-11;
};

/// What a converged harmonic-balance point says about the motion.
struct HbmMeasures {
  double amp_m = 0.0;              // (max z − min z) / 2 over the response period
  std::complex<double> z1_m;       // Z1: complex amplitude of e^{iωt} (base harmonic ν)
  double edc_j = 0.0;              // eq. (13), our sign: π f0 |Z1| sin θ1 = −π f0 Re Z1
  double edc_dissipation_j = 0.0;  // ∮ D dz per forcing cycle from the time samples
  double mean_m = 0.0;             // Z0
};

/// Harmonic balance of eq. (1), m z̈ + R(z, ż) = f0 sin ωt, with the alternating frequency–time
/// scheme (Cameron & Griffin 1989, "An alternating frequency/time domain method for calculating
/// the steady-state response of nonlinear dynamic systems").
///
/// Unknowns x = [a0, a1, b1, …, a_M, b_M] (M = νH) of z(τ) = a0 + Σ a_h cos hτ + b_h sin hτ,
/// τ = Ωt, Ω = ω/ν, ż = Ω dz/dτ. The residual is the Galerkin projection of the equation of
/// motion onto the same functions (derivation in docs/hbm.md):
///
///   r_0   = P_0[R]
///   r_a,h = −m (hΩ)² a_h + P_c,h[R]
///   r_b,h = −m (hΩ)² b_h + P_s,h[R] − f0 δ_{hν}
///
/// with P_0 = (1/N) Σ_n, P_c,h = (2/N) Σ_n cos hτ_n, P_s,h = (2/N) Σ_n sin hτ_n over the N samples
/// R_n = R(z(τ_n), ż(τ_n)) (one forward real FFT). The Jacobian is analytic: with the sampled
/// partials K_n = ∂R/∂z, C_n = ∂R/∂ż,
///
///   ∂P_i[R]/∂x_j = P_i[K φ_j + C Ω φ_j']   (φ_j the basis function of x_j)
///
/// and, by cos·cos = ½(cos(i−j) + cos(i+j)) etc., every entry is a sum of two DFT bins of K_n and
/// of C_n: two forward FFTs and O(M²) additions instead of O(N M²).
///
/// Terms with internal state (hysteresis, e.g. the Dahl element) enter through their periodic
/// steady force along the sampled orbit (HysteresisMarch). Their force depends on the whole path,
/// not on (z, ż) at one instant. For terms that give their step sensitivities (the Dahl element)
/// the periodic state is solved exactly and their part of the Jacobian is the march's exact
/// derivative (one O(N) recurrence and one FFT per column); for others the states are marched
/// period after period and that part of the Jacobian is taken by forward differences. The
/// stateless terms keep the analytic Jacobian above. Floquet stability does not cover stateful
/// terms.
///
/// Thread-safety: not thread-safe (owns FFT buffers); use one object per thread.
class HarmonicBalance {
 public:
  /// Throws InputError for H < 1, ν < 1, freq ≤ 0 or N ≤ 2νH.
  HarmonicBalance(Model model, double freq_hz, const HbmOptions& options);

  const Model& model() const { return model_; }
  const HbmOptions& options() const { return options_; }
  int size() const { return grid_.coefficient_count(); }
  int base_harmonics() const { return grid_.harmonics(); }
  int samples() const { return grid_.samples(); }
  int forcing_harmonic() const { return options_.subharmonic; }
  /// Index in x of a_ν and b_ν (the forcing harmonic).
  int forcing_cos_index() const { return 2 * options_.subharmonic - 1; }
  int forcing_sin_index() const { return 2 * options_.subharmonic; }

  void set_frequency(double freq_hz);
  double frequency_hz() const { return freq_hz_; }
  double omega() const;       // ω = 2πν_f, rad/s
  double base_omega() const;  // Ω = ω/ν, rad/s

  /// r(x; f0), N.
  void residual(const Eigen::VectorXd& x, double f0_n, Eigen::VectorXd& r);
  /// r and ∂r/∂x (N/m).
  void residual_and_jacobian(const Eigen::VectorXd& x, double f0_n, Eigen::VectorXd& r,
                             Eigen::MatrixXd& jacobian);
  /// ∂r/∂f0 (dimensionless): −1 at b_ν.
  void d_residual_d_f0(Eigen::VectorXd& out) const;
  /// ∂r/∂ω at x (N s/rad), for continuation in frequency.
  void d_residual_d_omega(const Eigen::VectorXd& x, Eigen::VectorXd& out);

  /// The linear response about the equilibrium `z_star_m` (stiffness and damping linearised
  /// there), a starting guess for Newton.
  Eigen::VectorXd linear_guess(double z_star_m, double f0_n) const;

  /// Newton's method at fixed f0 and ω, from x (overwritten with the last iterate).
  NewtonReport solve(Eigen::VectorXd& x, double f0_n, const NewtonOptions& options = {});

  /// Amplitude, first harmonic and both EDCs of the point x.
  HbmMeasures measure(const Eigen::VectorXd& x, double f0_n);

  /// z and ż on `count` equally spaced instants of one base period (count > 2νH), starting at
  /// t = 0: used by the variational equation and the tests.
  void sample(const Eigen::VectorXd& x, int count, Eigen::VectorXd& z_m,
              Eigen::VectorXd& z_dot_m_s);

 private:
  /// ∂r/∂x at x right after residual(x, …): the samples, partials and the stateful terms' march
  /// that residual left are used as they are (Newton evaluates the accepted step's residual once).
  void jacobian_after_residual(const Eigen::VectorXd& x, Eigen::MatrixXd& jacobian);
  void evaluate_samples(const Eigen::VectorXd& x);
  /// The stateful terms' periodic force at the samples of x into hysteretic_ (zero without them).
  void march_hysteresis(const Eigen::VectorXd& x);
  double half_peak_to_peak(const Eigen::VectorXd& x);

  Model model_;
  HbmOptions options_;
  HysteresisMarch march_;  // the stateful terms of model_
  double freq_hz_ = 0.0;
  FourierGrid grid_;
  std::vector<std::unique_ptr<FourierGrid>> samplers_;  // one grid per sample() count used
  // Work buffers sized once.
  Eigen::VectorXd amp_z_, amp_z_dot_;
  Eigen::VectorXd z_, z_tau_, z_dot_, force_, force_coefficients_, stiffness_, damping_;
  Eigen::VectorXd hysteretic_, hysteretic_plus_, projection_, projection_plus_;
  Eigen::MatrixXd basis_, basis_dot_,
      basis_force_;           // exact stateful Jacobian: φ_j, Ω φ_j' and δF_j
  double basis_omega_ = 0.0;  // Ω of basis_dot_
  std::vector<std::complex<double>> stiffness_dft_, damping_dft_;
};

}  // namespace oscilab::analysis
