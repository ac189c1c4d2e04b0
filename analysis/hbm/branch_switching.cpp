#include "analysis/hbm/branch_switching.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "analysis/common/input_error.h"
#include "analysis/hbm/regula_falsi.h"

namespace oscilab::analysis {

void PeriodDoublingSwitchOptions::validate() const {
  if (!(perturbation_m >= 0.0) || !std::isfinite(perturbation_m)) {
    throw InputError("period-doubling switch: perturbation_m: " + std::to_string(perturbation_m) +
                     " must be finite and >= 0");
  }
  if (!(pitchfork_search_n >= 0.0) || !(pitchfork_scan_step_n > 0.0)) {
    throw InputError(
        "period-doubling switch: pitchfork_search_n must be >= 0 and "
        "pitchfork_scan_step_n > 0");
  }
  if (max_corrector_iterations < 1) {
    throw InputError("period-doubling switch: max_corrector_iterations must be >= 1");
  }
  if (!(residual_tolerance_n > 0.0)) {
    throw InputError("period-doubling switch: residual_tolerance_n must be positive");
  }
  continuation.validate();
}

Eigen::VectorXd embed_in_doubled_ansatz(const Eigen::VectorXd& coefficients) {
  const Eigen::Index harmonics = (coefficients.size() - 1) / 2;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(4 * harmonics + 1);
  out[0] = coefficients[0];
  for (Eigen::Index k = 1; k <= harmonics; ++k) {
    out[2 * (2 * k) - 1] = coefficients[2 * k - 1];  // a_k → a_2k
    out[2 * (2 * k)] = coefficients[2 * k];          // b_k → b_2k
  }
  return out;
}

double odd_harmonic_norm_m(const Eigen::VectorXd& coefficients) {
  double sum = 0.0;
  for (Eigen::Index k = 1; 2 * k < coefficients.size(); k += 2) {
    sum += coefficients[2 * k - 1] * coefficients[2 * k - 1] +
           coefficients[2 * k] * coefficients[2 * k];
  }
  return std::sqrt(sum);
}

namespace {

// The period-2νT ansatz's harmonic balance at the switch, with its residual and Jacobian buffers
// and the odd (sub-harmonic) block of that Jacobian: the harmonics the period-νT orbit lacks.
class DoubledAnsatz {
 public:
  DoubledAnsatz(const Model& model, double freq_hz, const HbmOptions& doubled)
      : hbm(model, freq_hz, doubled), n(hbm.size()), r(n), jacobian(n, n) {
    for (int k = 1; k <= hbm.base_harmonics(); k += 2) {
      odd.push_back(2 * k - 1);
      odd.push_back(2 * k);
    }
    n_odd = static_cast<int>(odd.size());
    odd_block.resize(n_odd, n_odd);
  }

  void fill_odd_block(const Eigen::VectorXd& x_embedded, double f0_n) {
    hbm.residual_and_jacobian(x_embedded, f0_n, r, jacobian);
    for (int i = 0; i < n_odd; ++i) {
      for (int j = 0; j < n_odd; ++j) odd_block(i, j) = jacobian(odd[i], odd[j]);
    }
  }

  // Signed smallest singular value of the odd block, sign(det J_o) σ_min: continuous along the
  // period-νT branch and zero exactly where J_o is singular (det itself would overflow at H = 21).
  double singularity_test(const Eigen::VectorXd& x_embedded, double f0_n) {
    fill_odd_block(x_embedded, f0_n);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(odd_block);
    double sign = lu.permutationP().determinant();
    for (int i = 0; i < n_odd; ++i) sign *= lu.matrixLU()(i, i) < 0.0 ? -1.0 : 1.0;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(odd_block);
    return sign * svd.singularValues()[n_odd - 1];
  }

