#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "analysis/model/model.h"

namespace oscilab::analysis {

/// The periodic steady force of a model's terms with internal state (hysteresis) along a periodic
/// orbit that harmonic balance has sampled: what the alternating frequency–time scheme needs to
/// treat a hysteretic term like any other force.
///
/// The states are marched sample to sample with ModelTerm::advance_state (exact for the Dahl
/// element), starting from rest where the orbit crosses its mean value upwards (a virgin start at
/// the centre gives the centred loop of a symmetric cycle at once), period after period until the
/// states at the start of two successive periods agree to `tolerance` (at most `max_periods`);
/// the force of the last period is the result. Rate-independent hysteresis settles within a
/// period or two once the cycle exceeds its presliding range; small elastic-hysteretic loops
/// settle as e^(−2κ·peak-to-peak) per period.
///
/// Thread-safety: not thread-safe (scratch buffers); one object per HarmonicBalance.
class HysteresisMarch {
 public:
  /// For `model`'s stateful terms; later calls must pass the same model (or a copy).
  explicit HysteresisMarch(const Model& model, double tolerance = 1e-11, int max_periods = 24);

  /// Whether the model has any term with a state.
  bool active() const { return !terms_.empty(); }

  /// force_n[k] = Σ_i F_i(z_k, ż_k, s_i(t_k)) of the stateful terms at the N samples of one period
  /// (t_k = k T / N). Returns the periods marched.
  int forces(const Model& model, const Eigen::VectorXd& z_m, const Eigen::VectorXd& z_dot_m_s,
             double period_s, Eigen::VectorXd& force_n);

 private:
  double tolerance_;
  int max_periods_;
  std::vector<std::size_t> terms_;
  std::vector<double> state_, start_of_period_;
};

}  // namespace oscilab::analysis
