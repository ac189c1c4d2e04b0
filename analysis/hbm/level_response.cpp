#include "analysis/hbm/level_response.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include <Eigen/LU>

#include "analysis/common/input_error.h"
#include "analysis/hbm/continuation.h"
#include "analysis/hbm/hysteresis_march.h"

namespace oscilab::analysis {

namespace {

LevelResponse responses_at(const Model& model, double freq_hz, bool positive_well,
                           const std::vector<double>& levels_n, const HbmOptions& hbm_options) {
  LevelResponse out;
  out.harmonics = hbm_options.harmonics;
  if (levels_n.empty()) return out;
  HarmonicBalance hbm(model, freq_hz, hbm_options);
  const double z_star = model.well(positive_well).z_m;

  // Natural continuation from rest: the equilibrium is the exact solution at f0 = 0. A level
  // whose Newton solve fails from the extrapolated guess is approached again in halved steps
  // (up to kMaxHalvings times) before the whole set falls back to arclength continuation: sharp
  // friction (small v_t) bends the branch between levels without any fold, and a few
  // intermediate solves are far cheaper than a continuation from rest.
  constexpr int kMaxHalvings = 4;
  Eigen::VectorXd previous = hbm.linear_guess(z_star, 0.0), before_previous;
  double previous_f0 = 0.0, before_previous_f0 = 0.0;
  int sign = 0;
  bool fast = true;
  const auto predict = [&](double f0) -> Eigen::VectorXd {
    if (before_previous.size() == 0) {
      Eigen::VectorXd x = hbm.linear_guess(z_star, f0);
      if (previous_f0 > 0.0) x = previous + (x - hbm.linear_guess(z_star, previous_f0));
      return x;
    }
    return previous +
           (previous - before_previous) * ((f0 - previous_f0) / (previous_f0 - before_previous_f0));
  };
  // Newton at f0 from the prediction; on success the point becomes the newest of the two that
  // the next prediction extrapolates from.
  const auto step_to = [&](double f0, Eigen::VectorXd& x) {
    x = predict(f0);
    const NewtonReport report = hbm.solve(x, f0);
    out.newton_iterations += report.iterations;
    if (!report.converged() || (sign != 0 && report.jacobian_sign != sign)) return false;
    sign = report.jacobian_sign;
    before_previous = previous;
    before_previous_f0 = previous_f0;
    previous = x;
    previous_f0 = f0;
    return true;
  };
  for (double f0 : levels_n) {
    Eigen::VectorXd x;
    bool reached = step_to(f0, x);
    for (int halvings = 1; !reached && halvings <= kMaxHalvings; ++halvings) {
      // A failed solve leaves previous untouched: retry from it in 2^halvings equal steps.
      const double from = previous_f0;
      const int steps = 1 << halvings;
      reached = true;
      for (int i = 1; i <= steps && reached; ++i) {
        reached = step_to(from + (f0 - from) * i / steps, x);
      }
      if (!reached && sign != 0 && previous_f0 > from) break;  // crossed a fold on the way
    }
    if (!reached) {
      fast = false;
      break;
    }
    const HbmMeasures measures = hbm.measure(x, f0);
    out.f0_n.push_back(f0);
    out.edc_j.push_back(measures.edc_j);
    out.amp_m.push_back(measures.amp_m);
    out.coefficients.push_back(x);
  }
  if (fast) return out;

  // A fold lies ahead (the Jacobian's sign flipped) or Newton failed even in small steps:
  // follow the branch by pseudo-arclength continuation from the last level reached (from rest
  // when none was), landing at the remaining levels and taking each one's first crossing. The
  // levels solved so far stand: natural continuation reached them with one Jacobian sign, so the
  // branch up to there has no fold and rises monotonically in f0.
  out.used_arclength = true;
  const std::size_t solved = out.f0_n.size();
  ContinuationOptions options;
  options.freq_hz = freq_hz;
  options.positive_well = positive_well;
  options.hbm = hbm_options;
  options.start = solved > 0 ? out.f0_n.back() : 0.0;
  if (solved > 0) {
    options.initial_coefficients = out.coefficients.back();
    // Past a fold the branch may turn back below the level it started from before it rises
    // again, as far as rest (the second fold of a softening well's jump can lie near f0 = 0);
    // only a return past rest ends it.
    options.stop_when_turning_back = false;
    options.turn_back_limit = options.start;
  }
  options.end = levels_n.back();
  options.stability = false;
  options.locate_events = false;
  options.landing.assign(levels_n.begin() + static_cast<std::ptrdiff_t>(solved), levels_n.end());
  const Branch branch = continue_branch(model, options);
  out.newton_iterations += branch.newton_iterations;
  std::size_t next = solved;
  for (const BranchPoint& point : branch.points) {
    if (next < levels_n.size() &&
        std::abs(point.f0_n - levels_n[next]) <= 1e-12 * levels_n.back() &&
        (point.marker == PointMarker::Landing || point.marker == PointMarker::End ||
         point.marker == PointMarker::Start)) {
      out.f0_n.push_back(point.f0_n);
      out.edc_j.push_back(point.measures.edc_j);
      out.amp_m.push_back(point.measures.amp_m);
      out.coefficients.push_back(point.coefficients);
      ++next;
    }
  }
  if (next < levels_n.size()) {
    out.status = branch.status == JobStatus::Ok ? JobStatus::NoConvergence : branch.status;
    out.message = "continuation reached " + std::to_string(next) + " of " +
                  std::to_string(levels_n.size()) + " levels" +
                  (branch.message.empty() ? "" : ": " + branch.message);
  }
  return out;
}

// |Z1| of a solution: the amplitude of the forcing harmonic.
double z1_abs(const HarmonicBalance& hbm, const Eigen::VectorXd& x) {
  return std::hypot(x[hbm.forcing_cos_index()], x[hbm.forcing_sin_index()]);
}

// Where the swept responses are off the measured |Z1| by more than kBranchMismatch, follows the
// top level's branch down by natural continuation (linear extrapolation from the last two
// solutions, as the sweep up does) and takes its solution at each such level when it is another
// branch (|Z1| apart by more than kBranchMismatch) closer to the measurement. Stops at the first
// level where Newton fails or the Jacobian's sign flips (the branch's fold: below it the branch is
// unstable or gone).
void prefer_measured_branch(const Model& model, double freq_hz, const HbmOptions& hbm_options,
                            const std::vector<double>& measured, LevelResponse& out) {
  const std::size_t n = out.coefficients.size();
  // Only a sweep that crossed a fold (it handed over to arclength continuation) has levels with
  // a second stable response below it; elsewhere the branch followed down is the swept one.
  if (out.status != JobStatus::Ok || !out.used_arclength || measured.size() != n || n < 2) return;
  HarmonicBalance hbm(model, freq_hz, hbm_options);
  const auto off = [&](const Eigen::VectorXd& x, std::size_t k) {
    return std::abs(z1_abs(hbm, x) - measured[k]);
  };
  std::size_t lowest = n;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (measured[k] > 0.0 && off(out.coefficients[k], k) > kBranchMismatch * measured[k]) {
      lowest = k;
      break;
    }
  }
  if (lowest == n) return;
  Eigen::VectorXd previous = out.coefficients[n - 1], before_previous;
  double previous_f0 = out.f0_n[n - 1], before_previous_f0 = 0.0;
  // The branch's side of its fold: the Jacobian's sign at the top level (already converged, so
  // Newton only reports it).
  Eigen::VectorXd top = previous;
  const int sign = hbm.solve(top, previous_f0).jacobian_sign;
  for (std::size_t k = n - 1; k-- > lowest;) {
    const double f0 = out.f0_n[k];
    Eigen::VectorXd x = before_previous.size() == 0
                            ? Eigen::VectorXd(previous * (f0 / previous_f0))
                            : Eigen::VectorXd(previous + (previous - before_previous) *
                                                             ((f0 - previous_f0) /
                                                              (previous_f0 - before_previous_f0)));
    if (before_previous.size() == 0) x[0] = previous[0];  // the mean stays; the motion scales
    const NewtonReport report = hbm.solve(x, f0);
    out.newton_iterations += report.iterations;
    if (!report.converged() || report.jacobian_sign != sign) return;
    const double swept_z1 = z1_abs(hbm, out.coefficients[k]);
    const bool other_branch = std::abs(z1_abs(hbm, x) - swept_z1) > kBranchMismatch * swept_z1;
    if (other_branch && measured[k] > 0.0 &&
        off(out.coefficients[k], k) > kBranchMismatch * measured[k] &&
        off(x, k) < off(out.coefficients[k], k)) {
      const HbmMeasures measures = hbm.measure(x, f0);
      out.edc_j[k] = measures.edc_j;
      out.amp_m[k] = measures.amp_m;
      out.coefficients[k] = x;
      ++out.branch_switched;
    }
    before_previous = previous;
    before_previous_f0 = previous_f0;
    previous = x;
    previous_f0 = f0;
  }
}

}  // namespace

