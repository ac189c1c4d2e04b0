#include "analysis/diagnosis/diagnosis.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "analysis/common/input_error.h"
#include "analysis/common/parallel_for.h"
#include "analysis/diagnosis/candidate_trial.h"
#include "analysis/diagnosis/diagnosis_progress.h"
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

// Whether a parameter other than the stiffness's sits within 1e-3 of a bound (unit cube).
bool at_a_bound(const ModelForm& form, const Eigen::VectorXd& theta) {
  const Eigen::VectorXd unit = form.to_unit(theta);
  for (int i = 0; i < form.size(); ++i) {
    if (!form.is_stiffness(i) && (unit(i) <= 1e-3 || unit(i) >= 1.0 - 1e-3)) return true;
  }
  return false;
}

}  // namespace

namespace {

// One diagnosis: the baseline, then steps of candidates until nothing is accepted or the model
// explains the data within its noise. The current model (form, θ, its shared σ budget, its
// evaluation and discrepancy maps) is what each step measures its candidates against.
class DiagnosisRun {
 public:
  DiagnosisRun(const CampaignAnalysis& campaign, const ModelForm& form,
               const DiagnosisOptions& options, const CancelToken& cancel,
               DiagnosisProgressTracker& progress)
      : campaign_(campaign),
        form_(form),
        options_(options),
        cancel_(cancel),
        progress_(progress),
        data_(edc_dataset(campaign)),
        n_(data_.level_count()),
        current_(form),
        use_fp_(options.use_fingerprints) {
    result_.excluded_levels = data_.excluded;
    base_cost_ = options.cost;
    base_cost_.cancel = cancel;  // the calibrations stop with the job
  }

  void baseline();
  // One step of the candidate search (1, 2 …); false when the search ends with it. A step whose
  // winner only found a deeper basin of the current model is run again from that basin, once.
  bool step(int number, bool may_rebase = true);
  // Withdraws accepted effects whose strength vanished and names the verdict.
  void withdraw_vanished();
  DiagnosisResult finish();

 private:
  double noise_level(int parameters) const {
    const int dof = std::max(1, n_ - parameters);
    return 1.0 + 3.0 * std::sqrt(2.0 / dof);
  }
  void settle();
  // The current model becomes `form` at θ, settled (a restart, a robust refit, a rebase or an
  // accepted candidate adopting its refit).
  void settle_at(const ModelForm& form, const Eigen::VectorXd& theta);
  void restart_at_bound();
  void refit_robustly();
  // The nested check of a winning candidate: true when the current model, refitted from the
  // winner's θ without its term, takes the term's evidence below the threshold or itself gains
  // more than the threshold (the refit is then the current model, settled).
  bool rebase_from(const ModelForm& extended, const CandidateTrial& winner, double dispersion);
  // The step's candidates with their fingerprint scores, best-ranked first; effects accepted
  // before are not offered again (stiffness powers share one term type).
  std::vector<std::pair<EffectCandidate, double>> ranked_candidates() const;
  // The slots of the solved trials by joint ΔBIC, best first, and of those the finalists: very
  // strong joint evidence and at least 70 % of the best one's (at most three).
  std::pair<std::vector<std::size_t>, std::vector<std::size_t>> finalists(
      const DiagnosisStep& record, const std::vector<TrialOutcome>& outcomes) const;
  // The trial in `slot` of the record (after its finalist's refit) becomes the current model.
  void accept(DiagnosisStep& record, std::size_t slot, const ModelForm& extended,
              const EffectCandidate& candidate, int form_size_before);