  HarmonicBalance hbm;
  int n;
  Eigen::VectorXd r;
  Eigen::MatrixXd jacobian;
  std::vector<int> odd;
  int n_odd = 0;
  Eigen::MatrixXd odd_block;
};

// The harmonic-balance pitchfork: where J_o of the period-νT orbit is singular. The Floquet
// flip (monodromy of the HBM orbit) and the singularity of the truncated Hill matrix J_o agree
// only as H grows (docs/hbm.md, "Period-2 branch"), so the switch happens at the latter, found
// by scanning the period-νT branch from the flip outwards within (low, high) and refining by
// regula falsi. Sets out.f0_pitchfork_n and `x_source` (the period-νT orbit there); false when
// no sign change was bracketed.
bool locate_pitchfork(DoubledAnsatz& ansatz, HarmonicBalance& source_hbm, const BranchPoint& flip,
                      const PeriodDoublingSwitchOptions& options, double low, double high,
                      PeriodDoublingSwitch& out, Eigen::VectorXd& x_source) {
  out.f0_pitchfork_n = flip.f0_n;
  x_source = flip.coefficients;
  NewtonOptions newton;
  newton.residual_tolerance_n = options.residual_tolerance_n;
  const double g_flip = ansatz.singularity_test(embed_in_doubled_ansatz(x_source), flip.f0_n);
  bool bracketed = g_flip == 0.0;
  if (bracketed || !(options.pitchfork_search_n > 0.0)) return bracketed;
  for (double side : {-1.0, 1.0}) {
    Eigen::VectorXd x_b = flip.coefficients;
    double a = flip.f0_n, g_a = g_flip;
    for (double b = flip.f0_n + side * options.pitchfork_scan_step_n;
         std::abs(b - flip.f0_n) <= options.pitchfork_search_n && b > low && b < high && !bracketed;
         b += side * options.pitchfork_scan_step_n) {
      if (!source_hbm.solve(x_b, b, newton).converged()) break;
      const double g_b = ansatz.singularity_test(embed_in_doubled_ansatz(x_b), b);
      if ((g_b > 0.0) != (g_a > 0.0)) {
        Eigen::VectorXd x_c = x_b;  // each solve starts from the last one's orbit
        illinois_regula_falsi(a, g_a, b, g_b, 1e-12, [&](double c) -> std::optional<double> {
          if (!source_hbm.solve(x_c, c, newton).converged()) return std::nullopt;
          out.f0_pitchfork_n = c;
          x_source = x_c;
          return ansatz.singularity_test(embed_in_doubled_ansatz(x_c), c);
        });
        bracketed = true;
      }
      a = b;
      g_a = g_b;
    }
    if (bracketed) break;
  }
  return bracketed;
}

// The critical (null) direction v of the odd block at the pitchfork (out.critical_direction, and
// the block's extreme singular values), then the predictor x_p + ε v and the corrector: Newton on
// [r(x, f0); vᵀ(x − x_pred)] = 0 with the bordered Jacobian [∂r/∂x, ∂r/∂f0; vᵀ, 0], left in
// `bordered` with `dr_df0`. Returns whether it converged; (x, f0) is the corrected point.
bool correct_onto_doubled_branch(DoubledAnsatz& ansatz, const BranchPoint& flip,
                                 const PeriodDoublingSwitchOptions& options,
                                 PeriodDoublingSwitch& out, Eigen::VectorXd& x, double& f0,
                                 Eigen::MatrixXd& bordered, Eigen::VectorXd& dr_df0) {
  const int n = ansatz.n, n_odd = ansatz.n_odd;
  ansatz.fill_odd_block(out.embedded, out.f0_pitchfork_n);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(ansatz.odd_block, Eigen::ComputeFullV);
  out.odd_block_sigma_max_n_m = svd.singularValues()[0];
  out.odd_block_sigma_min_n_m = svd.singularValues()[n_odd - 1];
  out.critical_direction = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n_odd; ++i) {
    out.critical_direction[ansatz.odd[i]] = svd.matrixV()(i, n_odd - 1);
  }

