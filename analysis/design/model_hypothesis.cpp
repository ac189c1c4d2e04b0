#include "analysis/design/model_hypothesis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <utility>

#include "analysis/common/parallel_for.h"
#include "analysis/design/model_weights.h"
#include "analysis/diagnosis/campaign_fit.h"
#include "analysis/diagnosis/diagnosis.h"
#include "analysis/diagnosis/effect_candidates.h"
#include "analysis/diagnosis/joint_refit.h"
#include "analysis/diagnosis/response_fingerprints.h"

namespace oscilab::analysis {

ModelHypothesis::ModelHypothesis(std::string effect_name, std::string embodiment_name,
                                 ModelForm model_form, Eigen::VectorXd start)
    : effect(std::move(effect_name)),
      embodiment(std::move(embodiment_name)),
      form(std::move(model_form)),
      theta(std::move(start)) {}

double ModelHypothesis::reduced_edc_chi2() const {
  const int dof = levels - parameters();
  return dof > 0 ? edc_chi2 / dof : std::numeric_limits<double>::quiet_NaN();
}

std::string ModelHypothesis::label() const {
  return effect == "none" ? std::string("baseline") : candidate_label(effect, embodiment);
}

namespace {

// The shared σ budget of the dataset, calibrated at the baseline's θ.
EdcCostSettings shared_cost(const ModelForm& form, const Eigen::VectorXd& theta,
                            const EdcDataset& data, const HypothesisOptions& options) {
  EdcCostSettings cost = options.cost;
  cost.budget.reset();
  cost.budget = EdcObjective::calibrate_budget(form, data, cost, theta);
  return cost;
}

// The hypothesis's own defect correction at its θ (reference up to correction_max_harmonics),
// with the shared budget's σ: a new term that changes the response's harmonics does not share
// the baseline's correction, but the χ² of all hypotheses stay on one scale.
EdcCostSettings own_cost(const ModelForm& form, const Eigen::VectorXd& theta,
                         const EdcDataset& data, const EdcCostSettings& shared,
                         const HypothesisOptions& options) {
  EdcCostSettings own = shared;
  EdcCostSettings reference = options.cost;
  reference.budget.reset();
  reference.max_harmonics = std::min(options.cost.max_harmonics, options.correction_max_harmonics);
  const SigmaBudget calibrated = EdcObjective::calibrate_budget(form, data, reference, theta);
  own.budget->adopt_corrections(calibrated);
  return own;
}

void score(ModelHypothesis& h, const JointRefit& fit, const EdcDataset& data,
           const HypothesisOptions& options) {
  h.theta = fit.theta;
  h.solved = fit.theta.size() > 0 && std::isfinite(fit.joint_chi2) && fit.evaluation.ok;
  h.edc_chi2 = fit.evaluation.weighted_cost;
  h.joint_chi2 = fit.joint_chi2;
  h.levels = data.level_count();
  h.residuals = h.levels + (options.use_fingerprints ? fit.fingerprints.count : 0);
  h.bic = h.solved ? h.joint_chi2 + h.parameters() * std::log(static_cast<double>(h.residuals))
                   : std::numeric_limits<double>::infinity();
}

// Levenberg–Marquardt from each start, the best kept.
JointRefit best_refit(const EdcObjective& objective, const std::vector<Eigen::VectorXd>& starts,
                      bool use_fp, int evaluations, const CancelToken& cancel) {
  JointRefit best;
  best.joint_chi2 = std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& start : starts) {
    if (cancel.cancelled()) break;
    JointRefit attempt = joint_refit(objective, start, use_fp, evaluations, cancel);
    if (attempt.theta.size() > 0 && attempt.joint_chi2 < best.joint_chi2) best = std::move(attempt);
  }
  return best;
}

// Starting values of a candidate's own parameters besides its scan points (unlike the diagnosis's
// candidate_grid, one or two parameters of non-negative bounds only): each parameter on a
// log-spaced grid from 1e-3 of its upper bound (or its lower bound, when larger) to the upper
// bound, 10 values for one parameter and 5 × 5 for two (the diagnosis's grid); more parameters
// keep the scan points only.
std::vector<Eigen::VectorXd> start_grid(const EffectCandidate& c) {
  const int p = static_cast<int>(c.free.size());
  if (p < 1 || p > 2) return {};
  const int per = p == 1 ? 10 : 5;
  std::vector<std::vector<double>> axes;
  for (const FreeParameter& f : c.free) {
    const double hi = f.upper, lo = std::max(f.lower, 1e-3 * f.upper);
    std::vector<double> axis;
    for (int i = 0; i < per; ++i) {
      axis.push_back(lo > 0.0 ? lo * std::pow(hi / lo, i / (per - 1.0))
                              : lo + (hi - lo) * i / (per - 1.0));
    }
    axes.push_back(axis);
  }
  std::vector<Eigen::VectorXd> out;
  for (int i = 0; i < per; ++i) {
    for (int j = 0; j < (p == 2 ? per : 1); ++j) {
      Eigen::VectorXd point(p);
      point[0] = axes[0][static_cast<std::size_t>(i)];
      if (p == 2) point[1] = axes[1][static_cast<std::size_t>(j)];
      out.push_back(point);
    }
  }
  return out;
}

// Runs one hypothesis's fit on a worker: nothing throws across threads. A fit that throws (a θ
// outside a term's domain that the search reached, a model harmonic balance cannot take) leaves
// its hypothesis unsolved with the message.
template <typename Fit>
void guarded(ModelHypothesis& h, const Fit& fit, std::size_t slot) {
  try {
    fit(slot);
  } catch (const std::exception& error) {
    h.solved = false;
    h.bic = std::numeric_limits<double>::infinity();
    h.message = error.what();
  }
}

bool wanted(const std::vector<std::string>& effects, const std::string& effect) {
  return effects.empty() || std::find(effects.begin(), effects.end(), effect) != effects.end();
}

}  // namespace

