#include "analysis/design/adaptive_test.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "analysis/common/input_error.h"
#include "analysis/diagnosis/effect_candidates.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_fit.h"

namespace oscilab::analysis {
namespace {

double elapsed_s(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The runs made so far, each analysed as offline as it comes in.
struct Measured {
  CampaignAnalysis campaign;
  std::vector<MeasurementChannels> runs;
  double shaker_time_s = 0.0;

  void add(LevelRun run) {
    campaign.records.push_back(analyze_record(run.channels, campaign.settings));
    runs.push_back(std::move(run.channels));
    shaker_time_s += run.shaker_s;
  }
};

// The proposal and the stop rule's answer at this point. The proposal comes first: what the best
// setting could still tell apart is part of the stop rule.
AdaptiveDecision decide(const std::vector<ModelHypothesis>& hypotheses,
                        const AdaptiveTestOptions& options, const NextPointOptions& next,
                        const AdmissibleSettings& settings, double shaker_time_s,
                        int adaptive_levels, const CancelToken& cancel) {
  AdaptiveDecision d;
  d.decision = stop_decision(hypotheses, options.stop, shaker_time_s);
  if (!d.decision.stop && adaptive_levels < options.max_levels) {
    const auto proposing = std::chrono::steady_clock::now();
    d.next = propose_next_point(hypotheses, settings, next, {}, cancel);
    d.proposal_s = elapsed_s(proposing);
    if (d.next.found) {
      d.decision =
          stop_decision(hypotheses, options.stop, shaker_time_s, d.next.max_discrimination);
    }
  }
  if (!d.decision.stop && adaptive_levels >= options.max_levels) {
    d.decision.stop = true;
    d.decision.reason = "max levels: " + std::to_string(options.max_levels) +
                        " adaptive levels run; " + d.decision.reason;
  } else if (!d.decision.stop && !d.next.found) {
    d.decision.stop = true;
    d.decision.reason = "no admissible setting: " + d.next.message + "; " + d.decision.reason;
  }
  return d;
}

}  // namespace

void AdaptiveTestOptions::validate() const {
  settings.validate();
  if (pilot_levels_n.empty()) throw InputError("pilot_levels_n: at least one level");
  for (double f0 : pilot_levels_n) {
    if (!(f0 > 0.0) || !std::isfinite(f0)) {
      throw InputError("pilot_levels_n: " + std::to_string(f0) + " is not a positive force in N");
    }
  }
  if (!(stop.leader_weight > 0.5 && stop.leader_weight < 1.0)) {
    throw InputError("stop.leader_weight: must be between 0.5 and 1");
  }
  if (!(stop.min_discrimination >= 0.0) || !std::isfinite(stop.min_discrimination)) {
    throw InputError("stop.min_discrimination: must be >= 0");
  }
  if (!(stop.budget_s > 0.0) || !std::isfinite(stop.budget_s)) {
    throw InputError("stop.budget_s: must be a positive number of s");
  }
  if (max_levels < 1) throw InputError("max_levels: must be at least 1");
  if (hypotheses.global_evaluations < 0 || hypotheses.global_evaluations > kMaxFitEvaluations) {
    throw InputError("hypotheses.global_evaluations: must be 0 to 10^7");
  }
  if (hypotheses.initial_evaluations < 10) {
    throw InputError("hypotheses.initial_evaluations: must be at least 10");
  }
  if (hypotheses.refit_evaluations < 10) {
    throw InputError("hypotheses.refit_evaluations: must be at least 10");
  }
  if (hypotheses.threads < 0 || hypotheses.threads > kMaxThreads) {
    throw InputError("hypotheses.threads: " + std::to_string(hypotheses.threads) +
                     " must be 0 (all cores) to " + std::to_string(kMaxThreads));
  }
  const std::vector<std::string>& vocabulary = effect_vocabulary();
  for (const std::string& e : hypotheses.effects) {
    if (e == "none" || std::find(vocabulary.begin(), vocabulary.end(), e) == vocabulary.end()) {
      throw InputError("hypotheses.effects: unknown effect \"" + e + "\"");
    }
  }
}

void validate_as_named(const AdaptiveTestOptions& options,
                       const std::vector<std::pair<std::string, std::string>>& names) {
  try {
    options.validate();
  } catch (const InputError& error) {
    const std::string message = error.what();
    const std::size_t colon = message.find(": ");
    for (const auto& [field, name] : names) {
      if (colon != std::string::npos && message.compare(0, colon, field) == 0) {
        throw InputError(name + message.substr(colon));
      }
    }
    throw;
  }
}

AdaptiveTestResult run_adaptive_test(LevelRunner& runner, const AdaptiveTestOptions& options,
                                     const DecisionFn& on_decision, const ProgressFn& progress,
                                     const CancelToken& cancel, const ProposalGate& gate) {
  options.validate();
  const auto started = std::chrono::steady_clock::now();
  AdaptiveTestResult result;
  Measured measured;
  // The loop's share of the progress, then the final diagnosis's.
  constexpr double kLoopShare = 0.8;
  const auto report_progress = [&] {
    if (progress) {
      progress(kLoopShare * std::min(1.0, measured.shaker_time_s / options.stop.budget_s));
    }
  };
  const auto finish = [&](JobStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    result.runs = std::move(measured.runs);
    result.shaker_time_s = measured.shaker_time_s;
    result.seconds = elapsed_s(started);
    return std::move(result);
  };

  // The pilot: a short sweep up in each well, enough for a baseline to start from.
  AdmissibleSettings settings = options.settings;
  bool current_positive = settings.positive_well;
  for (bool positive : {true, false}) {
    if (positive ? !settings.positive_well : !settings.negative_well) continue;
    if (cancel.cancelled()) return finish(JobStatus::Cancelled, "cancelled during the pilot");
    if (!measured.runs.empty()) measured.shaker_time_s += settings.well_change_s;
    measured.add(runner.run(options.pilot_levels_n, settings.freq_hz, positive, "pilot"));
    current_positive = positive;
    report_progress();
  }
  result.pilot_levels_per_well = static_cast<int>(options.pilot_levels_n.size());
  require_measured_levels(measured.campaign);

  // Every hypothesis, the baseline first, by a global search on the pilot from the form's start.
  const PreparedFit prepared = prepare_fit(measured.campaign, options.setup);
  HypothesisOptions hypothesis_options = options.hypotheses;
  hypothesis_options.cost = prepared.cost;
  const ModelForm& start_form = prepared.objective->form();
  result.hypotheses =
      initial_hypotheses(start_form, start_form.initial(), measured.campaign,
                         edc_dataset(measured.campaign), hypothesis_options, {}, cancel);

  double refit_s = 0.0;
  NextPointOptions next = options.next;  // with the settings the operator skips
  for (int index = 0;; ++index) {
    if (cancel.cancelled()) return finish(JobStatus::Cancelled, "cancelled");
    settings.current_positive_well = current_positive;
    AdaptiveDecision d = decide(result.hypotheses, options, next, settings, measured.shaker_time_s,
                                result.adaptive_levels, cancel);
    if (cancel.cancelled()) return finish(JobStatus::Cancelled, "cancelled");
    d.index = index;
    d.time_s = elapsed_s(started);
    d.shaker_time_s = measured.shaker_time_s;
    d.levels = edc_dataset(measured.campaign).level_count();
    d.refit_s = refit_s;
    result.decision = d.decision;
    if (on_decision) on_decision(d, result.hypotheses);
    if (d.decision.stop) break;

    const SettingScore& p = d.next.best;
    const ProposalAnswer answer = gate ? gate(d) : ProposalAnswer::Run;
    if (cancel.cancelled()) return finish(JobStatus::Cancelled, "cancelled");
    if (answer == ProposalAnswer::Skip) {
      next.skipped.push_back({p.f0_n, p.freq_hz, p.positive_well});
      refit_s = 0.0;  // no level, so no refit before the next decision
      continue;
    }
    if (answer == ProposalAnswer::Stop) {
      result.decision.stop = true;
      result.decision.decided = false;
      result.decision.reason = "stopped by the operator; " + result.decision.reason;
      break;
    }
    if (p.positive_well != current_positive) measured.shaker_time_s += settings.well_change_s;
    measured.add(runner.run({p.f0_n}, p.freq_hz, p.positive_well, "level"));
    current_positive = p.positive_well;
    ++result.adaptive_levels;
    report_progress();
    const auto refitting = std::chrono::steady_clock::now();
    refit_hypotheses(result.hypotheses, edc_dataset(measured.campaign), hypothesis_options, {},
                     cancel);
    refit_s = elapsed_s(refitting);
  }
  result.levels = edc_dataset(measured.campaign).level_count();
  if (!options.final_diagnosis) return finish(JobStatus::Ok, result.decision.reason);

  // The final diagnosis: the same as `diagnose` on the recordings made.
  const CampaignAnalysis campaign = analyze_campaign(measured.runs, PipelineSettings{});
  const ModelForm form = fit_form(campaign, options.setup, result.notes);
  DiagnosisOptions diagnosis_options = options.diagnosis;
  diagnosis_options.cost = options.setup.cost;
  result.diagnosis = diagnose(
      campaign, form, diagnosis_options,
      [&](const DiagnosisProgress& p) {
        if (progress) progress(kLoopShare + (1.0 - kLoopShare) * p.fraction);
      },
      cancel);
  result.diagnosed = result.diagnosis.status != JobStatus::Cancelled;
  if (!result.diagnosed) return finish(JobStatus::Cancelled, "cancelled during the diagnosis");
  return finish(JobStatus::Ok, result.decision.reason);
}

std::string AdaptiveTestResult::leader() const {
  return decision.leader >= 0 ? hypotheses[static_cast<std::size_t>(decision.leader)].effect
                              : "none";
}

}  // namespace oscilab::analysis