  const CampaignAnalysis& campaign_;
  const ModelForm& form_;
  const DiagnosisOptions& options_;
  const CancelToken& cancel_;
  DiagnosisProgressTracker& progress_;
  const EdcDataset data_;
  const int n_;
  EdcCostSettings base_cost_;
  DiagnosisResult result_;
  // The current model.
  ModelForm current_;
  Eigen::VectorXd theta_;
  EdcCostSettings cost_;
  std::shared_ptr<const EdcObjective> objective_;
  EdcEvaluation evaluation_;
  DiscrepancyMaps maps_;
  const bool use_fp_;
  std::vector<std::string> accepted_effects_;
};

// Baseline: the form as given, searched globally, its σ budget calibrated at the form's initial
// θ. An identified stiffness is held at its start (the slice's cubic or the model's) in the
// global search on the EDC, which barely sees it, and freed when the model is settled on the EDC
// and the fingerprints, which pin it.
void DiagnosisRun::baseline() {
  const auto start = std::chrono::steady_clock::now();
  const bool identified_stiffness = form_.identifies_stiffness();
  const ModelForm search_form =
      identified_stiffness ? form_.holding_stiffness(form_.initial()) : form_;
  const EdcObjective baseline_objective(search_form, data_, base_cost_);
  FitOptions fit_options;
  fit_options.max_evaluations = options_.baseline_evaluations;
  fit_options.seed = options_.seed;
  fit_options.threads = options_.threads;
  fit_options.compute_uncertainty = false;
  fit_options.check_truncation = false;
  progress_.phase(DiagnosisPhase::Baseline, 0, 0);
  result_.baseline = fit_edc(
      baseline_objective, fit_options,
      [this](const FitProgress& p) { progress_.baseline_search(p.evaluations); }, cancel_);
  result_.evaluations += result_.baseline.evaluations;
  theta_ = identified_stiffness ? form_.expand(result_.baseline.theta, form_.initial())
                                : result_.baseline.theta;
  current_ = form_.with_initial(theta_);
  progress_.phase(DiagnosisPhase::Settling, 0, result_.evaluations);
  settle();
  restart_at_bound();
  const auto robust_start = std::chrono::steady_clock::now();
  refit_robustly();
  const auto end = std::chrono::steady_clock::now();
  result_.baseline_robust_refit_seconds = std::chrono::duration<double>(end - robust_start).count();
  result_.baseline_seconds = std::chrono::duration<double>(end - start).count();
  result_.baseline.theta = theta_;
  result_.baseline.names = current_.names();
  result_.baseline.evaluation = evaluation_;
  result_.baseline_maps = maps_;
  result_.noise_reduced_chi2 = noise_level(current_.size());
  progress_.baseline_settled();
}

// Settling (settle_model): the σ budget calibrated at θ, the joint refit repeated while θ moves.
// The σ budget is then shared by every objective of the step, so that the χ² of the current
// model and of all its candidates are comparable. A candidate's gain is measured against the
// settled model, so that a baseline search that stopped short of its optimum (the paper's form
// has a weakly identified f_d(0), §5) does not credit an added term with the rest.
void DiagnosisRun::settle() {
  SettledModel settled = settle_model(current_, theta_, data_, campaign_, base_cost_, use_fp_,
                                      static_cast<int>(options_.candidate_evaluations), cancel_);
  result_.evaluations += settled.evaluations;
  current_ = std::move(settled.form);
  theta_ = std::move(settled.theta);
  cost_ = std::move(settled.cost);
  objective_ = std::move(settled.objective);
  evaluation_ = std::move(settled.evaluation);
  maps_ = std::move(settled.maps);
}

void DiagnosisRun::settle_at(const ModelForm& form, const Eigen::VectorXd& theta) {
  theta_ = theta;
  current_ = form.with_initial(theta_);
  settle();
}

// A baseline at a bound: the weakly identified f_d(0) of §5 (or another friction parameter) can
// be pushed onto its bound by a search that stopped in the wrong basin, and nothing after it
// recovers. Then the refit is restarted from space-filling points of the friction's unit cube
// (Halton, bases 2, 3, 5 …; the stiffness at its settled values) and the best is settled.
void DiagnosisRun::restart_at_bound() {
  if (cancel_.cancelled() || !at_a_bound(current_, theta_)) return;
  const double before = joint_chi2(evaluation_, maps_.response, use_fp_);
  JointRefit best;
  best.joint_chi2 = before;
  const Eigen::VectorXd unit = current_.to_unit(theta_);
  for (int k = 1; k <= kBoundRestarts && !cancel_.cancelled(); ++k) {
    Eigen::VectorXd start = unit;
    int dimension = 0;
    for (int i = 0; i < current_.size(); ++i) {
      if (!current_.is_stiffness(i)) start(i) = halton(k, kPrimes[dimension++ % kPrimes.size()]);
    }
    JointRefit fit = joint_refit(*objective_, current_.from_unit(start), use_fp_,
                                 static_cast<int>(options_.candidate_evaluations), cancel_);
    result_.evaluations += fit.evaluations;
    if (fit.theta.size() > 0 && fit.joint_chi2 < best.joint_chi2) best = std::move(fit);
  }
  ++result_.baseline_restarts;
  if (best.theta.size() > 0 && best.joint_chi2 < before) {
    settle_at(current_, best.theta);
    result_.baseline_restart_improved = true;
  }
}

// A baseline that does not explain the data may be held back by a few levels: a level just across
// a fold from the model's (measured on the lower branch where the model has already jumped) sits
// hundreds of σ off whatever θ does nearby, and the least-squares step pulls the whole θ towards
// it rather than crossing the fold (measured on a control: one level at −1 139 σ, the rest within
// 7 σ; there the budget's correction was itself a branch gap, SigmaBudget::branch_ambiguous, and
// the robust refit alone took χ²/ν 3·10⁴ to 16 in one run of two). A refit under the Cauchy loss of
// scale kCauchyScale σ lets the other levels place θ, and the plain refit from there keeps it when
// its χ² is lower.
void DiagnosisRun::refit_robustly() {
  constexpr double kCauchyScale = 3.0;
  if (cancel_.cancelled() || maps_.reduced_chi2 <= noise_level(current_.size())) return;
  const double before = joint_chi2(evaluation_, maps_.response, use_fp_);
  const int budget = static_cast<int>(options_.candidate_evaluations);
  // From the settled θ, and (with the stiffness identified) from it with K(z) back at the
  // records' slice: a settled stiffness can itself have moved into the wrong basin.
  std::vector<Eigen::VectorXd> starts = {theta_};
  if (form_.identifies_stiffness()) {
    Eigen::VectorXd measured = theta_;
    const Eigen::VectorXd initial = form_.initial();
    for (int i = 0; i < current_.size() && i < initial.size(); ++i) {
      if (current_.is_stiffness(i)) measured(i) = initial(i);
    }
    if (measured != theta_) starts.push_back(measured);
  }
  JointRefit best;
  best.joint_chi2 = before;
  for (const Eigen::VectorXd& start : starts) {
    if (cancel_.cancelled()) return;
    const JointRefit robust =
        joint_refit(*objective_, start, use_fp_, budget, cancel_, kCauchyScale);
    result_.evaluations += robust.evaluations;
    if (cancel_.cancelled() || robust.theta.size() == 0) return;
    JointRefit fit = joint_refit(*objective_, robust.theta, use_fp_, budget, cancel_);
    result_.evaluations += fit.evaluations;
    if (fit.theta.size() > 0 && fit.joint_chi2 < best.joint_chi2) best = std::move(fit);
  }
  result_.baseline_robust_refit = true;
  if (best.theta.size() == 0) return;
  settle_at(current_, best.theta);
  result_.baseline_robust_refit_improved = true;
}

std::vector<std::pair<EffectCandidate, double>> DiagnosisRun::ranked_candidates() const {
  std::vector<std::pair<EffectCandidate, double>> ranked;
  for (EffectCandidate& c : effect_candidates(current_, data_)) {
    if (std::find(accepted_effects_.begin(), accepted_effects_.end(), c.effect) !=
        accepted_effects_.end()) {
      continue;
    }
    const double score = fingerprint_score(c, maps_);
    ranked.emplace_back(std::move(c), score);
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.second < b.second; });
  return ranked;
}