  out.perturbation_m =
      options.perturbation_m > 0.0 ? options.perturbation_m : 0.02 * flip.measures.amp_m;
  const Eigen::VectorXd x_pred = out.embedded + out.perturbation_m * out.critical_direction;
  x = x_pred;
  f0 = out.f0_pitchfork_n;
  dr_df0.resize(n);
  ansatz.hbm.d_residual_d_f0(dr_df0);
  bordered = Eigen::MatrixXd::Zero(n + 1, n + 1);
  Eigen::VectorXd rhs(n + 1);
  for (out.corrector_iterations = 0;; ++out.corrector_iterations) {
    ansatz.hbm.residual_and_jacobian(x, f0, ansatz.r, ansatz.jacobian);
    const double constraint = out.critical_direction.dot(x - x_pred);
    if (!ansatz.r.allFinite()) return false;
    if (ansatz.r.norm() <= options.residual_tolerance_n && std::abs(constraint) <= 1e-12) {
      return true;
    }
    if (out.corrector_iterations >= options.max_corrector_iterations) return false;
    bordered.topLeftCorner(n, n) = ansatz.jacobian;
    bordered.topRightCorner(n, 1) = dr_df0;
    bordered.bottomLeftCorner(1, n) = out.critical_direction.transpose();
    rhs.head(n) = -ansatz.r;
    rhs[n] = -constraint;
    const Eigen::VectorXd delta = bordered.partialPivLu().solve(rhs);
    if (!delta.allFinite()) return false;
    x += delta.head(n);
    f0 += delta[n];
  }
}

// The flip orbit itself heads the continued branch, marked as the branch point.
void head_with_flip_orbit(DoubledAnsatz& ansatz, const PeriodDoublingSwitchOptions& options,
                          PeriodDoublingSwitch& out) {
  BranchPoint head;
  head.f0_n = out.f0_pitchfork_n;
  head.freq_hz = options.continuation.freq_hz;
  head.coefficients = out.embedded;
  head.measures = ansatz.hbm.measure(out.embedded, out.f0_pitchfork_n);
  if (options.continuation.stability) {
    head.floquet = FloquetAnalysis(options.continuation.floquet).analyse(ansatz.hbm, out.embedded);
    head.stability_known = true;
  }
  head.marker = PointMarker::BranchPoint;
  ansatz.hbm.residual(out.embedded, out.f0_pitchfork_n, ansatz.r);
  head.residual_norm_n = ansatz.r.norm();
  if (!out.branch.points.empty()) {
    out.branch.points.front().marker = PointMarker::None;
    head.tangent_parameter = 0.0;  // the new branch leaves the flip along (v, 0)
  }
  out.branch.points.insert(out.branch.points.begin(), std::move(head));
  for (BranchEvent& event : out.branch.events) ++event.point_index;
  out.branch.events.insert(
      out.branch.events.begin(),
      {PointMarker::BranchPoint, out.f0_pitchfork_n, options.continuation.freq_hz,
       out.branch.points.front().measures.amp_m, 0});
}

}  // namespace