int contact_resolving_harmonics(const Model& model, double freq_hz, bool positive_well) {
  const double stiffness = small_loop_stiffness_n_m(model, model.well(positive_well).z_m);
  if (!(stiffness > 0.0)) return 0;
  const double ring = std::sqrt(stiffness / model.mass_kg()) / (2.0 * std::numbers::pi * freq_hz);
  return static_cast<int>(std::ceil(1.5 * ring));
}

LevelResponse level_response(const Model& model, double freq_hz, bool positive_well,
                             const std::vector<double>& levels_n, const HbmOptions& hbm_options,
                             const std::vector<double>& measured_z1_abs_m) {
  for (std::size_t i = 0; i < levels_n.size(); ++i) {
    if (!(levels_n[i] >= 0.0) || (i > 0 && !(levels_n[i] > levels_n[i - 1]))) {
      throw InputError("level response: levels must be non-negative and increasing");
    }
  }
  // A stuck contact rings on its presliding stiffness; below the ringing's harmonic the truncated
  // balance has no solution near the stick–slip transition, or a wrong one (the EDC off by 10–26 %
  // there at δ = 1 µm with H = 7): every level is solved with the ringing resolved (at most
  // kMaxContactHarmonics), so that the model side stays one smooth function of θ.
  const int contact =
      std::min(kMaxContactHarmonics, contact_resolving_harmonics(model, freq_hz, positive_well));
  HbmOptions resolved = hbm_options;
  if (contact > hbm_options.harmonics) {
    resolved.harmonics = contact;
    resolved.samples = 0;
  }
  LevelResponse out = responses_at(model, freq_hz, positive_well, levels_n, resolved);
  if (!measured_z1_abs_m.empty()) {
    if (measured_z1_abs_m.size() != levels_n.size()) {
      throw InputError("level response: " + std::to_string(measured_z1_abs_m.size()) +
                       " measured amplitudes for " + std::to_string(levels_n.size()) + " levels");
    }
    prefer_measured_branch(model, freq_hz, resolved, measured_z1_abs_m, out);
  }
  return out;
}