// A candidate's refit frees every parameter, so it can reach a deeper basin of the current
// model's own parameters than the current model's search did (the paper's weakly identified
// f_d(0), a stiffness started from its slice; measured on a control: a quintic stiffness took
// χ²/ν 59 to 0.16, and the form itself, refitted from there, reaches 0.16). The current model is
// refitted from the winner's θ without the term; what the term adds beyond that is its own.
bool DiagnosisRun::rebase_from(const ModelForm& extended, const CandidateTrial& winner,
                               double dispersion) {
  const std::vector<std::string> names = extended.names();
  Eigen::VectorXd start = theta_;
  for (int i = 0; i < current_.size(); ++i) {
    const auto found = std::find(names.begin(), names.end(), current_.parameters()[i].name);
    if (found != names.end()) start(i) = winner.theta(found - names.begin());
  }
  JointRefit fit = joint_refit(*objective_, current_.clamp(start), use_fp_,
                               static_cast<int>(options_.candidate_evaluations), cancel_);
  result_.evaluations += fit.evaluations;
  const double current_joint = joint_chi2(evaluation_, maps_.response, use_fp_);
  if (cancel_.cancelled() || fit.theta.size() == 0 || !(fit.joint_chi2 < current_joint)) {
    return false;
  }
  // The term's own gain stands, and the current model's candidates were measured against nearly
  // its best: accepted as it is. A deeper basin found otherwise becomes the current model, and
  // the step's candidates are measured against it again.
  const double basin_gain = (current_joint - fit.joint_chi2) / dispersion;
  const double rebased_bic = winner.delta_bic_joint + basin_gain;
  if (rebased_bic < -options_.bic_threshold && basin_gain <= options_.bic_threshold) return false;
  settle_at(current_, fit.theta);
  ++result_.rebases;
  if (accepted_effects_.empty()) {  // the baseline itself moved
    result_.baseline.theta = theta_;
    result_.baseline.evaluation = evaluation_;
    result_.baseline_maps = maps_;
  }
  return true;
}