PeriodDoublingSwitch switch_at_period_doubling(const Model& model, const BranchPoint& flip,
                                               const PeriodDoublingSwitchOptions& options,
                                               const ProgressFn& progress,
                                               const CancelToken& cancel) {
  options.validate();
  const HbmOptions& source = options.continuation.hbm;
  if (flip.coefficients.size() != 2 * source.harmonics * source.subharmonic + 1) {
    throw InputError(
        "period-doubling switch: the flip point has " + std::to_string(flip.coefficients.size()) +
        " coefficients, not those of the ansatz H = " + std::to_string(source.harmonics) +
        ", nu = " + std::to_string(source.subharmonic));
  }
  PeriodDoublingSwitch out;
  out.f0_flip_n = flip.f0_n;
  out.subharmonic = 2 * source.subharmonic;
  HbmOptions doubled = source;
  doubled.subharmonic = out.subharmonic;
  doubled.samples = source.samples > 0 ? 2 * source.samples : 0;
  DoubledAnsatz ansatz(model, options.continuation.freq_hz, doubled);
  HarmonicBalance source_hbm(model, options.continuation.freq_hz, source);

  const double low = std::min(options.continuation.start, options.continuation.end);
  const double high = std::max(options.continuation.start, options.continuation.end);
  Eigen::VectorXd x_source;
  if (!locate_pitchfork(ansatz, source_hbm, flip, options, low, high, out, x_source)) {
    out.status = JobStatus::NoConvergence;
    out.message =
        "period-doubling switch: the harmonic-balance Jacobian's sub-harmonic block is "
        "not singular within " +
        std::to_string(options.pitchfork_search_n) + " N of the flip at " +
        std::to_string(flip.f0_n) + " N";
    return out;
  }
  out.embedded = embed_in_doubled_ansatz(x_source);

  Eigen::VectorXd x, dr_df0;
  double f0 = 0.0;
  Eigen::MatrixXd bordered;
  const bool converged =
      correct_onto_doubled_branch(ansatz, flip, options, out, x, f0, bordered, dr_df0);
  out.branch.parameter = BranchParameter::ForcingAmplitude;
  out.branch.hbm = doubled;
  out.branch.samples = ansatz.hbm.samples();
  out.branch.positive_well = options.continuation.positive_well;
  if (!converged) {
    out.status = JobStatus::NoConvergence;
    out.message = "period-doubling switch at " + std::to_string(flip.f0_n) +
                  " N: the corrector did not converge from x + eps v (eps = " +
                  std::to_string(out.perturbation_m) +
                  " m, |r| = " + std::to_string(ansatz.r.norm()) + " N after " +
                  std::to_string(out.corrector_iterations) + " iterations)";
    return out;
  }

  // Continue from the corrected point away from the pitchfork: along the tangent t whose
  // sub-harmonic component grows, [∂r/∂x, ∂r/∂f0; vᵀ, 0] t = [0; 1]; the sign of its f0 component
  // says which end of the range the branch bends to (up for a supercritical flip).
  const int n = ansatz.n;
  bordered.topLeftCorner(n, n) = ansatz.jacobian;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  rhs[n] = 1.0;
  const Eigen::VectorXd tangent = bordered.partialPivLu().solve(rhs);
  ContinuationOptions continuation = options.continuation;
  continuation.hbm = doubled;
  continuation.start = f0;
  continuation.end = tangent[n] > 0.0 ? high : low;
  continuation.initial_coefficients = x;
  continuation.stop_when_turning_back = false;
  if (!(f0 > low && f0 < high)) {
    out.status = JobStatus::NoConvergence;
    out.message = "period-doubling switch: the corrected point (f0 = " + std::to_string(f0) +
                  " N) is outside the f0 range";
    return out;
  }
  out.branch = continue_branch(model, continuation, progress, cancel);
  head_with_flip_orbit(ansatz, options, out);
  out.branch.newton_iterations += out.corrector_iterations;
  out.status = out.branch.status;
  out.message = out.branch.message;
  return out;
}

std::vector<PeriodDoublingSwitch> follow_period_doublings(const Model& model, const Branch& branch,
                                                          const ContinuationOptions& options,
                                                          const ProgressFn& progress,
                                                          const CancelToken& cancel) {
  constexpr int kMaxSubharmonic = 4;  // period 4T at most
  constexpr int kMaxPoints = 2000;
  std::vector<PeriodDoublingSwitch> out;
  out.reserve(kMaxSubharmonic);  // `from` points into `out`: no reallocation
  const Branch* from = &branch;
  for (;;) {
    const auto flips = from->events_of(PointMarker::PeriodDoubling);
    if (flips.empty() || cancel.cancelled()) break;
    PeriodDoublingSwitchOptions switching;
    switching.continuation = options;
    switching.continuation.hbm = from->hbm;
    switching.continuation.max_points = kMaxPoints;
    out.push_back(switch_at_period_doubling(model, from->points[flips.front().point_index],
                                            switching, progress, cancel));
    const PeriodDoublingSwitch& doubled = out.back();
    const bool followed = doubled.status == JobStatus::Ok || !doubled.branch.points.empty();
    if (!followed || doubled.subharmonic >= kMaxSubharmonic) break;
    from = &out.back().branch;
  }
  return out;
}

}  // namespace oscilab::analysis
