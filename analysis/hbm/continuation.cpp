#include "analysis/hbm/continuation.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <string>

#include <Eigen/LU>

#include "analysis/common/input_error.h"
#include "analysis/hbm/regula_falsi.h"

namespace oscilab::analysis {

void ContinuationOptions::validate() const {
  auto fail = [](const std::string& what) { throw InputError("continuation: " + what); };
  if (!std::isfinite(start) || !std::isfinite(end) || start == end) {
    fail("start and end must be finite and differ");
  }
  if (parameter == BranchParameter::ForcingAmplitude && (start < 0.0 || end < 0.0)) {
    fail("forcing amplitudes must not be negative");
  }
  if (parameter == BranchParameter::Frequency && (start <= 0.0 || end <= 0.0 || !(f0_n > 0.0))) {
    fail("frequencies and the fixed f0 must be positive");
  }
  if (parameter == BranchParameter::ForcingAmplitude && !(freq_hz > 0.0)) {
    fail("frequency must be positive");
  }
  if (!(min_step > 0.0) || !(initial_step >= min_step) || !(max_step >= initial_step)) {
    fail("steps must satisfy 0 < min_step <= initial_step <= max_step");
  }
  if (max_corrector_iterations < 1 || target_iterations < 1) fail("iteration counts must be >= 1");
  if (!(turn_back_limit >= 0.0) || !std::isfinite(turn_back_limit)) {
    fail("turn_back_limit must be finite and non-negative");
  }
  if (!(max_turn_rad > 0.0) || !(residual_tolerance > 0.0) || max_points < 2) {
    fail("max_turn_rad, residual_tolerance must be positive and max_points >= 2");
  }
}

namespace {

// Scaled unknowns y = [x / z_ref; p / p_ref] and residual G(y) = r(x, p) / f_ref: with these all
// entries of y move by O(1) along the branch, so that an arc-length step weighs the response and
// the parameter alike (without scaling, x in metres would be invisible next to f0 in newtons and
// the "arc length" would be the parameter step, which cannot turn at a fold).
class Continuer {
 public:
  Continuer(const Model& model, const ContinuationOptions& options)
      : options_(options),
        hbm_(model,
             options.parameter == BranchParameter::Frequency ? options.start : options.freq_hz,
             options.hbm),
        floquet_(options.floquet),
        n_(hbm_.size()) {
    const Equilibrium well = model.well(options.positive_well);
    z_star_ = well.z_m;
    p_ref_ = std::max(std::abs(options.start), std::abs(options.end));
    f_ref_ = amplitude() ? p_ref_ : options.f0_n;
    z_ref_ = options.displacement_scale_m > 0.0 ? options.displacement_scale_m
                                                : f_ref_ / well.stiffness_n_m;
    f0_ = options.f0_n;
    r_.resize(n_);
    dr_dp_.resize(n_);
    jacobian_.resize(n_, n_);
    g_.resize(n_);
    g_y_.resize(n_, n_ + 1);
    e_p_ = Eigen::VectorXd::Unit(n_ + 1, n_);
  }

  Branch run(const ProgressFn& progress, const CancelToken& cancel) {
    Branch branch = run_steps(progress, cancel);
    attribute_crossings_to_folds(branch);
    return branch;
  }

 private:
  Branch run_steps(const ProgressFn& progress, const CancelToken& cancel);

  // The Floquet multiplier of a truncated HBM orbit reaches +1 a little away from the HBM fold
  // (the orbit is not exactly periodic; at H = 7 on eq. (14) it is 1.017 at the fold, 1.0003 at
  // H = 21), so a +1 crossing can fall in the step next to the fold's. Such a crossing belongs to
  // the fold, not to a bifurcation: drop branch points within two points of a fold.
  static void attribute_crossings_to_folds(Branch& branch) {
    std::vector<BranchEvent> kept;
    for (const BranchEvent& event : branch.events) {
      bool near_fold = false;
      if (event.kind == PointMarker::BranchPoint) {
        for (const BranchEvent& fold : branch.events) {
          near_fold |=
              fold.kind == PointMarker::Fold &&
              (fold.point_index > event.point_index ? fold.point_index - event.point_index
                                                    : event.point_index - fold.point_index) <= 2;
        }
      }
      if (near_fold) {
        branch.points[event.point_index].marker = PointMarker::None;
      } else {
        kept.push_back(event);
      }
    }
    branch.events = kept;
  }

  struct Solved {
    bool ok = false;
    Eigen::VectorXd y;
    Eigen::MatrixXd g_y;  // ∂G/∂y at y
    int iterations = 0;
    double residual_norm = 0.0;  // ‖G‖ (scaled)
    std::string message;
  };