bool DiagnosisRun::step(int number, bool may_rebase) {
  if (maps_.reduced_chi2 <= noise_level(current_.size())) return false;  // explained
  const std::vector<std::pair<EffectCandidate, double>> ranked = ranked_candidates();
  DiagnosisStep record;
  const int form_size_before = current_.size();
  // Quasi-likelihood after the first accepted effect: the misfit the extended model leaves (its
  // reduced joint χ², at least 1) inflates σ, so a further term must explain a share of what is
  // left, not a few per cent of a large misfit. The first step compares at the stated σ: the
  // baseline may be far from the data because an effect is missing.
  record.dispersion =
      accepted_effects_.empty()
          ? 1.0
          : std::max(1.0, joint_reduced_chi2(evaluation_, maps_, use_fp_, n_, current_.size()));
  record.maps_before = maps_;
  record.cost_before_j = evaluation_.cost_j;
  record.weighted_before = evaluation_.weighted_cost;
  record.reduced_chi2_before = maps_.reduced_chi2;
  const TrialContext context{form_,
                             current_,
                             theta_,
                             data_,
                             cost_,
                             base_cost_,
                             evaluation_,
                             maps_.response,
                             use_fp_,
                             n_,
                             record.dispersion,
                             options_.candidate_evaluations,
                             options_.cost.max_harmonics};
  progress_.candidates(number, static_cast<int>(ranked.size()), result_.evaluations);
  progress_.set_trial_budget(trial_budget(options_.candidate_evaluations));
  std::vector<TrialOutcome> outcomes(ranked.size());
  parallel_for(ranked.size(), options_.threads, [&](std::size_t slot) {
    const EffectCandidate& c = ranked[slot].first;
    outcomes[slot] = try_candidate(
        c, ranked[slot].second, context,
        [&, slot](long spent) { progress_.candidate_spent(slot, spent); }, cancel_);
    progress_.candidate_done(slot, candidate_label(c.effect, c.embodiment));
  });
  if (cancel_.cancelled()) return false;  // an interrupted step accepts nothing
  record.trials.resize(outcomes.size());
  for (std::size_t slot = 0; slot < outcomes.size(); ++slot) {
    record.trials[slot] = outcomes[slot].trial;
  }

  // Finalists get the longer refit before they are compared again: short refits from a large
  // misfit stop at different distances from their optima, and a law that mimics the true one
  // (quadratic for cubic damping) can lead by a few per cent there.
  const auto [ranked_slots, chosen] = finalists(record, outcomes);
  progress_.phase(DiagnosisPhase::Finalists, number, result_.evaluations);
  parallel_for(chosen.size(), options_.threads, [&](std::size_t i) {
    const std::size_t slot = chosen[i];
    refine_finalist(record.trials[slot], *outcomes[slot].form, outcomes[slot].own_cost, context,
                    options_.accepted_evaluations, cancel_);
  });
  if (cancel_.cancelled()) return false;
  std::optional<std::size_t> best;
  for (std::size_t slot : ranked_slots) {
    if (!best || record.trials[slot].delta_bic_joint < record.trials[*best].delta_bic_joint) {
      best = slot;
    }
  }
  // Accepted: very strong joint evidence, and the EDC itself is explained better (an effect that
  // helps the fingerprints while the EDC gets worse is not a missing damping or stiffness law of
  // this model).
  if (!best || !(record.trials[*best].delta_bic_joint < -options_.bic_threshold) ||
      !(record.trials[*best].weighted_cost < evaluation_.weighted_cost)) {
    record.effect = "none";  // tried, nothing accepted
    result_.steps.push_back(std::move(record));
    return false;
  }
  if (may_rebase && rebase_from(*outcomes[*best].form, record.trials[*best], record.dispersion)) {
    return step(number, false);  // the candidates again, against the deeper basin
  }
  accept(record, *best, *outcomes[*best].form, ranked[*best].first, form_size_before);
  return true;
}