std::vector<LevelResponse> nearby_level_responses(const Model& model,
                                                  const std::vector<Model>& nearby, double freq_hz,
                                                  const LevelResponse& base,
                                                  const HbmOptions& hbm_options) {
  // The options level_response solved base with: H raised for a ringing contact, N by default.
  HbmOptions options = hbm_options;
  if (base.harmonics != options.harmonics) {
    options.harmonics = base.harmonics;
    options.samples = 0;
  }
  HarmonicBalance at_base(model, freq_hz, options);
  std::vector<std::unique_ptr<HarmonicBalance>> balances;
  std::vector<LevelResponse> out(nearby.size());
  for (std::size_t j = 0; j < nearby.size(); ++j) {
    balances.push_back(std::make_unique<HarmonicBalance>(nearby[j], freq_hz, options));
    out[j].harmonics = base.harmonics;
    out[j].status = base.status;
    out[j].message = base.message;
  }
  Eigen::VectorXd r, r_nearby, x_nearby;
  Eigen::MatrixXd jacobian;
  for (std::size_t k = 0; k < base.coefficients.size() && k < base.f0_n.size(); ++k) {
    const Eigen::VectorXd& x = base.coefficients[k];
    const double f0 = base.f0_n[k];
    at_base.residual_and_jacobian(x, f0, r, jacobian);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(jacobian);
    for (std::size_t j = 0; j < nearby.size(); ++j) {
      if (out[j].status == JobStatus::NumericalIssue) continue;
      balances[j]->residual(x, f0, r_nearby);
      x_nearby = x - lu.solve(r_nearby - r);
      if (!x_nearby.allFinite()) {
        out[j] = LevelResponse{};
        out[j].status = JobStatus::NumericalIssue;
        out[j].message = "the Jacobian is singular at f0 = " + std::to_string(f0) + " N";
        continue;
      }
      const HbmMeasures measures = balances[j]->measure(x_nearby, f0);
      out[j].f0_n.push_back(f0);
      out[j].edc_j.push_back(measures.edc_j);
      out[j].amp_m.push_back(measures.amp_m);
      out[j].coefficients.push_back(x_nearby);
    }
  }
  return out;
}

}  // namespace oscilab::analysis
