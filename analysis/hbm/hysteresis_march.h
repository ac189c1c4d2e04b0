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
/// Step k moves a term's state from sample k to sample k + 1 (indices mod N) with
/// ModelTerm::advance_state. Two ways to the periodic state:
///
/// - **Exact periodic solve** (terms with one rate-independent state value that give their step
///   sensitivities, e.g. the Dahl element). One period is a map s_N = Φ(s_0) with slope
///   A = Π_k ∂s_{k+1}/∂s_k, so the periodic state is the root of g(s_0) = Φ(s_0) − s_0, found by
///   Newton, s_0 ← s_0 + g / (1 − A), exact in one step for the Dahl element, whose steps are
///   affine in s: then the marched states shift by P_k Δs_0 and one march is all it takes. 1 − A is
///   taken as −expm1(Σ ln ∂s_{k+1}/∂s_k), accurate even for loops far below the presliding length
///   (A → 1), where marching period after period would settle only as A^periods. The same
///   recurrence gives the force's exact derivative with respect to the orbit (sensitivity()): for a
///   perturbation δz_k of the samples,
///
///     δs_{k+1} = a_k δs_k + p_k δz_k + q_k δz_{k+1},   δs_0 = δs_N (periodic),
///
///   solved as u_k (the recurrence from u_0 = 0) plus P_k δs_0 with P_k = Π_{i<k} a_i and
///   δs_0 = u_N / (1 − A); then δF_k = Σ_terms ∂F/∂s δs_k. O(N) per direction, no step size.
/// - **Marching** (any other stateful term): from rest where the orbit crosses its mean upwards,
///   period after period until the states at the start of two successive periods agree to
///   `tolerance` (at most `max_periods`); the force of the last period is the result.
///
/// Thread-safety: not thread-safe (scratch buffers); one object per HarmonicBalance.
class HysteresisMarch {
 public:
  /// For `model`'s stateful terms; later calls must pass the same model (or a copy).
  explicit HysteresisMarch(const Model& model, double tolerance = 1e-11, int max_periods = 24);

  /// Whether the model has any term with a state.
  bool active() const { return !terms_.empty(); }
  /// Whether the exact periodic solve and sensitivity() are available for every stateful term.
  bool exact() const { return exact_; }

  /// force_n[k] = Σ_i F_i(z_k, ż_k, s_i(t_k)) of the stateful terms at the N samples of one period
  /// (t_k = k T / N). Returns the marches made (periods, or Newton marches of the exact solve).
  int forces(const Model& model, const Eigen::VectorXd& z_m, const Eigen::VectorXd& z_dot_m_s,
             double period_s, Eigen::VectorXd& force_n);

  /// Exact solve only: δF at the samples of the last forces() orbit for M perturbations δz of its
  /// samples: column k of `dz_m` (M × N) holds the M directions at sample k, and so does
  /// `dforce_n` (the stateful terms' forces depend on z through their states only).
  void sensitivity(const Eigen::MatrixXd& dz_m, Eigen::MatrixXd& dforce_n) const;

 private:
  int exact_forces(const Model& model, const Eigen::VectorXd& z_m, const Eigen::VectorXd& z_dot_m_s,
                   Eigen::VectorXd& force_n);
  int marched_forces(const Model& model, const Eigen::VectorXd& z_m,
                     const Eigen::VectorXd& z_dot_m_s, double period_s, Eigen::VectorXd& force_n);

  double tolerance_;
  int max_periods_;
  bool exact_ = false;
  std::vector<std::size_t> terms_;
  std::vector<double> state_, start_of_period_;
  // Exact solve, per stateful term (rows) and step k (columns): ∂s_{k+1}/∂s_k, ∂s_{k+1}/∂z_k,
  // ∂s_{k+1}/∂z_{k+1}, ∂F/∂s at sample k, the prefix products P_k, and 1 − A.
  Eigen::MatrixXd a_, p_, q_, force_slope_, prefix_, states_;
  Eigen::VectorXd one_minus_a_;
};

}  // namespace oscilab::analysis