namespace {

std::vector<ModelHypothesis> initial(const ModelForm& form, const Eigen::VectorXd& theta,
                                     const CampaignAnalysis* campaign, const EdcDataset& data,
                                     const HypothesisOptions& options, const ProgressFn& progress,
                                     const CancelToken& cancel) {
  const EdcCostSettings shared = shared_cost(form, theta, data, options);
  std::vector<ModelHypothesis> out;
  out.emplace_back("none", "", form, theta);
  std::vector<EffectCandidate> candidates;
  for (EffectCandidate& c : effect_candidates(form, data)) {
    if (wanted(options.effects, c.effect)) candidates.push_back(std::move(c));
  }
  for (const EffectCandidate& c : candidates) {
    const ModelForm extended = c.extend(form, c.scan.front());
    Eigen::VectorXd start(extended.size());
    start << theta, c.scan.front();
    out.emplace_back(c.effect, c.embodiment, extended, extended.clamp(start));
  }
  std::mutex done_mutex;
  std::size_t done = 0;
  const auto fit_one = [&](std::size_t slot) {
    ModelHypothesis& h = out[slot];
    if (cancel.cancelled()) return;
    const auto objective = std::make_shared<const EdcObjective>(h.form, data, shared);
    std::vector<Eigen::VectorXd> starts;
    if (slot == 0) {
      starts.push_back(h.theta);
    } else {
      // The candidate's grid and scan points with the baseline's parameters at θ, one
      // evaluation each; Levenberg–Marquardt from the three best (a term that starts too weak or
      // too strong needs more than one start, as in the diagnosis).
      const EffectCandidate& c = candidates[slot - 1];
      std::vector<std::pair<double, Eigen::VectorXd>> scored;
      std::vector<Eigen::VectorXd> points = start_grid(c);
      points.insert(points.end(), c.scan.begin(), c.scan.end());
      for (const Eigen::VectorXd& s : points) {
        if (cancel.cancelled()) return;
        Eigen::VectorXd point(h.form.size());
        point << theta, s;
        point = h.form.clamp(point);
        const EdcEvaluation e = objective->evaluate(point);
        scored.emplace_back(joint_chi2(e, response_fingerprints(data, e), options.use_fingerprints),
                            point);
        ++h.evaluations;
      }
      std::sort(scored.begin(), scored.end(),
                [](const auto& x, const auto& y) { return x.first < y.first; });
      for (std::size_t i = 0; i < std::min<std::size_t>(3, scored.size()); ++i) {
        starts.push_back(scored[i].second);
      }
    }
    if (campaign && options.global_evaluations > 0 && !cancel.cancelled()) {
      // The global search over the hypothesis's form; the grid's best point stays a start.
      EdcCostSettings cost = options.cost;
      cost.budget.reset();
      const PreparedFit prepared{
          std::make_shared<const EdcObjective>(h.form, data, cost), {}, cost};
      FitOptions fit_options;
      fit_options.max_evaluations = options.global_evaluations;
      fit_options.seed = options.seed;
      fit_options.threads = 1;  // the hypotheses run in parallel
      fit_options.compute_uncertainty = false;
      fit_options.check_truncation = false;
      const CampaignFit global = fit_campaign(prepared, *campaign, fit_options, {}, cancel);
      h.evaluations += global.fit.evaluations;
      if (global.fit.theta.size() == h.form.size()) {
        starts.resize(std::min<std::size_t>(starts.size(), 1));
        starts.insert(starts.begin(), global.fit.theta);
      }
    }
    const int per_start =
        std::max(20, options.initial_evaluations /
                         static_cast<int>(std::max<std::size_t>(1, starts.size())));
    JointRefit fit = best_refit(*objective, starts, options.use_fingerprints, per_start, cancel);
    if (fit.theta.size() == 0) return;
    // Its own correction at the fitted θ, and one warm refit with it.
    const auto own = std::make_shared<const EdcObjective>(
        h.form, data, own_cost(h.form, fit.theta, data, shared, options));
    JointRefit again =
        joint_refit(*own, fit.theta, options.use_fingerprints, options.refit_evaluations, cancel);
    h.evaluations += fit.evaluations + again.evaluations;
    if (again.theta.size() > 0 && again.joint_chi2 <= fit.joint_chi2) fit = std::move(again);
    h.objective = own;
    score(h, fit, data, options);
    const std::lock_guard lock(done_mutex);
    ++done;
    if (progress) progress(static_cast<double>(done) / out.size());
  };
  parallel_for(out.size(), options.threads,
               [&](std::size_t slot) { guarded(out[slot], fit_one, slot); });
  update_weights(out);
  return out;
}

}  // namespace

