#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/model/model.h"
#include "analysis/simulation/table_motion.h"

namespace oscilab::analysis {

/// Time integration of eq. (1), m z̈ + R(z, ż, s) = f(t) = −m b̈(t), under a table motion.
///
/// Method: the embedded Dormand–Prince 5(4) pair with error control (Boost.Odeint
/// `runge_kutta_dopri5` in a controlled stepper; Dormand & Prince 1980, "A family of embedded
/// Runge–Kutta formulae"). Steps are shortened to land exactly on every output sample and probe
/// time, so no reported state is interpolated. The friction switch of eq. (5) is smooth (tanh over
/// v_t) but steep: the step control shrinks the step through each |ż| ≲ v_t passage and grows it
/// again in between, which a fixed step cannot do at a comparable cost. The largest switch
/// stiffness, ∂D/∂ż ≈ 4 f_d / v_t (≈ 180 N s/m for Table 3, time constant m/(∂D/∂ż) ≈ 1.5 ms),
/// stays within the explicit method's stability region at the steps the accuracy needs, so an
/// implicit method buys nothing.
///
/// The state is augmented with two energy integrals, W_in = ∫ f ż dt and W_diss = ∫ D ż dt,
/// integrated by the same error-controlled scheme, so the energy balance
/// W_in − W_diss − ΔE_mech = 0 (E_mech = ½ m ż² + U(z)) holds to the integration tolerance and
/// dissipated energies need no numerical quadrature of sampled data.
class TimeSimulator {
 public:
  struct Options {
    double relative_tolerance = 1e-9;  // per-step local error, relative to the state
    /// Absolute tolerance, applied to every state (z in m, ż in m/s, energies in J). 1e-12
    /// resolves displacements of 1e-12 m and energies of 1e-12 J, far below sensor noise.
    double absolute_tolerance = 1e-12;
    /// Largest step; 0: the smaller of one output interval and 2 ms (≥ 50 steps per period of a
    /// 9 Hz forcing even where the error estimate would allow more).
    double max_step_s = 0.0;
  };
  enum class Status { Ok, Cancelled, NumericalIssue };
  /// The most samples one run holds: a day at 512 Hz is 44 M, and a run keeps 9 doubles a sample
  /// (72 B; the virtual rig adds 3 more), so 50 M samples stay under 5 GB. A longer or faster run
  /// is refused before anything is allocated.
  static constexpr double kMaxSamples = 50e6;
  /// What to integrate: initial conditions, length, output rate, and probe times at which the
  /// energy integrals are read (e.g. forcing-cycle boundaries); steps land on them exactly.
  struct Run {
    double z0_m = 0.0;
    double z_dot0_m_s = 0.0;
    double duration_s = 0.0;
    double sample_rate_hz = 512.0;
    std::vector<double> probe_times_s;  // increasing, within [0, duration_s]
  };
  /// Samples at t_k = k / sample_rate_hz; names match the truth file's columns.
  struct Result {
    Status status = Status::Ok;
    std::string message;
    Eigen::VectorXd t_s, z_m, z_dot_m_s, z_ddot_m_s2;
    Eigen::VectorXd f_n;                // −m b̈
    Eigen::VectorXd restoring_force_n;  // R = K + D
    Eigen::VectorXd damping_force_n;    // D
    Eigen::VectorXd work_in_j;          // ∫₀ᵗ f ż dt
    Eigen::VectorXd dissipated_j;       // ∫₀ᵗ D ż dt
    /// At each probe time: W_in, W_diss and E_mech = ½ m ż² + U(z).
    Eigen::VectorXd probe_t_s, probe_work_in_j, probe_dissipated_j, probe_mechanical_j;
    long rhs_evaluations = 0;
  };

  TimeSimulator(Model model, Options options);  // throws InputError on bad options

  /// Integrates from rest-or-given initial conditions over [0, duration_s]. Progress is reported
  /// about once per simulated second; cancellation is polled as often and returns the samples
  /// computed so far with Status::Cancelled.
  Result simulate(const TableMotion& motion, const Run& run, const ProgressFn& progress = {},
                  const CancelToken& cancel = {}) const;

  const Model& model() const { return model_; }

 private:
  Model model_;
  Options options_;
};

}  // namespace oscilab::analysis