std::pair<std::vector<std::size_t>, std::vector<std::size_t>> DiagnosisRun::finalists(
    const DiagnosisStep& record, const std::vector<TrialOutcome>& outcomes) const {
  constexpr std::size_t kFinalists = 3;
  std::vector<std::size_t> ranked;
  for (std::size_t slot = 0; slot < outcomes.size(); ++slot) {
    if (record.trials[slot].solved && outcomes[slot].form) ranked.push_back(slot);
  }
  std::sort(ranked.begin(), ranked.end(), [&](std::size_t a, std::size_t b) {
    return record.trials[a].delta_bic_joint < record.trials[b].delta_bic_joint;
  });
  std::vector<std::size_t> chosen;
  for (std::size_t slot : ranked) {
    const double joint = record.trials[slot].delta_bic_joint;
    if (chosen.size() < kFinalists && joint < -options_.bic_threshold &&
        joint <= 0.7 * record.trials[ranked.front()].delta_bic_joint) {
      chosen.push_back(slot);
    }
  }
  return {ranked, chosen};
}

// The accepted candidate becomes the current model, settled; the step records how the model
// changed.
void DiagnosisRun::accept(DiagnosisStep& record, std::size_t slot, const ModelForm& extended,
                          const EffectCandidate& candidate, int form_size_before) {
  const CandidateTrial accepted = record.trials[slot];
  progress_.phase(DiagnosisPhase::Accepting, static_cast<int>(result_.steps.size()) + 1,
                  result_.evaluations, candidate_label(accepted.effect, accepted.embodiment));
  settle_at(extended, accepted.theta);
  record.effect = accepted.effect;
  record.embodiment = accepted.embodiment;
  record.can_vanish = candidate.can_vanish;
  record.strength_parameter = candidate.free.front().name;
  record.evidence = accepted.evidence;
  record.delta_bic_joint = accepted.delta_bic_joint;
  record.cost_after_j = evaluation_.cost_j;
  record.weighted_after = evaluation_.weighted_cost;
  record.reduced_chi2_after = maps_.reduced_chi2;
  record.delta_bic =
      (evaluation_.weighted_cost - record.weighted_before) / record.dispersion +
      static_cast<double>(current_.size() - form_size_before) * std::log(static_cast<double>(n_));
  record.parameters_after = current_.named(theta_);
  accepted_effects_.push_back(accepted.effect);
  result_.steps.push_back(std::move(record));
}

// An effect accepted early can lose its part to effects accepted after it (a cubic damping that
// stood in for a quadratic one and a presliding hysteresis together): its strength vanishes in
// the final refit. It is withdrawn, and the verdict is the first effect that stands. A trailing
// "none" step records what was tried last; it is not an accepted effect.
void DiagnosisRun::withdraw_vanished() {
  for (DiagnosisStep& s : result_.steps) {
    if (s.effect == "none") continue;
    if (!s.can_vanish) {
      if (result_.verdict == "none") result_.verdict = s.effect;
      continue;
    }
    for (int i = 0; i < current_.size(); ++i) {
      const FreeParameter& p = current_.parameters()[i];
      if (p.name != s.strength_parameter) continue;
      // A log-scale strength (a Dahl force, a presliding length) vanishes at its lower bound,
      // within a decade of it; a linear one at 0, within 1e-3 of its bound.
      const double scale = std::max(std::abs(p.lower), std::abs(p.upper));
      s.withdrawn = p.log_scale ? theta_(i) <= 10.0 * p.lower : std::abs(theta_(i)) <= 1e-3 * scale;
    }
    if (!s.withdrawn && result_.verdict == "none") result_.verdict = s.effect;
  }
}

// The final model and how well it explains the data.
DiagnosisResult DiagnosisRun::finish() {
  result_.final_form = current_;
  result_.final_theta = theta_;
  result_.final_evaluation = evaluation_;
  result_.final_maps = maps_;
  result_.sigma_budget = sigma_budget_json(*objective_);
  result_.final_cost = cost_;
  result_.final_noise_reduced_chi2 = noise_level(current_.size());
  result_.gap_explained = maps_.reduced_chi2 <= result_.final_noise_reduced_chi2;
  result_.largest_residual_levels = largest_residual_levels(maps_, 3);
  return std::move(result_);
}

}  // namespace

DiagnosisResult diagnose(const CampaignAnalysis& campaign, const ModelForm& form,
                         const DiagnosisOptions& options, const DiagnosisProgressFn& progress,
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
  DiagnosisProgressTracker tracker(progress, options);
  DiagnosisRun run(campaign, form, options, cancel, tracker);
  run.baseline();
  for (int step = 1; step <= options.max_steps && !cancel.cancelled(); ++step) {
    if (!run.step(step)) break;
  }
  run.withdraw_vanished();
  DiagnosisResult result = run.finish();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  tracker.phase(DiagnosisPhase::Done, 0, result.evaluations);
  return result;
}

}  // namespace oscilab::analysis
