#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/hbm/floquet.h"
#include "analysis/hbm/harmonic_balance.h"

namespace oscilab::analysis {

/// The continuation parameter of a branch.
enum class BranchParameter { ForcingAmplitude, Frequency };

/// Why a point is on the branch besides being a continuation step.
enum class PointMarker {
  None,            // an accepted predictor–corrector step
  Start,           // the first point, at the start value
  End,             // the last point, landed exactly at the end value
  Landing,         // landed exactly on a requested parameter value
  Fold,            // located limit point: the parameter turns (a multiplier through +1)
  PeriodDoubling,  // located flip: a multiplier through −1
  BranchPoint,     // a multiplier through +1 without a fold (symmetry breaking, e.g. at a flip
                   // seen with a sub-harmonic ansatz)
};
const char* marker_name(PointMarker marker);

/// One point of a branch. f0_n and freq_hz are both stored whatever the parameter.
struct BranchPoint {
  double f0_n = 0.0;
  double freq_hz = 0.0;
  Eigen::VectorXd coefficients;  // [a0, a1, b1, …] of HarmonicBalance
  HbmMeasures measures;
  bool stability_known = false;
  FloquetResult floquet;  // valid when stability_known
  PointMarker marker = PointMarker::None;
  int newton_iterations = 0;
  double residual_norm_n = 0.0;
  double arclength = 0.0;          // scaled arc length from the start
  double tangent_parameter = 0.0;  // parameter component of the unit (scaled) tangent
};

/// A fold or bifurcation found on the branch; point_index refers to Branch::points.
struct BranchEvent {
  PointMarker kind = PointMarker::Fold;
  double f0_n = 0.0;
  double freq_hz = 0.0;
  double amp_m = 0.0;
  std::size_t point_index = 0;
};

/// The result of a continuation: points in continuation order, folds and bifurcations marked,
/// and how the run ended.
struct Branch {
  JobStatus status = JobStatus::Ok;
  std::string message;  // why, whenever status != Ok
  BranchParameter parameter = BranchParameter::ForcingAmplitude;
  HbmOptions hbm;
  int samples = 0;  // N actually used
  bool positive_well = true;
  std::vector<BranchPoint> points;
  std::vector<BranchEvent> events;
  int steps_accepted = 0;
  int steps_rejected = 0;
  int newton_iterations = 0;

  std::vector<BranchEvent> events_of(PointMarker kind) const;
};

/// Branch CSV of docs/contracts.md §3: `f0_n,amp_m,z1_abs_m,phase_rad,edc_j,stable` in
/// continuation order, then extra columns: `freq_hz,edc_dissipation_j,mu1_abs,mu2_abs,mu1_re,
/// mu1_im,mu2_re,mu2_im,marker,newton_iterations`. z1 is the complex amplitude of e^{iωt} and
/// phase_rad its argument (docs/conventions.md); `stable` is 1 or 0 (0 also when stability was
/// not computed, in which case the multiplier columns are empty).
void write_branch_csv(const Branch& branch, std::ostream& out);
/// Throws InputError naming the file when it cannot be written.
void write_branch_csv(const Branch& branch, const std::string& path);

}  // namespace oscilab::analysis
