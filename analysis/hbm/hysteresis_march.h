#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "analysis/model/model.h"

namespace oscilab::analysis {

/// The stiffness of a small loop about z of the model's rate-independent hysteresis, in N/m:
/// Σ ∂F/∂s ∂s/∂z at rest (F_c κ = σ0 for the Dahl element, f_d(z)/δ for a friction in its
/// presliding regime); 0 without such terms. A stuck contact is this spring: the response's
/// linear guess needs it, and the mass rings on it at √(k/m), which harmonic balance must
/// resolve.
double small_loop_stiffness_n_m(const Model& model, double z_m);

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
///   (plus terms in δż_k and δż_{k+1} for a step whose Hermite path turns: it is marched through
///   the turning point, hermite_turning_point, so that the state is continuous in the orbit)
///   solved as u_k (the recurrence from u_0 = 0) plus P_k δs_0 with P_k = Π_{i<k} a_i and
///   δs_0 = u_N / (1 − A); then δF_k = Σ_terms (∂F/∂s δs_k + ∂F/∂z|_s δz_k), the second part for
///   a state part that also depends on z (the presliding regime's f_d(z) s). O(N) per direction,
///   no step size.
///
/// The forces are the state parts, force(z, ż, s) − force(z, ż, nullptr) (ModelTerm, "force
/// without a state"): the stateless parts are the caller's, as for every other term.
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

  /// force_n[k] = Σ_i F_i(z_k, ż_k, s_i(t_k)) − F_i(z_k, ż_k, ∅), the state parts of the stateful
  /// terms' forces at the N samples of one period
  /// (t_k = k T / N). Returns the marches made (periods, or Newton marches of the exact solve).
  int forces(const Model& model, const Eigen::VectorXd& z_m, const Eigen::VectorXd& z_dot_m_s,
             double period_s, Eigen::VectorXd& force_n);

  /// Exact solve only: δF at the samples of the last forces() orbit for M perturbations of it:
  /// column k of `dz_m` and of `dz_dot_m_s` (M × N) hold the M directions' δz and δż at sample
  /// k, and so does `dforce_n`. δż enters through the turning points only (a step whose path
  /// turns is marched through the turning point, whose z depends on the ends' slopes).
  void sensitivity(const Eigen::MatrixXd& dz_m, const Eigen::MatrixXd& dz_dot_m_s,
                   Eigen::MatrixXd& dforce_n) const;

 private:
  int exact_forces(const Model& model, const Eigen::VectorXd& z_m, const Eigen::VectorXd& z_dot_m_s,
                   double period_s, Eigen::VectorXd& force_n);
  int marched_forces(const Model& model, const Eigen::VectorXd& z_m,
                     const Eigen::VectorXd& z_dot_m_s, double period_s, Eigen::VectorXd& force_n);

  double tolerance_;
  int max_periods_;
  bool exact_ = false;
  std::vector<std::size_t> terms_;
  std::vector<double> state_, start_of_period_;
  // Exact solve, per stateful term (rows) and step k (columns): ∂s_{k+1}/∂s_k, ∂s_{k+1}/∂z_k,
  // ∂s_{k+1}/∂z_{k+1}, ∂s_{k+1}/∂ż_k, ∂s_{k+1}/∂ż_{k+1}, ∂F/∂s and ∂F/∂z at fixed s at sample k,
  // the prefix products P_k, and 1 − A.
  Eigen::MatrixXd a_, p_, q_, r_, w_, force_slope_, force_dz_, prefix_, states_;
  Eigen::VectorXd one_minus_a_;
};

}  // namespace oscilab::analysis
