#include "analysis/diagnosis/candidate_trial.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "analysis/diagnosis/joint_refit.h"

namespace oscilab::analysis {
namespace {

// A friction parameter farther than this from the lab form's start (a share of its range) makes
// the candidate's refits start from the lab's friction as well.
constexpr double kLabStartDistance = 0.05;

// The grid over a candidate's own parameters: per parameter 10 values (one parameter) or 5
// (two), log-spaced over its bounds (from 1e-3 of the upper bound when the lower is 0; both signs
// when the bounds straddle 0).
std::vector<Eigen::VectorXd> candidate_grid(const EffectCandidate& c) {
  const int per_axis = c.free.size() == 1 ? 10 : 5;
  std::vector<std::vector<double>> axes;
  for (const FreeParameter& p : c.free) {
    std::vector<double> axis;
    const double hi = p.upper;
    const double lo = p.lower > 0.0 ? p.lower : 1e-3 * std::abs(hi);
    const int count = p.lower < 0.0 ? per_axis / 2 : per_axis;
    for (int i = 0; i < count; ++i) {
      const double v = lo * std::pow(std::abs(hi) / lo, static_cast<double>(i) / (count - 1));
      axis.push_back(v);
      if (p.lower < 0.0) axis.push_back(-v);
    }
    axes.push_back(axis);
  }
  std::vector<Eigen::VectorXd> grid;
  std::vector<std::size_t> index(axes.size(), 0);
  for (;;) {
    Eigen::VectorXd point(static_cast<Eigen::Index>(axes.size()));
    for (std::size_t a = 0; a < axes.size(); ++a) point(a) = axes[a][index[a]];
    grid.push_back(point);
    std::size_t a = 0;
    while (a < axes.size() && ++index[a] == axes[a].size()) index[a++] = 0;
    if (a == axes.size()) break;
  }
  return grid;
}

// The evidence a candidate's refit moved: the EDC's χ² and each response fingerprint's.
std::vector<EvidenceChange> evidence_changes(double edc_before, double edc_after,
                                             const ResponseFingerprints& before,
                                             const ResponseFingerprints& after) {
  std::vector<EvidenceChange> out = {{"edc", edc_before, edc_after}};
  for (std::size_t i = 0; i < before.items.size() && i < after.items.size(); ++i) {
    if (before.items[i].levels == 0) continue;
    out.push_back({before.items[i].name, before.items[i].chi2, after.items[i].chi2});
  }
  return out;
}

// Scores a candidate's refit against the current model: ΔBIC of the EDC alone and jointly with
// the fingerprints, and how each piece of evidence moved. The dispersion φ ≥ 1 divides the Δχ²
// (quasi-likelihood: σ inflated by √φ when the current model still misses the data by more than
// its noise), so that a term must explain a real share of what is left.
void score_trial(CandidateTrial& trial, const JointRefit& fit, const TrialContext& context,
                 int added) {
  const EdcEvaluation& current = context.evaluation;
  const double levels = static_cast<double>(context.levels);
  trial.theta = fit.theta;
  trial.joint_chi2 = fit.joint_chi2;
  trial.weighted_cost = fit.evaluation.weighted_cost;
  trial.cost_j = fit.evaluation.cost_j;
  trial.solved = fit.evaluation.ok;
  trial.delta_bic = (fit.evaluation.weighted_cost - current.weighted_cost) / context.dispersion +
                    added * std::log(levels);
  trial.evidence = evidence_changes(current.weighted_cost, fit.evaluation.weighted_cost,
                                    context.fingerprints, fit.fingerprints);
  trial.delta_bic_joint = trial.delta_bic;
  if (context.use_fingerprints && fit.fingerprints.count > 0) {
    trial.delta_bic_joint =
        (fit.joint_chi2 - joint_chi2(current, context.fingerprints, true)) / context.dispersion +
        added * std::log(levels + fit.fingerprints.count);
  }
}

// Stage (1): the joint χ² of the extended model at each of `own` (the new term's parameters)
// with the others at `others`, best first.
std::vector<std::pair<double, Eigen::VectorXd>> scored_at(const ModelForm& extended,
                                                          const EdcObjective& objective,
                                                          const TrialContext& context,
                                                          const Eigen::VectorXd& others,
                                                          const std::vector<Eigen::VectorXd>& own,
                                                          const CancelToken& cancel) {
  std::vector<std::pair<double, Eigen::VectorXd>> out;
  for (const Eigen::VectorXd& s : own) {
    if (cancel.cancelled()) break;
    Eigen::VectorXd point(extended.size());
    point << others, s;
    point = extended.clamp(point);
    const EdcEvaluation e = objective.evaluate(point);
    out.emplace_back(
        joint_chi2(e, response_fingerprints(context.data, e), context.use_fingerprints), point);
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  return out;
}

// The current θ with its friction moved back to the lab form's start (the stiffness and the
// accepted terms as they are), when the current friction differs from it by more than
// kLabStartDistance of a parameter's range; nullopt otherwise.
std::optional<Eigen::VectorXd> lab_friction_start(const TrialContext& context) {
  const ModelForm& form = context.lab_form;
  Eigen::VectorXd start = context.theta;
  bool differs = false;
  const Eigen::VectorXd form_unit = form.to_unit(form.initial()),
                        current_unit = context.current.to_unit(context.theta);
  for (int i = 0; i < form.size(); ++i) {
    if (form.is_stiffness(i)) continue;
    start(i) = form.initial()(i);
    differs = differs || std::abs(form_unit(i) - current_unit(i)) > kLabStartDistance;
  }
  if (!differs) return std::nullopt;
  return start;
}

}  // namespace

long trial_budget(long candidate_evaluations) {
  return candidate_evaluations + candidate_evaluations / 2;
}

TrialOutcome try_candidate(const EffectCandidate& c, double fingerprint_score,
                           const TrialContext& context,
                           const std::function<void(long evaluations)>& spent_so_far,
                           const CancelToken& cancel) {
  TrialOutcome out{{}, std::nullopt, context.cost};
  CandidateTrial& trial = out.trial;
  trial.effect = c.effect;
  trial.embodiment = c.embodiment;
  trial.fingerprint_score = fingerprint_score;
  const ModelForm extended = c.extend(context.current, c.scan.front());
  const EdcObjective extended_objective(extended, context.data, context.cost);
  const auto scored = [&](const Eigen::VectorXd& others, const std::vector<Eigen::VectorXd>& own) {
    return scored_at(extended, extended_objective, context, others, own, cancel);
  };
  const auto grid = scored(context.theta, candidate_grid(c));
  const auto scan = scored(context.theta, c.scan);
  // A new term that starts too strong or too weak, or whose effect the current parameters partly
  // mimic, needs more than one start.
  std::vector<Eigen::VectorXd> starts;
  for (std::size_t i = 0; i < std::min<std::size_t>(2, grid.size()); ++i) {
    starts.push_back(grid[i].second);
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(2, scan.size()); ++i) {
    starts.push_back(scan[i].second);
  }
  long spent = static_cast<long>(grid.size() + scan.size());
  // A baseline bends its friction to stand in for a missing effect (a sliding law pushed to its
  // bounds for a stiff presliding regime), and an effect that changes that law needs the
  // friction to move back, which a refit from the bent θ may not find.
  if (const std::optional<Eigen::VectorXd> lab_start = lab_friction_start(context)) {
    const auto lab_grid = scored(*lab_start, candidate_grid(c));
    if (!lab_grid.empty()) starts.push_back(lab_grid.front().second);
    spent += static_cast<long>(lab_grid.size());
  }
  if (spent_so_far) spent_so_far(spent);
  JointRefit fit;
  fit.joint_chi2 = std::numeric_limits<double>::infinity();
  const long per_start = std::max<long>(
      40, (context.candidate_evaluations - spent) / std::max<long>(1, starts.size()));
  for (const Eigen::VectorXd& point : starts) {
    if (cancel.cancelled()) break;
    JointRefit attempt = joint_refit(extended_objective, point, context.use_fingerprints,
                                     static_cast<int>(per_start), cancel);
    spent += attempt.evaluations;
    if (spent_so_far) spent_so_far(spent);
    if (attempt.theta.size() > 0 && attempt.joint_chi2 < fit.joint_chi2) fit = std::move(attempt);
  }
  if (fit.theta.size() == 0 || cancel.cancelled()) {
    trial.solved = false;
    return out;
  }
  // The current model's defect correction does not hold for a new term that changes the
  // response's harmonics (a strong presliding or Stribeck term): the candidate gets its own
  // correction at its refitted θ (reference up to H = 31 here; the accepted model is settled up
  // to the full reference) and one more refit with it. Its σ stays the shared budget's, so that
  // the candidates' χ² remain comparable.
  {
    EdcCostSettings reference = context.base_cost;
    reference.max_harmonics = std::min(context.max_harmonics, 31);
    const SigmaBudget calibrated =
        EdcObjective::calibrate_budget(extended, context.data, reference, fit.theta);
    out.own_cost.budget->adopt_corrections(calibrated);
  }
  if (!cancel.cancelled()) {
    const EdcObjective own_objective(extended, context.data, out.own_cost);
    JointRefit again = joint_refit(own_objective, fit.theta, context.use_fingerprints,
                                   static_cast<int>(context.candidate_evaluations / 2), cancel);
    spent += again.evaluations;
    if (spent_so_far) spent_so_far(spent);
    if (again.theta.size() > 0) fit = std::move(again);
  }
  score_trial(trial, fit, context, static_cast<int>(c.free.size()));
  out.form = extended;
  return out;
}

void refine_finalist(CandidateTrial& trial, const ModelForm& extended,
                     const EdcCostSettings& own_cost, const TrialContext& context, long evaluations,
                     const CancelToken& cancel) {
  const JointRefit fit =
      joint_refit(EdcObjective(extended, context.data, own_cost), trial.theta,
                  context.use_fingerprints, static_cast<int>(evaluations), cancel);
  if (fit.theta.size() == 0 || !(fit.joint_chi2 < trial.joint_chi2) || !fit.evaluation.ok) return;
  score_trial(trial, fit, context, extended.size() - context.current.size());
}

}  // namespace oscilab::analysis
