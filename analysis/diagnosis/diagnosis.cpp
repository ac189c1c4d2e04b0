#include "analysis/diagnosis/diagnosis.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <thread>

#include "analysis/common/input_error.h"
#include "analysis/common/parallel_for.h"
#include "analysis/diagnosis/effect_candidates.h"
#include "analysis/diagnosis/joint_refit.h"
#include "analysis/diagnosis/settled_model.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/identification/sigma_budget_report.h"

namespace oscilab::analysis {
namespace {

// Fingerprint score of a candidate (lower ranks first). Damping laws: distance of the expected
// slope of the energy they add from the slope of the energy the model misses, in units of that
// slope's standard error (at least 0.25: a slope from few levels is rough). Stiffness powers: by
// the significance of their power in the stiffness-slice residual, after every damping law whose
// slope is within reach when the residual is not significant.
double fingerprint_score(const EffectCandidate& c, const DiscrepancyMaps& maps) {
  if (c.stiffness) {
    for (const auto& test : maps.stiffness.tests) {
      if (test.power == c.stiffness_power) return test.p_value < 1e-3 ? test.p_value : 10.0;
    }
    return 20.0;
  }
  const LogSlope& slope = maps.slopes.missing_all;
  if (!slope.valid() || !std::isfinite(slope.standard_error)) return 5.0;
  return std::abs(slope.slope - c.expected_slope) / std::max(slope.standard_error, 0.25);
}

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

std::vector<std::pair<std::string, double>> named(const ModelForm& form,
                                                  const Eigen::VectorXd& theta) {
  std::vector<std::pair<std::string, double>> out;
  for (int i = 0; i < form.size(); ++i) out.emplace_back(form.parameters()[i].name, theta(i));
  return out;
}

// A cancellation token that fires when the caller cancels or the deadline passes, whichever
// comes first (a watcher thread polls both every 20 ms and stops when the work is done).
class DeadlineToken {
 public:
  DeadlineToken(const CancelToken& outer, double max_seconds) : outer_(outer) {
    const bool bounded = max_seconds > 0.0 && std::isfinite(max_seconds);
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(bounded ? max_seconds : 0.0));
    watcher_ = std::thread([this, bounded, deadline] {
      std::unique_lock lock(mutex_);
      while (!done_) {
        if (outer_.cancelled()) {
          inner_.cancel();
          return;
        }
        if (bounded && std::chrono::steady_clock::now() >= deadline) {
          expired_ = true;
          inner_.cancel();
          return;
        }
        wake_.wait_for(lock, std::chrono::milliseconds(20));
      }
    });
  }
  ~DeadlineToken() {
    {
      const std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    watcher_.join();
  }
  DeadlineToken(const DeadlineToken&) = delete;
  DeadlineToken& operator=(const DeadlineToken&) = delete;
  const CancelToken& token() const { return inner_; }
  bool expired() const { return expired_.load(); }

 private:
  CancelToken outer_, inner_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::atomic<bool> expired_{false};
  std::thread watcher_;
};

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
// the fingerprints, and how each piece of evidence moved. `dispersion` φ ≥ 1 divides the Δχ²
// (quasi-likelihood: σ inflated by √φ when the current model still misses the data by more than
// its noise), so that a term must explain a real share of what is left.
void score_trial(CandidateTrial& trial, const JointRefit& fit, const EdcEvaluation& current,
                 const ResponseFingerprints& current_fingerprints, int added, int levels,
                 bool use_fingerprints, double dispersion) {
  trial.theta = fit.theta;
  trial.joint_chi2 = fit.joint_chi2;
  trial.weighted_cost = fit.evaluation.weighted_cost;
  trial.cost_j = fit.evaluation.cost_j;
  trial.solved = fit.evaluation.ok;
  trial.delta_bic = (fit.evaluation.weighted_cost - current.weighted_cost) / dispersion +
                    added * std::log(static_cast<double>(levels));
  trial.evidence = evidence_changes(current.weighted_cost, fit.evaluation.weighted_cost,
                                    current_fingerprints, fit.fingerprints);
  trial.delta_bic_joint = trial.delta_bic;
  if (use_fingerprints && fit.fingerprints.count > 0) {
    trial.delta_bic_joint =
        (fit.joint_chi2 - joint_chi2(current, current_fingerprints, true)) / dispersion +
        added * std::log(static_cast<double>(levels + fit.fingerprints.count));
  }
}

// The reduced joint χ² of the current model (EDC, and the fingerprints when they are weighed).
double joint_reduced_chi2(const EdcEvaluation& evaluation, const DiscrepancyMaps& maps,
                          bool use_fingerprints, int levels, int parameters) {
  const int residuals = levels + (use_fingerprints ? maps.response.count : 0);
  return joint_chi2(evaluation, maps.response, use_fingerprints) /
         std::max(1, residuals - parameters);
}

// Halton's radical inverse of k in `base`: a space-filling sequence in [0, 1).
double halton(int k, int base) {
  double value = 0.0, fraction = 1.0;
  for (int i = k; i > 0; i /= base) {
    fraction /= base;
    value += fraction * (i % base);
  }
  return value;
}
constexpr std::array<int, 8> kPrimes = {2, 3, 5, 7, 11, 13, 17, 19};
constexpr int kBoundRestarts = 4;
// A friction parameter farther than this from the form's start (a share of its range) makes the
// candidates' refits start from the form's friction as well.
constexpr double kLabStartDistance = 0.05;

// Whether a parameter other than the stiffness's sits within 1e-3 of a bound (unit cube).
bool at_a_bound(const ModelForm& form, const Eigen::VectorXd& theta) {
  const Eigen::VectorXd unit = form.to_unit(theta);
  for (int i = 0; i < form.size(); ++i) {
    if (!form.is_stiffness(i) && (unit(i) <= 1e-3 || unit(i) >= 1.0 - 1e-3)) return true;
  }
  return false;
}

}  // namespace

DiagnosisResult diagnose(const CampaignAnalysis& campaign, const ModelForm& form,
                         const DiagnosisOptions& options, const ProgressFn& progress,
                         const CancelToken& outer_cancel) {
  if (options.max_steps < 0) throw InputError("diagnose: max steps must be ≥ 0");
  if (!(options.bic_threshold >= 0.0)) throw InputError("diagnose: the ΔBIC threshold must be ≥ 0");
  if (options.threads < 0 || options.threads > kMaxThreads) {
    throw InputError("diagnose: threads: " + std::to_string(options.threads) +
                     " must be 0 (all cores) to " + std::to_string(kMaxThreads));
  }
  for (const long evaluations : {options.baseline_evaluations, options.candidate_evaluations}) {
    if (evaluations < 1 || evaluations > kMaxFitEvaluations) {
      throw InputError("diagnose: evaluations: " + std::to_string(evaluations) + " must be 1 to " +
                       std::to_string(kMaxFitEvaluations));
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const DeadlineToken deadline(outer_cancel, options.max_seconds);
  const CancelToken& cancel = deadline.token();
  DiagnosisResult result;
  const EdcDataset data = edc_dataset(campaign);
  result.excluded_levels = data.excluded;
  const int n = data.level_count();
  const auto report = [&](double fraction) {
    if (progress) progress(std::clamp(fraction, 0.0, 1.0));
  };

  // Baseline: the form as given, searched globally, its σ budget calibrated at the form's
  // initial θ. An identified stiffness is held at its start (the slice's cubic or the model's)
  // in the global search on the EDC, which barely sees it, and freed when the model is settled
  // on the EDC and the fingerprints, which pin it.
  const bool identified_stiffness = form.identifies_stiffness();
  const ModelForm search_form =
      identified_stiffness ? form.holding_stiffness(form.initial()) : form;
  EdcCostSettings base_cost = options.cost;
  base_cost.cancel = cancel;  // the calibrations stop with the job
  const EdcObjective baseline_objective(search_form, data, base_cost);
  FitOptions baseline_options;
  baseline_options.max_evaluations = options.baseline_evaluations;
  baseline_options.seed = options.seed;
  baseline_options.threads = options.threads;
  baseline_options.compute_uncertainty = false;
  baseline_options.check_truncation = false;
  result.baseline = fit_edc(baseline_objective, baseline_options, {}, cancel);
  result.evaluations += result.baseline.evaluations;
  report(0.25);
  Eigen::VectorXd theta = identified_stiffness ? form.expand(result.baseline.theta, form.initial())
                                               : result.baseline.theta;
  ModelForm current = form.with_initial(theta);
  const bool use_fp = options.use_fingerprints;

  // Settling (settle_model): the σ budget calibrated at θ, the joint refit repeated while θ moves.
  // The σ budget is then shared by every objective of the step, so that the χ² of the current
  // model and of all its candidates are comparable. A candidate's gain is measured against the
  // settled model, so that a baseline search that stopped short of its optimum (the paper's form
  // has a weakly identified f_d(0), §5) does not credit an added term with the rest.
  EdcCostSettings cost = base_cost;
  std::shared_ptr<const EdcObjective> objective;
  EdcEvaluation evaluation;
  DiscrepancyMaps maps;
  const auto settle = [&] {
    SettledModel settled = settle_model(current, theta, data, campaign, base_cost, use_fp,
                                        static_cast<int>(options.candidate_evaluations), cancel);
    result.evaluations += settled.evaluations;
    current = std::move(settled.form);
    theta = std::move(settled.theta);
    cost = std::move(settled.cost);
    objective = std::move(settled.objective);
    evaluation = std::move(settled.evaluation);
    maps = std::move(settled.maps);
  };
  settle();
  // A baseline at a bound: the weakly identified f_d(0) of §5 (or another friction parameter)
  // can be pushed onto its bound by a search that stopped in the wrong basin, and nothing after
  // it recovers. Then the refit is restarted from space-filling points of the friction's unit
  // cube (Halton, bases 2, 3, 5 …; the stiffness at its settled values) and the best is settled.
  if (!cancel.cancelled() && at_a_bound(current, theta)) {
    const double before = joint_chi2(evaluation, maps.response, use_fp);
    JointRefit best;
    best.joint_chi2 = before;
    const Eigen::VectorXd unit = current.to_unit(theta);
    for (int k = 1; k <= kBoundRestarts && !cancel.cancelled(); ++k) {
      Eigen::VectorXd start = unit;
      int dimension = 0;
      for (int i = 0; i < current.size(); ++i) {
        if (!current.is_stiffness(i)) start(i) = halton(k, kPrimes[dimension++ % kPrimes.size()]);
      }
      JointRefit fit = joint_refit(*objective, current.from_unit(start), use_fp,
                                   static_cast<int>(options.candidate_evaluations), cancel);
      result.evaluations += fit.evaluations;
      if (fit.theta.size() > 0 && fit.joint_chi2 < best.joint_chi2) best = std::move(fit);
    }
    ++result.baseline_restarts;
    if (best.theta.size() > 0 && best.joint_chi2 < before) {
      theta = best.theta;
      current = current.with_initial(theta);
      settle();
      result.baseline_restart_improved = true;
    }
  }
  result.baseline.theta = theta;
  result.baseline.names = current.names();
  result.baseline.evaluation = evaluation;
  result.baseline_maps = maps;
  const auto noise_level = [&](int parameters) {
    const int dof = std::max(1, n - parameters);
    return 1.0 + 3.0 * std::sqrt(2.0 / dof);
  };
  result.noise_reduced_chi2 = noise_level(current.size());
  std::vector<std::string> accepted_effects;

  for (int step = 0; step < options.max_steps && !cancel.cancelled(); ++step) {
    if (maps.reduced_chi2 <= noise_level(current.size())) break;  // explained within its noise
    std::vector<EffectCandidate> candidates = effect_candidates(current, data);
    // An effect already accepted is not offered again (stiffness powers share one term type).
    std::erase_if(candidates, [&](const EffectCandidate& c) {
      return std::find(accepted_effects.begin(), accepted_effects.end(), c.effect) !=
             accepted_effects.end();
    });
    std::vector<double> scores;
    for (const auto& c : candidates) scores.push_back(fingerprint_score(c, maps));
    std::vector<std::size_t> order(candidates.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return scores[a] < scores[b]; });

    DiagnosisStep record;
    const int form_size_before = current.size();
    // Quasi-likelihood after the first accepted effect: the misfit the extended model leaves
    // (its reduced joint χ², at least 1) inflates σ, so a further term must explain a share of
    // what is left, not a few per cent of a large misfit. The first step compares at the stated
    // σ: the baseline may be far from the data because an effect is missing.
    record.dispersion =
        accepted_effects.empty()
            ? 1.0
            : std::max(1.0, joint_reduced_chi2(evaluation, maps, use_fp, n, current.size()));
    const double dispersion = record.dispersion;
    record.maps_before = maps;
    record.cost_before_j = evaluation.cost_j;
    record.weighted_before = evaluation.weighted_cost;
    record.reduced_chi2_before = maps.reduced_chi2;
    record.trials.resize(order.size());
    std::vector<std::optional<ModelForm>> forms(order.size());
    std::vector<EdcCostSettings> own_costs(order.size(), cost);
    std::mutex done_mutex;
    int done = 0;
    parallel_for(order.size(), options.threads, [&](std::size_t slot) {
      const EffectCandidate& c = candidates[order[slot]];
      CandidateTrial& trial = record.trials[slot];
      trial.effect = c.effect;
      trial.embodiment = c.embodiment;
      trial.fingerprint_score = scores[order[slot]];
      const ModelForm extended = c.extend(current, c.scan.front());
      const EdcObjective extended_objective(extended, data, cost);
      // Two stages. (1) A grid over the new term's own parameters, and its scan points spread
      // over the plausible range, with the others at the current θ (one evaluation each).
      // (2) Levenberg–Marquardt refits of all parameters from the two best grid points and the
      // two best scan points: a new term that starts too strong or too weak, or whose effect the
      // current parameters partly mimic, needs more than one start.
      const auto scored_at = [&](const Eigen::VectorXd& others,
                                 const std::vector<Eigen::VectorXd>& own) {
        std::vector<std::pair<double, Eigen::VectorXd>> out;
        for (const Eigen::VectorXd& s : own) {
          if (cancel.cancelled()) break;
          Eigen::VectorXd point(extended.size());
          point << others, s;
          point = extended.clamp(point);
          const EdcEvaluation e = extended_objective.evaluate(point);
          out.emplace_back(joint_chi2(e, response_fingerprints(data, e), use_fp), point);
        }
        std::sort(out.begin(), out.end(),
                  [](const auto& x, const auto& y) { return x.first < y.first; });
        return out;
      };
      const auto scored = [&](const std::vector<Eigen::VectorXd>& own) {
        return scored_at(theta, own);
      };
      const auto grid = scored(candidate_grid(c));
      const auto scan = scored(c.scan);
      std::vector<Eigen::VectorXd> starts;
      for (std::size_t i = 0; i < std::min<std::size_t>(2, grid.size()); ++i) {
        starts.push_back(grid[i].second);
      }
      for (std::size_t i = 0; i < std::min<std::size_t>(2, scan.size()); ++i) {
        starts.push_back(scan[i].second);
      }
      long spent = static_cast<long>(grid.size() + scan.size());
      // The form's starting friction (the lab's model) with the current stiffness and accepted
      // terms: a baseline bends its friction to stand in for a missing effect (a sliding law
      // pushed to its bounds for a stiff presliding regime), and an effect that changes that
      // law needs the friction to move back, which a refit from the bent θ may not find. One
      // more start, from the best grid point about that friction, when it differs.
      Eigen::VectorXd lab_start = theta;
      bool differs = false;
      const Eigen::VectorXd form_unit = form.to_unit(form.initial()),
                            current_unit = current.to_unit(theta);
      for (int i = 0; i < form.size(); ++i) {
        if (form.is_stiffness(i)) continue;
        lab_start(i) = form.initial()(i);
        differs = differs || std::abs(form_unit(i) - current_unit(i)) > kLabStartDistance;
      }
      if (differs) {
        const auto lab_grid = scored_at(lab_start, candidate_grid(c));
        if (!lab_grid.empty()) starts.push_back(lab_grid.front().second);
        spent += static_cast<long>(lab_grid.size());
      }
      JointRefit fit;
      fit.joint_chi2 = std::numeric_limits<double>::infinity();
      const long per_start = std::max<long>(
          40, (options.candidate_evaluations - spent) / std::max<long>(1, starts.size()));
      for (const Eigen::VectorXd& point : starts) {
        if (cancel.cancelled()) break;
        JointRefit attempt =
            joint_refit(extended_objective, point, use_fp, static_cast<int>(per_start), cancel);
        spent += attempt.evaluations;
        if (attempt.theta.size() > 0 && attempt.joint_chi2 < fit.joint_chi2)
          fit = std::move(attempt);
      }
      if (fit.theta.size() == 0 || cancel.cancelled()) {
        trial.solved = false;
        return;
      }
      // The current model's defect correction does not hold for a new term that changes the
      // response's harmonics (a strong presliding or Stribeck term): the candidate gets its own
      // correction at its refitted θ (reference up to H = 31 here; the accepted model is settled
      // up to the full reference) and one more refit with it. Its σ stays the shared budget's, so
      // that the candidates' χ² remain comparable.
      EdcCostSettings& own = own_costs[slot];
      {
        EdcCostSettings reference = base_cost;
        reference.max_harmonics = std::min(options.cost.max_harmonics, 31);
        const SigmaBudget calibrated =
            EdcObjective::calibrate_budget(extended, data, reference, fit.theta);
        own.budget->correction_j = calibrated.correction_j;
        own.budget->correction_z1_m = calibrated.correction_z1_m;
        own.budget->correction_h2 = calibrated.correction_h2;
        own.budget->correction_h3 = calibrated.correction_h3;
      }
      if (!cancel.cancelled()) {
        const EdcObjective own_objective(extended, data, own);
        JointRefit again = joint_refit(own_objective, fit.theta, use_fp,
                                       static_cast<int>(options.candidate_evaluations / 2), cancel);
        if (again.theta.size() > 0) fit = std::move(again);
      }
      score_trial(trial, fit, evaluation, maps.response, static_cast<int>(c.free.size()), n, use_fp,
                  dispersion);
      forms[slot] = extended;
      const std::lock_guard lock(done_mutex);
      ++done;
      report(0.25 + 0.75 * (step + static_cast<double>(done) / order.size()) / options.max_steps);
    });
    if (cancel.cancelled()) break;  // an interrupted step accepts nothing

    // Finalists: every candidate with very strong joint evidence and at least 70 % of the best
    // one's (at most kFinalists) gets the longer refit before they are compared again. Short
    // refits from a large misfit stop at different distances from their optima, and a law that
    // mimics the true one (quadratic for cubic damping) can lead by a few per cent there.
    constexpr std::size_t kFinalists = 3;
    std::vector<std::size_t> ranked_slots;
    for (std::size_t slot = 0; slot < order.size(); ++slot) {
      if (record.trials[slot].solved && forms[slot]) ranked_slots.push_back(slot);
    }
    std::sort(ranked_slots.begin(), ranked_slots.end(), [&](std::size_t a, std::size_t b) {
      return record.trials[a].delta_bic_joint < record.trials[b].delta_bic_joint;
    });
    std::vector<std::size_t> finalists;
    for (std::size_t slot : ranked_slots) {
      const double joint = record.trials[slot].delta_bic_joint;
      if (finalists.size() < kFinalists && joint < -options.bic_threshold &&
          joint <= 0.7 * record.trials[ranked_slots.front()].delta_bic_joint) {
        finalists.push_back(slot);
      }
    }
    parallel_for(finalists.size(), options.threads, [&](std::size_t i) {
      CandidateTrial& trial = record.trials[finalists[i]];
      const ModelForm& extended = *forms[finalists[i]];
      const JointRefit fit =
          joint_refit(EdcObjective(extended, data, own_costs[finalists[i]]), trial.theta, use_fp,
                      static_cast<int>(options.accepted_evaluations), cancel);
      if (fit.theta.size() == 0 || !(fit.joint_chi2 < trial.joint_chi2) || !fit.evaluation.ok) {
        return;
      }
      score_trial(trial, fit, evaluation, maps.response, extended.size() - current.size(), n,
                  use_fp, dispersion);
    });
    if (cancel.cancelled()) break;
    std::size_t best = order.size();
    for (std::size_t slot : ranked_slots) {
      const CandidateTrial& t = record.trials[slot];
      if (best == order.size() || t.delta_bic_joint < record.trials[best].delta_bic_joint) {
        best = slot;
      }
    }
    // Accepted: very strong joint evidence, and the EDC itself is explained better (an effect
    // that helps the fingerprints while the EDC gets worse is not a missing damping or
    // stiffness law of this model).
    if (best == order.size() || !(record.trials[best].delta_bic_joint < -options.bic_threshold) ||
        !(record.trials[best].weighted_cost < evaluation.weighted_cost)) {
      result.steps.push_back(std::move(record));  // tried, nothing accepted
      result.steps.back().effect = "none";
      break;
    }
    const CandidateTrial& accepted = record.trials[best];
    theta = accepted.theta;
    current = forms[best]->with_initial(theta);
    settle();
    record.effect = accepted.effect;
    record.embodiment = accepted.embodiment;
    record.can_vanish = candidates[order[best]].can_vanish;
    record.strength_parameter = candidates[order[best]].free.front().name;
    record.evidence = accepted.evidence;
    record.delta_bic_joint = accepted.delta_bic_joint;
    record.cost_after_j = evaluation.cost_j;
    record.weighted_after = evaluation.weighted_cost;
    record.reduced_chi2_after = maps.reduced_chi2;
    record.delta_bic =
        (evaluation.weighted_cost - record.weighted_before) / dispersion +
        static_cast<double>(current.size() - form_size_before) * std::log(static_cast<double>(n));
    record.parameters_after = named(current, theta);
    accepted_effects.push_back(accepted.effect);
    result.steps.push_back(std::move(record));
  }
  // An effect accepted early can lose its part to effects accepted after it (a cubic damping
  // that stood in for a quadratic one and a presliding hysteresis together): its strength
  // vanishes in the final refit. It is withdrawn, and the verdict is the first effect that stands.
  for (DiagnosisStep& s : result.steps) {
    if (s.effect == "none") continue;
    if (!s.can_vanish) {
      if (result.verdict == "none") result.verdict = s.effect;
      continue;
    }
    for (int i = 0; i < current.size(); ++i) {
      const FreeParameter& p = current.parameters()[i];
      if (p.name != s.strength_parameter) continue;
      // A log-scale strength (a Dahl force, a presliding length) vanishes at its lower bound,
      // within a decade of it; a linear one at 0, within 1e-3 of its bound.
      const double scale = std::max(std::abs(p.lower), std::abs(p.upper));
      s.withdrawn = p.log_scale ? theta(i) <= 10.0 * p.lower : std::abs(theta(i)) <= 1e-3 * scale;
    }
    if (!s.withdrawn && result.verdict == "none") result.verdict = s.effect;
  }
  // A trailing "none" step records what was tried last; it is not an accepted effect.
  result.final_form = current;
  result.final_theta = theta;
  result.final_evaluation = evaluation;
  result.final_maps = maps;
  result.sigma_budget = sigma_budget_json(*objective);
  result.final_cost = cost;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.final_noise_reduced_chi2 = noise_level(current.size());
  result.gap_explained = maps.reduced_chi2 <= result.final_noise_reduced_chi2;
  result.largest_residual_levels = largest_residual_levels(maps, 3);
  if (deadline.expired()) {
    result.incomplete = true;
    result.message = "stopped at the " + std::to_string(options.max_seconds) +
                     " s limit: the steps completed before it stand, the rest was not tried";
  } else if (outer_cancel.cancelled()) {
    result.status = JobStatus::Cancelled;
    result.message = "cancelled";
  }
  if (!result.gap_explained && result.status == JobStatus::Ok) {
    if (!result.message.empty()) result.message += "; ";
    result.message += gap_open_message(result);
  }
  report(1.0);
  return result;
}

}  // namespace oscilab::analysis
