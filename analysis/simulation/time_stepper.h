#pragma once

#include <memory>
#include <vector>

#include "analysis/model/model.h"
#include "analysis/simulation/table_motion.h"

namespace oscilab::analysis {

/// The error-controlled integration of eq. (1), m z̈ + R(z, ż, s) = f(t) = −m b̈(t), as a state
/// that advances on request: TimeSimulator drives it over a whole run, the live virtual rig block
/// by block while the operator changes the excitation.
///
/// Method (see TimeSimulator): embedded Dormand–Prince 5(4) with step control (Boost.Odeint);
/// every requested time is landed on exactly (no interpolation). The state is augmented with
/// W_in = ∫ f ż dt and W_diss = ∫ D ż dt, so energies need no quadrature of sampled data.
///
/// Holds a reference to `model`, which must outlive it. Not thread-safe.
class TimeStepper {
 public:
  /// State layout: [z, ż, W_in, W_diss, s_0 ... s_{n−1}] (s: the terms' internal states).
  static constexpr std::size_t kZ = 0, kZDot = 1, kWorkIn = 2, kDissipated = 3, kInternal = 4;

  /// Starts at t = 0 in (z0, ż0) with the terms' internal states at rest. Tolerances as
  /// TimeSimulator::Options; `max_step_s` > 0 bounds every step.
  TimeStepper(const Model& model, double relative_tolerance, double absolute_tolerance,
              double max_step_s, double z0_m, double z_dot0_m_s);
  ~TimeStepper();
  TimeStepper(const TimeStepper&) = delete;
  TimeStepper& operator=(const TimeStepper&) = delete;

  /// Integrates from time_s() to t_target_s under `motion` (nothing when t_target_s ≤ time_s()).
  /// Returns false when the step size underflows or the state stops being finite; the state is
  /// then that of the last good step.
  bool advance_to(const TableMotion& motion, double t_target_s);

  double time_s() const { return t_s_; }
  const std::vector<double>& state() const { return x_; }
  double z_m() const { return x_[kZ]; }
  double z_dot_m_s() const { return x_[kZDot]; }
  /// The terms' internal states, or null when the model has none.
  const double* internal_state() const {
    return model_.state_size() > 0 ? x_.data() + kInternal : nullptr;
  }
  long rhs_evaluations() const { return rhs_evaluations_; }

 private:
  struct Controller;  // Boost.Odeint's controlled stepper, kept between calls (FSAL derivative)
  const Model& model_;
  std::unique_ptr<Controller> controller_;
  std::vector<double> x_;
  double t_s_ = 0.0;
  double step_s_;
  const TableMotion* last_motion_ = nullptr;
  long rhs_evaluations_ = 0;
};

}  // namespace oscilab::analysis
