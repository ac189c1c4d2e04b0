#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/hbm/harmonic_balance.h"
#include "analysis/model/model.h"

namespace oscilab::analysis {

/// The model's steady response at the levels of a stepped-sine test (§4.2): what an
/// identification compares with the measured EDCs, one call per well and candidate θ.
struct LevelResponse {
  JobStatus status = JobStatus::Ok;
  std::string message;
  std::vector<double> f0_n;
  std::vector<double> edc_j;  // eq. (13), our sign (docs/conventions.md)
  std::vector<double> amp_m;
  std::vector<Eigen::VectorXd> coefficients;
  int newton_iterations = 0;
  bool used_arclength = false;  // the fast path failed and a full continuation was run
  int harmonics = 0;            // H of the responses (more than asked when a contact rings)
  int branch_switched = 0;      // levels taken from the top level's branch followed down
};

/// |Z_h| of harmonic h ≥ 1 of a solution's coefficients [a_0, a_1, b_1, …, a_H, b_H]: zero for
/// h > H, which a truncated balance does not hold (a solution at H = 1 has no second harmonic).
inline double harmonic_amplitude(const Eigen::VectorXd& coefficients, int h) {
  const Eigen::Index sine = 2 * static_cast<Eigen::Index>(h);
  return sine < coefficients.size() ? std::hypot(coefficients[sine - 1], coefficients[sine]) : 0.0;
}

/// The most harmonics level_response() raises H to for a ringing contact.
inline constexpr int kMaxContactHarmonics = 63;

/// H that resolves the ringing of the model's stuck contacts in the well: 1.5 √(k/m)/ω with k
/// the small-loop stiffness of its hysteresis (small_loop_stiffness_n_m); 0 without one.
/// Measured on the paper's friction in its presliding regime (9 Hz, 0.05 → 2.7 N): the branch
/// through the stick–slip transition is found for δ ≥ 1 µm at this H and above (at δ = 1 µm,
/// H = 35 to 63), and not reliably below 1 µm at any H up to 63.
int contact_resolving_harmonics(const Model& model, double freq_hz, bool positive_well);

/// Responses at increasing levels, as a sweep up from rest would find them: each level is solved
/// by Newton from the extrapolation of the previous two (natural continuation, cheap and, since
/// the levels increase, on the branch a sweep up follows). If a solve fails, or the sign of
/// det ∂r/∂x flips (the step crossed a fold onto the unstable part), the whole set is computed
/// instead by pseudo-arclength continuation from rest with a landing at every level, taking each
/// level's first crossing. When the model's stuck contact rings above the harmonics asked for
/// (contact_resolving_harmonics), every level is solved with H raised to resolve the ringing (at
/// most kMaxContactHarmonics; `harmonics` says the H used). Throws InputError for decreasing or
/// negative levels or a model that harmonic balance cannot handle.
///
/// With `measured_z1_abs_m` (the measured |Z1| of each level, as many as levels; empty: none)
/// the responses follow the branch the measurement was taken on where the model has two: when the
/// sweep handed over to arclength continuation (a fold ahead, or Newton failing even in small
/// steps) and a level's swept |Z1| is off the measured one by more than
/// kBranchMismatch of it, the branch of the top level is followed down by natural continuation
/// (stopping at its fold, where the sign of det ∂r/∂x flips), and each mismatched level takes that
/// solution when it is another branch (|Z1| apart by more than kBranchMismatch) closer to the
/// measured. Between the two folds of a jump both branches are stable responses of the model; a
/// model whose fold lies a little above a level where the specimen had already jumped (or a step
/// that kicked the specimen over early) is then compared on the specimen's branch, and the
/// comparison does not leap when θ moves a fold across a level. `branch_switched` counts the
/// levels taken from the branch followed down.
LevelResponse level_response(const Model& model, double freq_hz, bool positive_well,
                             const std::vector<double>& levels_n, const HbmOptions& hbm = {},
                             const std::vector<double>& measured_z1_abs_m = {});

/// The relative |Z1| mismatch above which level_response looks for the measured branch: 25 %, far
/// beyond what a parameter change of a fit moves on one branch between neighbouring evaluations
/// and below the factor of 2 to 4 between the branches of a jump (Fig. 11b).
inline constexpr double kBranchMismatch = 0.25;

/// The responses of models near `model` (parameters changed a little) at the levels of `base`,
/// `model`'s level_response with these options, without solving each again: at each level one
/// Newton step from base's solution x with `model`'s Jacobian there,
///
///   x_j = x − J(x)⁻¹ (r_j(x) − r(x)),
///
/// which is the implicit-function derivative dx/dθ = −J⁻¹ ∂r/∂θ applied to the change (exact to
/// first order in it: what a finite-difference Jacobian of a fit needs, at the cost of one
/// Jacobian and one residual per nearby model instead of a continuation each). The responses use
/// base's H. A response whose step is not finite has status NumericalIssue and no levels.
std::vector<LevelResponse> nearby_level_responses(const Model& model,
                                                  const std::vector<Model>& nearby, double freq_hz,
                                                  const LevelResponse& base,
                                                  const HbmOptions& hbm = {});

}  // namespace oscilab::analysis