std::vector<ModelHypothesis> initial_hypotheses(const ModelForm& form, const Eigen::VectorXd& theta,
                                                const EdcDataset& data,
                                                const HypothesisOptions& options,
                                                const ProgressFn& progress,
                                                const CancelToken& cancel) {
  return initial(form, theta, nullptr, data, options, progress, cancel);
}

std::vector<ModelHypothesis> initial_hypotheses(const ModelForm& form, const Eigen::VectorXd& theta,
                                                const CampaignAnalysis& campaign,
                                                const EdcDataset& data,
                                                const HypothesisOptions& options,
                                                const ProgressFn& progress,
                                                const CancelToken& cancel) {
  return initial(form, theta, &campaign, data, options, progress, cancel);
}

void refit_hypotheses(std::vector<ModelHypothesis>& hypotheses, const EdcDataset& data,
                      const HypothesisOptions& options, const ProgressFn& progress,
                      const CancelToken& cancel) {
  if (hypotheses.empty()) return;
  const EdcCostSettings shared =
      shared_cost(hypotheses.front().form, hypotheses.front().theta, data, options);
  std::mutex done_mutex;
  std::size_t done = 0;
  const auto refit_one = [&](std::size_t slot) {
    ModelHypothesis& h = hypotheses[slot];
    if (cancel.cancelled() || h.theta.size() != h.form.size()) return;
    const auto objective = std::make_shared<const EdcObjective>(
        h.form, data, own_cost(h.form, h.theta, data, shared, options));
    JointRefit fit = joint_refit(*objective, h.theta, options.use_fingerprints,
                                 options.refit_evaluations, cancel);
    if (fit.theta.size() == 0) {
      h.solved = false;
      h.bic = std::numeric_limits<double>::infinity();
      return;
    }
    h.objective = objective;
    h.evaluations += fit.evaluations;
    score(h, fit, data, options);
    const std::lock_guard lock(done_mutex);
    ++done;
    if (progress) progress(static_cast<double>(done) / hypotheses.size());
  };
  parallel_for(hypotheses.size(), options.threads,
               [&](std::size_t slot) { guarded(hypotheses[slot], refit_one, slot); });
  update_weights(hypotheses);
}

}  // namespace oscilab::analysis
