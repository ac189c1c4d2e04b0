#include "analysis/hbm/level_response.h"

#include <cmath>

#include "analysis/common/input_error.h"
#include "analysis/hbm/continuation.h"

namespace oscilab::analysis {

LevelResponse level_response(const Model& model, double freq_hz, bool positive_well,
                             const std::vector<double>& levels_n, const HbmOptions& hbm_options) {
  for (std::size_t i = 0; i < levels_n.size(); ++i) {
    if (!(levels_n[i] >= 0.0) || (i > 0 && !(levels_n[i] > levels_n[i - 1]))) {
      throw InputError("level response: levels must be non-negative and increasing");
    }
  }
  LevelResponse out;
  if (levels_n.empty()) return out;
  HarmonicBalance hbm(model, freq_hz, hbm_options);
  const double z_star = model.well(positive_well).z_m;

  // Natural continuation from rest: the equilibrium is the exact solution at f0 = 0.
  Eigen::VectorXd previous = hbm.linear_guess(z_star, 0.0), before_previous;
  double previous_f0 = 0.0, before_previous_f0 = 0.0;
  int sign = 0;
  bool fast = true;
  for (double f0 : levels_n) {
    Eigen::VectorXd x;
    if (before_previous.size() == 0) {
      x = hbm.linear_guess(z_star, f0);
      if (previous_f0 > 0.0) x = previous + (x - hbm.linear_guess(z_star, previous_f0));
    } else {
      x = previous +
          (previous - before_previous) * ((f0 - previous_f0) / (previous_f0 - before_previous_f0));
    }
    const NewtonReport report = hbm.solve(x, f0);
    out.newton_iterations += report.iterations;
    if (!report.converged() || (sign != 0 && report.jacobian_sign != sign)) {
      fast = false;
      break;
    }
    sign = report.jacobian_sign;
    const HbmMeasures measures = hbm.measure(x, f0);
    out.f0_n.push_back(f0);
    out.edc_j.push_back(measures.edc_j);
    out.amp_m.push_back(measures.amp_m);
    out.coefficients.push_back(x);
    before_previous = previous;
    before_previous_f0 = previous_f0;
    previous = x;
    previous_f0 = f0;
  }
  if (fast) return out;

  out.used_arclength = true;
  out.f0_n.clear();
  out.edc_j.clear();
  out.amp_m.clear();
  out.coefficients.clear();
  ContinuationOptions options;
  options.freq_hz = freq_hz;
  options.positive_well = positive_well;
  options.hbm = hbm_options;
  options.start = 0.0;
  options.end = levels_n.back();
  options.stability = false;
  options.locate_events = false;
  options.landing = levels_n;
  const Branch branch = continue_branch(model, options);
  out.newton_iterations += branch.newton_iterations;
  std::size_t next = 0;
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

}  // namespace oscilab::analysis
