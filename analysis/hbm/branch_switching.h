#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/hbm/branch.h"
#include "analysis/hbm/continuation.h"
#include "analysis/model/model.h"

namespace oscilab::analysis {

/// Options of a switch from a period-νT branch onto the period-2νT branch born at its period
/// doubling (a sub-harmonic ansatz follows the period-doubled branch).
struct PeriodDoublingSwitchOptions {
  /// The continuation of the new branch. hbm.harmonics, hbm.samples and hbm.subharmonic describe
  /// the ansatz of the *flip point* (ν, as on the branch it comes from); the new branch uses 2ν
  /// (and 2N when N was given). freq_hz, positive_well, step control, stability and landings apply
  /// to the new branch; [min(start, end), max(start, end)] is the f0 range it may cover, and it
  /// runs from the flip to whichever end the branch bends towards (the larger f0 for a
  /// supercritical flip). initial_coefficients is ignored.
  ContinuationOptions continuation;
  /// ε: the predictor's step along the critical eigenvector, m (in the sub-harmonic coefficients);
  /// 0 picks 2 % of the flip orbit's amplitude. Too small and the corrector's bordered matrix is
  /// nearly singular (it is exactly at ε = 0, a pitchfork of the doubled ansatz); too large and
  /// the first point lands far from the flip.
  double perturbation_m = 0.0;
  /// How far from the Floquet flip to look for the harmonic-balance pitchfork (where the
  /// sub-harmonic block of ∂r/∂x is singular), N, and the scan step, N. At H = 7 on the paper's
  /// model the two are 0.046 N apart (docs/hbm.md); 0 switches at the flip point itself.
  double pitchfork_search_n = 0.2;
  double pitchfork_scan_step_n = 0.005;
  int max_corrector_iterations = 30;
  /// ‖r‖₂ at which the corrected first point is accepted, N.
  double residual_tolerance_n = 1e-10;

  /// Throws InputError naming the option when the options make no sense.
  void validate() const;
};

/// The period-doubled branch and how it was reached.
struct PeriodDoublingSwitch {
  JobStatus status = JobStatus::Ok;
  std::string message;          // why, whenever status != Ok
  double f0_flip_n = 0.0;       // the Floquet flip of the period-νT branch (the input point)
  double f0_pitchfork_n = 0.0;  // where the HBM period-2νT branch meets the period-νT one
  int subharmonic = 2;          // ν of the new branch (twice the flip point's)
  Eigen::VectorXd embedded;     // the flip orbit in the 2ν ansatz (odd harmonics zero)
  Eigen::VectorXd critical_direction;  // unit null vector of the odd block of ∂r/∂x
  /// Smallest and largest singular values of the odd block of ∂r/∂x at the flip, N/m: their
  /// ratio says how singular the block is (0 at an exact flip).
  double odd_block_sigma_min_n_m = 0.0;
  double odd_block_sigma_max_n_m = 0.0;
  double perturbation_m = 0.0;  // ε used
  int corrector_iterations = 0;
  /// Points in continuation order: the flip orbit first (marker BranchPoint, it is where the
  /// period-2νT branch meets the period-νT one), then the corrected predictor and the
  /// continuation from it. Floquet multipliers (with stability) are those of Φ(2νT).
  Branch branch;
};

/// Branch switching at a period doubling (Seydel 2010, "Practical bifurcation and stability
/// analysis", §5.6; Doedel et al. 1991, "Numerical analysis and control of bifurcation problems
/// (II)"). At a flip of a period-νT orbit x_p (a Floquet multiplier μ = −1) a period-2νT orbit
/// bifurcates. In the 2ν ansatz the νT-periodic orbit has zero odd (sub-harmonic) coefficients and,
/// because K(t), C(t) are νT-periodic, ∂r/∂x splits into an even block and an odd block J_o. The
/// harmonic-balance period-2νT branch leaves the period-νT one where J_o is singular (a pitchfork
/// of the 2ν balance; its two halves are the same orbit shifted by νT), along v = null(J_o), the
/// truncated image of the Floquet mode of μ = −1.
///
///   1. x_p(f0): Newton in the ν ansatz from the flip point; f0_p: where sign(det J_o) σ_min(J_o)
///      changes sign, scanned outwards from the Floquet flip and refined by regula falsi. J_o is a
///      truncated Hill matrix, so f0_p matches the Floquet flip only as H grows (paper model,
///      9 Hz: 3.3853 N against 3.4314 N at H = 7, 3.4346 against 3.4295 at H = 21).
///   2. v      = right singular vector of J_o(x_p, f0_p) for its smallest singular value, ‖v‖ = 1
///   3. y_pred = (x_p + ε v, f0_p)
///      Newton on  r(x, f0) = 0,  vᵀ(x − x_pred) = 0    (pseudo-arclength corrector along (v, 0))
///      The constraint fixes the sub-harmonic content at ε, so the corrector cannot fall back on
///      the period-νT branch (on which vᵀ(x − x_p) = 0); f0 is free and lands at f0_p + O(ε²).
///   4. continue_branch from there, in the direction in which the sub-harmonic content grows
///      (the sign of the f0 component of the tangent with vᵀ t_x = 1).
///
/// `flip` is the located PeriodDoubling point of a branch computed with
/// options.continuation.hbm. Progress and cancellation are those of the continuation. Throws
/// InputError for bad options or a flip point whose size does not match the ansatz; a failed
/// search or corrector is the status and message.
PeriodDoublingSwitch switch_at_period_doubling(const Model& model, const BranchPoint& flip,
                                               const PeriodDoublingSwitchOptions& options,
                                               const ProgressFn& progress = {},
                                               const CancelToken& cancel = {});

/// The period-doubling cascade after `branch` (`hbm --follow-period-doubling`, the app and the
/// Python module): a switch at the first period doubling of `branch`, then once more at the first
/// one of the new branch, up to the period-4T branch. Each new branch is continued with
/// `options` (its f0 range, frequency, well, steps) to at most 2000 points: a truncated balance
/// can make a period-4T branch wind back and forth (docs/hbm.md). The switches are returned in
/// order, each with its status: one that found no branch (status not Ok, no points) ends the
/// cascade. Empty when `branch` has no period doubling.
std::vector<PeriodDoublingSwitch> follow_period_doublings(const Model& model, const Branch& branch,
                                                          const ContinuationOptions& options,
                                                          const ProgressFn& progress = {},
                                                          const CancelToken& cancel = {});

/// The coefficients of a ν-ansatz orbit in the 2ν ansatz: base harmonic k becomes 2k, the odd
/// ones are zero. Same orbit, described over twice its period.
Eigen::VectorXd embed_in_doubled_ansatz(const Eigen::VectorXd& coefficients);

/// Sub-harmonic amplitude of an orbit in a ν ≥ 2 ansatz: √(Σ_{k odd} a_k² + b_k²), m; it vanishes
/// on an orbit of period νT/2 and measures how far a period-doubled orbit is from it.
double odd_harmonic_norm_m(const Eigen::VectorXd& coefficients);

}  // namespace oscilab::analysis