  bool amplitude() const { return options_.parameter == BranchParameter::ForcingAmplitude; }
  double parameter_of(const Eigen::VectorXd& y) const { return y[n_] * p_ref_; }
  void set_parameter(double p) {
    if (amplitude()) {
      f0_ = p;
    } else {
      hbm_.set_frequency(p);
    }
  }
  Eigen::VectorXd x_of(const Eigen::VectorXd& y) const { return y.head(n_) * z_ref_; }
  Eigen::VectorXd y_of(const Eigen::VectorXd& x, double p) const {
    Eigen::VectorXd y(n_ + 1);
    y.head(n_) = x / z_ref_;
    y[n_] = p / p_ref_;
    return y;
  }

  // G(y) and ∂G/∂y into g_ and g_y_.
  void evaluate(const Eigen::VectorXd& y) {
    set_parameter(parameter_of(y));
    const Eigen::VectorXd x = x_of(y);
    hbm_.residual_and_jacobian(x, f0_, r_, jacobian_);
    if (amplitude()) {
      hbm_.d_residual_d_f0(dr_dp_);
    } else {
      hbm_.d_residual_d_omega(x, dr_dp_);
      dr_dp_ *= 2.0 * std::numbers::pi;  // per Hz
    }
    g_ = r_ / f_ref_;
    g_y_.leftCols(n_) = jacobian_ * (z_ref_ / f_ref_);
    g_y_.col(n_) = dr_dp_ * (p_ref_ / f_ref_);
  }

  // Unit tangent of the branch at a point with Jacobian g_y, oriented along `previous`:
  //   [ G_y ; previousᵀ ] t = [ 0 ; 1 ],  t ← t / ‖t‖.
  // previousᵀ t = 1 > 0 keeps the direction of travel through folds (where the parameter
  // component of t changes sign) without any sign bookkeeping.
  Eigen::VectorXd tangent(const Eigen::MatrixXd& g_y, const Eigen::VectorXd& previous) const {
    Eigen::MatrixXd bordered(n_ + 1, n_ + 1);
    bordered.topRows(n_) = g_y;
    bordered.row(n_) = previous.transpose();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n_ + 1);
    rhs[n_] = 1.0;
    Eigen::VectorXd t = bordered.partialPivLu().solve(rhs);
    return t / t.norm();
  }

  // Corrector: Newton on  G(y) = 0,  directionᵀ (y − predicted) = 0  from `predicted`. With the
  // tangent as `direction` this is the pseudo-arclength corrector (the point on the hyperplane
  // through the predictor orthogonal to the tangent); with e_p it is a solve at fixed parameter.
  Solved correct(const Eigen::VectorXd& predicted, const Eigen::VectorXd& direction) {
    Solved out;
    out.y = predicted;
    Eigen::MatrixXd bordered(n_ + 1, n_ + 1);
    Eigen::VectorXd rhs(n_ + 1);
    for (out.iterations = 0;; ++out.iterations) {
      evaluate(out.y);
      out.residual_norm = g_.norm();
      const double constraint = direction.dot(out.y - predicted);
      if (!std::isfinite(out.residual_norm)) {
        out.message = "residual not finite";
        return out;
      }
      if (out.residual_norm <= options_.residual_tolerance && std::abs(constraint) <= 1e-12) {
        out.ok = true;
        out.g_y = g_y_;
        return out;
      }
      if (out.iterations >= options_.max_corrector_iterations) {
        out.message =
            "corrector: no convergence in " + std::to_string(out.iterations) + " iterations";
        return out;
      }
      bordered.topRows(n_) = g_y_;
      bordered.row(n_) = direction.transpose();
      rhs.head(n_) = -g_;
      rhs[n_] = -constraint;
      const Eigen::VectorXd delta = bordered.partialPivLu().solve(rhs);
      if (!delta.allFinite() || delta.norm() > 1e3) {
        out.message = "corrector: singular or diverging";
        return out;
      }
      out.y += delta;
    }
  }

  BranchPoint make_point(const Eigen::VectorXd& y, const Solved& solved, const Eigen::VectorXd& t,
                         PointMarker marker, double arclength) {
    BranchPoint point;
    const double p = parameter_of(y);
    set_parameter(p);
    point.f0_n = f0_;
    point.freq_hz = hbm_.frequency_hz();
    point.coefficients = x_of(y);
    point.measures = hbm_.measure(point.coefficients, f0_);
    if (options_.stability) {
      point.floquet = floquet_.analyse(hbm_, point.coefficients);
      point.stability_known = true;
    }
    point.marker = marker;
    point.newton_iterations = solved.iterations;
    point.residual_norm_n = solved.residual_norm * f_ref_;
    point.arclength = arclength;
    point.tangent_parameter = t[n_];
    return point;
  }

