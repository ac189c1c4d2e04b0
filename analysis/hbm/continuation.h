#pragma once

#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/hbm/branch.h"
#include "analysis/hbm/floquet.h"
#include "analysis/hbm/harmonic_balance.h"
#include "analysis/model/model.h"

namespace oscilab::analysis {

/// Options of a pseudo-arclength continuation of harmonic-balance solutions.
struct ContinuationOptions {
  BranchParameter parameter = BranchParameter::ForcingAmplitude;
  double start = 0.0;  // f0 in N (amplitude continuation) or frequency in Hz
  double end = 1.0;
  double freq_hz = 9.0;       // the fixed frequency of an amplitude continuation
  double f0_n = 1.0;          // the fixed amplitude of a frequency continuation
  bool positive_well = true;  // the stable equilibrium z₊* (or z₋*) the branch grows from
  HbmOptions hbm;
  /// Start from these coefficients instead of the well's linear response (e.g. a branch switch).
  Eigen::VectorXd initial_coefficients;

  /// Step control in scaled arc length (unknowns x/z_ref, parameter p/p_ref; see docs/hbm.md).
  /// Small steps cost time, large ones risk a corrector that lands on another part of the branch;
  /// the turning-angle limit below is what keeps folds resolved.
  double initial_step = 0.02;
  double min_step = 1e-7;
  double max_step = 0.1;
  int max_corrector_iterations = 8;
  /// Steps grow when the corrector needs fewer iterations than this and shrink when it needs more.
  int target_iterations = 3;
  /// Largest angle between successive unit tangents, rad; a step turning more is retried shorter.
  double max_turn_rad = 0.3;
  /// Corrector convergence: ‖r‖₂ ≤ tolerance × force scale (f0 range, or f0).
  double residual_tolerance = 1e-11;
  int max_points = 20000;

  bool stability = true;  // Floquet multipliers of every point
  FloquetOptions floquet;
  /// Locate folds (and, with stability, period doublings and branch points) to full precision
  /// and insert them as points.
  bool locate_events = true;
  /// Parameter values at which to land exactly (every crossing), e.g. the measured levels.
  std::vector<double> landing;
  /// Stop when the branch turns back past the start value (a branch from rest that does so has
  /// left the range for good). A branch switched onto near a pitchfork may dip below its first
  /// point before it bends away: branch_switching.h turns this off (the run then stops only once
  /// it is further behind the start than the length of the range, or than turn_back_limit).
  bool stop_when_turning_back = true;
  /// With stop_when_turning_back off: how far behind the start the branch may turn back before
  /// the run stops, in the parameter's unit; 0 (the default) means the length of the range. A
  /// branch resumed at a level part-way up may fold back far below it before it rises to the
  /// levels above (a softening well's jump up: the second fold can lie near rest), so
  /// level_response lets it go back as far as f0 = 0.
  double turn_back_limit = 0.0;
  /// z_ref, m; 0: force scale / well stiffness (the static deflection under the largest force).
  double displacement_scale_m = 0.0;

  /// Throws InputError naming the option when the options make no sense.
  void validate() const;
};

/// Follows the periodic response of `model` from `start` to `end` of the parameter by
/// pseudo-arclength continuation (Keller 1977, "Numerical solution of bifurcation and nonlinear
/// eigenvalue problems"): tangent predictor, corrector orthogonal to the tangent, step control
/// by corrector iterations and turning angle. Folds are followed, not jumped. Throws InputError
/// for bad options or a model harmonic balance cannot handle; numerical outcomes are the
/// branch's status and message. Progress is the fraction of the parameter range covered;
/// cancellation is polled every step.
Branch continue_branch(const Model& model, const ContinuationOptions& options,
                       const ProgressFn& progress = {}, const CancelToken& cancel = {});

}  // namespace oscilab::analysis