  double flip_test(const Eigen::VectorXd& y) {
    set_parameter(parameter_of(y));
    return floquet_.analyse(hbm_, x_of(y)).flip_test;
  }
  double fold_test(const Eigen::VectorXd& y) {
    set_parameter(parameter_of(y));
    return floquet_.analyse(hbm_, x_of(y)).fold_test;
  }

  struct Located {
    bool ok = false;
    double sigma = 0.0;
    Solved solved;
    Eigen::VectorXd t;
  };
  // A zero of test(σ) for the point corrected from y + σ t on σ ∈ (0, ds), where the test
  // changes sign between σ = 0 (value g0) and σ = ds (g1): the Illinois variant of regula falsi
  // (Dowell & Jarratt 1971), superlinear and always bracketed.
  Located locate(const Eigen::VectorXd& y, const Eigen::VectorXd& t, double ds, double g0,
                 double g1,
                 const std::function<double(const Eigen::VectorXd&, const Solved&)>& test) {
    Located out;
    illinois_regula_falsi(0.0, g0, ds, g1, 1e-10 * std::max(ds, 1e-3),
                          [&](double c) -> std::optional<double> {
                            Solved s = correct(y + c * t, t);
                            if (!s.ok) return std::nullopt;  // keep the last corrected iterate
                            out.ok = true;
                            out.sigma = c;
                            out.solved = s;
                            return test(s.y, s);
                          });
    if (out.ok) out.t = tangent(out.solved.g_y, t);
    return out;
  }

  // A point found within an accepted step, σ along it.
  struct Insert {
    double sigma;
    double lambda;
    BranchPoint point;
  };
  // An accepted step from y (tangent t) to `next` (tangent t_next), of length ds, starting at
  // `arclength` along the branch.
  struct Step {
    const Eigen::VectorXd& y;
    const Eigen::VectorXd& t;
    const Solved& next;
    const Eigen::VectorXd& t_next;
    double ds;
    double arclength;
  };
  Solved start_point(const CancelToken& cancel);
  bool land(const Step& step, double lambda, PointMarker marker, std::vector<Insert>& inserts);
  void locate_events(const Step& step, const BranchPoint& here, const BranchPoint& next_point,
                     double lambda_end, double direction, std::vector<Insert>& inserts);
  static void append(Branch& branch, std::vector<Insert> inserts, bool passes_end,
                     double lambda_end, double direction);
  double next_step_size(double ds, int iterations, double turn_rad) const;

  ContinuationOptions options_;
  HarmonicBalance hbm_;
  FloquetAnalysis floquet_;
  int n_;
  double z_star_ = 0.0, p_ref_ = 1.0, f_ref_ = 1.0, z_ref_ = 1.0, f0_ = 0.0;
  Eigen::VectorXd r_, dr_dp_, g_;
  Eigen::MatrixXd jacobian_, g_y_;
  Eigen::VectorXd
      e_p_;  // the parameter's unit vector in y: the corrector's direction at a fixed value
};

// The first point: the given coefficients or the linear response about the well, corrected at
// the fixed start value. From rest (f0 = 0) the equilibrium itself is the exact solution.
Continuer::Solved Continuer::start_point(const CancelToken& cancel) {
  set_parameter(options_.start);
  Eigen::VectorXd x0 = options_.initial_coefficients.size() == n_
                           ? options_.initial_coefficients
                           : hbm_.linear_guess(z_star_, amplitude() ? options_.start : f0_);
  Solved solved = correct(y_of(x0, options_.start), e_p_);
  if (!solved.ok && amplitude() && options_.start > 0.0 &&
      options_.initial_coefficients.size() != n_) {
    // Grow the response from rest instead: a continuation from f0 = 0 to the start.
    ContinuationOptions pre = options_;
    pre.start = 0.0;
    pre.end = options_.start;
    pre.stability = false;
    pre.locate_events = false;
    pre.landing.clear();
    pre.displacement_scale_m = z_ref_;
    const Branch lead = continue_branch(hbm_.model(), pre, {}, cancel);
    if (lead.status == JobStatus::Ok && !lead.points.empty()) {
      solved = correct(y_of(lead.points.back().coefficients, options_.start), e_p_);
    }
  }
  return solved;
}

// The point of the step at parameter λ (between its ends), corrected at that fixed value from
// the chord; kept in `inserts` when the corrector converged.
bool Continuer::land(const Step& step, double lambda, PointMarker marker,
                     std::vector<Insert>& inserts) {
  const double lambda0 = step.y[n_], lambda1 = step.next.y[n_];
  const double fraction = (lambda - lambda0) / (lambda1 - lambda0);
  Eigen::VectorXd guess = step.y + fraction * (step.next.y - step.y);
  guess[n_] = lambda;
  const Solved s = correct(guess, e_p_);
  if (s.ok) {
    inserts.push_back(
        {fraction * step.ds, s.y[n_],
         make_point(s.y, s, tangent(s.g_y, step.t), marker, step.arclength + fraction * step.ds)});
  }
  return s.ok;
}

// Folds (the tangent's parameter component changes sign), branch points and period doublings
// (the Floquet test functions change sign) within the step, located and kept in `inserts` when
// they lie before the end value.
void Continuer::locate_events(const Step& step, const BranchPoint& here,
                              const BranchPoint& next_point, double lambda_end, double direction,
                              std::vector<Insert>& inserts) {
  auto keep = [&](const Located& located, PointMarker marker) {
    if (located.ok && (located.solved.y[n_] - lambda_end) * direction <= 0.0) {
      inserts.push_back({located.sigma, located.solved.y[n_],
                         make_point(located.solved.y, located.solved, located.t, marker,
                                    step.arclength + located.sigma)});
    }
  };
  const Eigen::VectorXd& t = step.t;
  if ((t[n_] > 0.0) != (step.t_next[n_] > 0.0)) {
    keep(locate(step.y, t, step.ds, t[n_], step.t_next[n_],
                [&](const Eigen::VectorXd&, const Solved& s) { return tangent(s.g_y, t)[n_]; }),
         PointMarker::Fold);
  } else if (options_.stability &&
             (here.floquet.fold_test > 0.0) != (next_point.floquet.fold_test > 0.0)) {
    keep(locate(step.y, t, step.ds, here.floquet.fold_test, next_point.floquet.fold_test,
                [&](const Eigen::VectorXd& yy, const Solved&) { return fold_test(yy); }),
         PointMarker::BranchPoint);
  }
  if (options_.stability &&
      (here.floquet.flip_test > 0.0) != (next_point.floquet.flip_test > 0.0)) {
    keep(locate(step.y, t, step.ds, here.floquet.flip_test, next_point.floquet.flip_test,
                [&](const Eigen::VectorXd& yy, const Solved&) { return flip_test(yy); }),
         PointMarker::PeriodDoubling);
  }
}

// The step's inserted points onto the branch in arclength order, its events listed; beyond the
// end value only the end point itself is kept.
void Continuer::append(Branch& branch, std::vector<Insert> inserts, bool passes_end,
                       double lambda_end, double direction) {
  std::sort(inserts.begin(), inserts.end(),
            [](const Insert& a, const Insert& b) { return a.sigma < b.sigma; });
  for (Insert& insert : inserts) {
    if (insert.point.marker != PointMarker::End && passes_end &&
        (insert.lambda - lambda_end) * direction > 0.0) {
      continue;
    }
    if (insert.point.marker == PointMarker::Fold ||
        insert.point.marker == PointMarker::PeriodDoubling ||
        insert.point.marker == PointMarker::BranchPoint) {
      branch.events.push_back({insert.point.marker, insert.point.f0_n, insert.point.freq_hz,
                               insert.point.measures.amp_m, branch.points.size()});
    }
    branch.points.push_back(std::move(insert.point));
  }
}

// Step control: grow when the corrector converged fast and the branch turned little, shrink when
// the corrector needed more than its target.
double Continuer::next_step_size(double ds, int iterations, double turn_rad) const {
  double factor = 1.0;
  if (iterations < options_.target_iterations) factor = 1.5;
  if (iterations > options_.target_iterations) factor = 0.7;
  if (turn_rad > 0.5 * options_.max_turn_rad) factor = std::min(factor, 1.0);
  return std::clamp(ds * factor, options_.min_step, options_.max_step);
}

Branch Continuer::run_steps(const ProgressFn& progress, const CancelToken& cancel) {
  Branch branch;
  branch.parameter = options_.parameter;
  branch.hbm = options_.hbm;
  branch.samples = hbm_.samples();
  branch.positive_well = options_.positive_well;

  const double direction = options_.end > options_.start ? 1.0 : -1.0;
  const double lambda_start = options_.start / p_ref_, lambda_end = options_.end / p_ref_;

  const Solved solved = start_point(cancel);
  if (!solved.ok) {
    branch.status = JobStatus::NoConvergence;
    branch.message = "no solution at the start value: " + solved.message;
    return branch;
  }
  Eigen::VectorXd y = solved.y;
  Eigen::VectorXd t = tangent(solved.g_y, direction * e_p_);
  double arclength = 0.0;
  branch.points.push_back(make_point(y, solved, t, PointMarker::Start, arclength));
  branch.newton_iterations += solved.iterations;

  std::vector<double> landing;
  for (double value : options_.landing) {
    const double l = value / p_ref_;
    if ((l - lambda_start) * direction > 0.0 && (lambda_end - l) * direction > 0.0) {
      landing.push_back(l);
    }
  }

  double ds = options_.initial_step;
  double progress_done = 0.0;
  const double cos_max_turn = std::cos(options_.max_turn_rad);
  while (true) {
    if (cancel.cancelled()) {
      branch.status = JobStatus::Cancelled;
      branch.message = "cancelled";
      return branch;
    }
    if (static_cast<int>(branch.points.size()) >= options_.max_points) {
      branch.status = JobStatus::NoConvergence;
      branch.message = "stopped at max_points = " + std::to_string(options_.max_points);
      return branch;
    }
    // Predictor along the tangent, corrector orthogonal to it.
    Solved next = correct(y + ds * t, t);
    Eigen::VectorXd t_next;
    bool accept = next.ok;
    if (accept) {
      t_next = tangent(next.g_y, t);
      accept = t_next.dot(t) >= cos_max_turn;
    }
    branch.newton_iterations += next.iterations;
    if (!accept) {
      ++branch.steps_rejected;
      ds *= 0.5;
      if (ds < options_.min_step) {
        branch.status = JobStatus::NoConvergence;
        branch.message = "step size fell below min_step at " + std::to_string(parameter_of(y)) +
                         (amplitude() ? " N" : " Hz") + (next.ok ? "" : ": " + next.message);
        return branch;
      }
      continue;
    }
    ++branch.steps_accepted;

    // Points to insert between y and the new point: landings, located events, the end.
    const Step step{y, t, next, t_next, ds, arclength};
    std::vector<Insert> inserts;
    const double lambda0 = y[n_], lambda1 = next.y[n_];
    const bool passes_end = (lambda1 - lambda_end) * direction >= 0.0;
    for (double l : landing) {
      if ((l - lambda0) * (l - lambda1) < 0.0) land(step, l, PointMarker::Landing, inserts);
    }
    BranchPoint next_point = make_point(next.y, next, t_next, PointMarker::None, arclength + ds);
    if (options_.locate_events) {
      locate_events(step, branch.points.back(), next_point, lambda_end, direction, inserts);
    }
    if (passes_end && !land(step, lambda_end, PointMarker::End, inserts)) {
      branch.status = JobStatus::NoConvergence;
      branch.message = "could not land on the end value";
      return branch;
    }
    append(branch, std::move(inserts), passes_end, lambda_end, direction);
    if (passes_end) break;

    const double turn = std::acos(std::clamp(t_next.dot(t), -1.0, 1.0));
    branch.points.push_back(std::move(next_point));
    arclength += ds;
    y = next.y;
    t = t_next;
    ds = next_step_size(ds, next.iterations, turn);

    const double behind = (lambda_start - y[n_]) * direction;  // > 0: behind the start value
    const double allowed_behind = options_.stop_when_turning_back ? 1e-12
                                  : options_.turn_back_limit > 0.0
                                      ? options_.turn_back_limit
                                      : std::abs(lambda_end - lambda_start);
    if (behind > allowed_behind) {
      branch.message = "the branch turned back past the start value";
      break;
    }
    const double done = std::clamp((y[n_] - lambda_start) / (lambda_end - lambda_start), 0.0, 1.0);
    if (progress && done > progress_done) {
      progress_done = done;
      progress(done);
    }
  }
  if (progress) progress(1.0);
  return branch;
}

}  // namespace

Branch continue_branch(const Model& model, const ContinuationOptions& options,
                       const ProgressFn& progress, const CancelToken& cancel) {
  options.validate();
  if (options.stability && model.state_size() > 0) {
    // The variational equation of FloquetAnalysis has no rows for internal states, so its
    // multipliers would describe another system: the branch is followed without stability.
    ContinuationOptions without = options;
    without.stability = false;
    Continuer continuer(model, without);
    Branch branch = continuer.run(progress, cancel);
    branch.message += std::string(branch.message.empty() ? "" : "; ") +
                      "stability not computed: Floquet analysis does not cover terms with "
                      "internal state (hysteresis)";
    return branch;
  }
  Continuer continuer(model, options);
  return continuer.run(progress, cancel);
}

}  // namespace oscilab::analysis
