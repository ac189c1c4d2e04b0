// `oscilab-cli adaptive-test --source rig --rig-model MODEL.json --out DIR`: a stepped-sine test
// that chooses its own levels. A pilot sweep in each well, then a loop: weigh the baseline and
// the candidate effects (BIC weights of warm refits), stop when a leader is clear at the noise or
// the shaker time is spent, otherwise propose the setting that best tells the plausible models
// apart per second of shaker time, run it on the virtual rig, analyse it as offline, repeat. The
// recordings, a decision log (one JSON line per decision) and the final diagnosis report.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "analysis/common/input_error.h"
#include "analysis/design/model_hypothesis.h"
#include "analysis/design/model_weights.h"
#include "analysis/design/next_point.h"
#include "analysis/diagnosis/campaign_fit.h"
#include "analysis/diagnosis/diagnosis.h"
#include "analysis/diagnosis/effect_candidates.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/model/model_json.h"
#include "analysis/pipeline/offline_analysis.h"
#include "app/cli/commands.h"
#include "app/cli/cost_options.h"
#include "app/cli/option_parsing.h"
#include "app/cli/output_files.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/recording/recording.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::cli {
namespace {

struct AdaptiveOptions {
  std::string source = "rig";
  std::string rig_model;
  std::string model = "paper";
  std::string stiffness = "identified";
  std::string out_dir;
  double freq_hz = 9.0;
  double freq_span_hz = 0.0;
  double freq_step_hz = 0.25;
  std::string f0 = "0.2:2.7";
  double f0_step_n = 0.1;
  std::string wells = "both";
  std::string pilot = "0.2,1.0,1.8,2.7";
  double hold_s = 10.0;
  double ramp_s = 1.0;
  double lead_in_s = 2.5;
  double well_change_s = 10.0;
  double budget_s = 520.0;
  double leader_weight = 0.99;
  double min_discrimination = 1.0;
  int max_levels = 40;
  std::string effects;
  long global_evaluations = 400;
  int initial_evaluations = 400;
  int refit_evaluations = 300;
  unsigned long long seed = 1;
  int threads = 0;
  CostOptions cost;
  double max_seconds = 120.0;
};

double elapsed_s(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void validate(const AdaptiveOptions& o) {
  if (o.source != "rig") {
    throw InputError("--source " + o.source +
                     ": only rig (the virtual rig) drives an adaptive test in this version");
  }
  if (o.rig_model.empty()) throw InputError("--rig-model: required with --source rig");
  const auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  const auto non_negative = [](double x) { return x >= 0.0 && std::isfinite(x); };
  if (!positive(o.freq_hz)) throw InputError("--freq: must be a positive number of Hz");
  if (!non_negative(o.freq_span_hz) || !positive(o.freq_step_hz) ||
      !(o.freq_hz - o.freq_span_hz > 0.0)) {
    throw InputError("--freq-span, --freq-step: the range must stay above 0 Hz, step > 0");
  }
  if (!positive(o.f0_step_n)) throw InputError("--f0-step: must be a positive number of N");
  if (!positive(o.hold_s) || !non_negative(o.ramp_s) || !(o.ramp_s < o.hold_s)) {
    throw InputError("--hold, --ramp: hold must be positive and longer than the ramp");
  }
  if (!non_negative(o.lead_in_s) || !non_negative(o.well_change_s)) {
    throw InputError("--lead-in, --well-change: must be >= 0 s");
  }
  if (!positive(o.budget_s)) throw InputError("--budget: must be a positive number of s");
  if (!(o.leader_weight > 0.5 && o.leader_weight < 1.0)) {
    throw InputError("--leader-weight: must be between 0.5 and 1");
  }
  if (!(o.min_discrimination >= 0.0) || !std::isfinite(o.min_discrimination)) {
    throw InputError("--min-discrimination: must be >= 0");
  }
  if (o.max_levels < 1) throw InputError("--max-levels: must be at least 1");
  if (o.global_evaluations < 0 || o.global_evaluations > analysis::kMaxFitEvaluations ||
      o.refit_evaluations < 10 || o.initial_evaluations < 10) {
    throw InputError(
        "--global-evaluations: 0 to 10^7; --initial-evaluations, --refit-evaluations: >= 10");
  }
  if (o.threads < 0 || o.threads > analysis::kMaxThreads) {
    throw InputError("--threads: " + std::to_string(o.threads) + " must be 0 (all cores) to " +
                     std::to_string(analysis::kMaxThreads));
  }
  if (!(o.max_seconds >= 0.0)) throw InputError("--max-seconds: must be >= 0");
}

// The admissible f0 range "A:B".
std::pair<double, double> parse_range(const std::string& text, const std::string& option) {
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() != 2) throw InputError(option + ": \"" + text + "\" is not A:B");
  const double a = parse_number(parts[0], option), b = parse_number(parts[1], option);
  if (!(a > 0.0) || !(b >= a)) throw InputError(option + ": need 0 < A <= B, got " + text);
  return {a, b};
}

// One run of the virtual rig, written and analysed as offline.
struct Runner {
  const analysis::Model& truth;
  const AdaptiveOptions& o;
  std::string out_dir;
  std::vector<analysis::MeasurementChannels> channels;
  std::vector<std::string> paths;
  analysis::CampaignAnalysis campaign;
  double shaker_time_s = 0.0;
  int runs = 0;

  void run(const std::vector<double>& levels, double freq_hz, bool positive, const char* what) {
    analysis::SteppedSineSchedule schedule;
    schedule.frequency_hz = freq_hz;
    schedule.levels_n = levels;
    schedule.hold_s = o.hold_s;
    schedule.ramp_s = o.ramp_s;
    schedule.lead_in_s = o.lead_in_s;
    daq::RigSpec spec;
    spec.positive_well = positive;
    spec.seed = o.seed * 1000 + static_cast<std::uint64_t>(runs);
    const daq::RigRecording rig = daq::record_stepped_sine(truth, schedule, spec);
    if (rig.status != analysis::TimeSimulator::Status::Ok) {
      throw InputError("virtual rig: " + rig.message);
    }
    char name[96];
    std::snprintf(name, sizeof name, "%02d_%s_%s.wav", runs, what,
                  positive ? "positive" : "negative");
    const std::string path = out_dir + "/recordings/" + name;
    daq::write_recording(rig.recording, path);
    channels.push_back(daq::measurement_channels(rig.recording));
    channels.back().name = name;
    campaign.records.push_back(analysis::analyze_record(channels.back(), campaign.settings));
    paths.push_back(path);
    shaker_time_s += schedule.duration_s();
    ++runs;
  }
};

nlohmann::json weights_json(const std::vector<analysis::ModelHypothesis>& h) {
  nlohmann::json out = nlohmann::json::object();
  for (const analysis::ModelHypothesis& x : h) out[x.label()] = x.weight;
  return out;
}

nlohmann::json chi2_json(const std::vector<analysis::ModelHypothesis>& h) {
  nlohmann::json out = nlohmann::json::object();
  for (const analysis::ModelHypothesis& x : h) {
    out[x.label()] = {{"edc", x.edc_chi2},
                      {"joint", x.joint_chi2},
                      {"bic", x.bic},
                      {"parameters", x.parameters()},
                      {"solved", x.solved}};
    if (!x.message.empty()) out[x.label()]["message"] = x.message;
  }
  return out;
}

nlohmann::json setting_json(const analysis::SettingScore& s) {
  return {{"f0_n", s.f0_n},
          {"freq_hz", s.freq_hz},
          {"well", s.positive_well ? "positive" : "negative"},
          {"admissible", s.admissible},
          {"criterion", s.criterion},
          {"criterion_per_s", s.criterion_per_s},
          {"shaker_s", s.shaker_s}};
}

// The settings the loop may choose from: the f0 grid, the frequencies around --freq, the wells,
// and what each costs in shaker time.
analysis::AdmissibleSettings admissible_settings(const AdaptiveOptions& o) {
  analysis::AdmissibleSettings settings;
  std::tie(settings.f0_min_n, settings.f0_max_n) = parse_range(o.f0, "--f0");
  settings.f0_step_n = o.f0_step_n;
  settings.freq_hz = o.freq_hz;
  settings.freq_span_hz = o.freq_span_hz;
  settings.freq_step_hz = o.freq_step_hz;
  settings.positive_well = o.wells != "negative";
  settings.negative_well = o.wells != "positive";
  settings.dwell_s = o.hold_s;
  settings.settling_s = o.lead_in_s;
  settings.well_change_s = o.well_change_s;
  settings.validate();
  return settings;
}

// One line of decisions.jsonl: the weights and fits after a level, the stop rule's answer and,
// when the test goes on, the proposal with every setting's score.
nlohmann::json decision_line(int decision_index, double time_s, double shaker_time_s, int levels,
                             const std::vector<analysis::ModelHypothesis>& hypotheses,
                             const analysis::StopDecision& decision,
                             const analysis::NextPoint& next, double proposal_s, double refit_s) {
  nlohmann::json line = {
      {"decision", decision_index},
      {"time_s", time_s},
      {"shaker_time_s", shaker_time_s},
      {"levels", levels},
      {"weights", weights_json(hypotheses)},
      {"fits", chi2_json(hypotheses)},
      {"leader",
       decision.leader >= 0 ? hypotheses[static_cast<std::size_t>(decision.leader)].label() : ""},
      {"leader_weight", decision.leader_weight},
      {"reduced_chi2", decision.reduced_chi2},
      {"noise_reduced_chi2", decision.noise_reduced_chi2},
      {"max_discrimination", next.found ? next.max_discrimination : 0.0},
      {"proposal_s", proposal_s},
      {"stop", decision.stop}};
  line["refit_s"] = refit_s;
  line["reason"] = decision.stop ? decision.reason : next.reason;
  if (!decision.stop) {
    line["proposal"] = setting_json(next.best);
    nlohmann::json scores = nlohmann::json::array();
    for (const analysis::SettingScore& s : next.settings) scores.push_back(setting_json(s));
    line["scores"] = scores;
  }
  return line;
}

// The final diagnosis, the same as `diagnose` on the recordings made, and report.json (and
// final_model.json) with the loop's own answer beside it.
void diagnose_and_report(const Runner& rig, const analysis::FitSetup& setup,
                         const std::vector<analysis::ModelHypothesis>& hypotheses,
                         const analysis::StopDecision& decision, std::size_t pilot_levels,
                         int adaptive_levels, const AdaptiveOptions& o,
                         std::chrono::steady_clock::time_point started) {
  // The final diagnosis: the same as `diagnose` on the recordings made.
  const analysis::CampaignAnalysis campaign =
      analysis::analyze_campaign(rig.channels, analysis::PipelineSettings{});
  std::vector<std::string> notes;
  const analysis::ModelForm form = analysis::fit_form(campaign, setup, notes);
  analysis::DiagnosisOptions diagnosis_options;
  diagnosis_options.cost = setup.cost;
  diagnosis_options.max_seconds = o.max_seconds;
  diagnosis_options.seed = o.seed;
  diagnosis_options.threads = o.threads;
  const analysis::DiagnosisResult result = analysis::diagnose(campaign, form, diagnosis_options);
  nlohmann::json report = analysis::diagnosis_report_json(result, rig.paths);
  report["notes"] = notes;
  report["shaker_time_s"] = rig.shaker_time_s;
  const int levels = analysis::edc_dataset(campaign).level_count();
  // The loop's own answer beside the diagnosis's: on a few levels a diagnosis's candidate refits,
  // started from its baseline, can miss a fit the loop's global searches found.
  const std::string leader =
      decision.leader >= 0 ? hypotheses[static_cast<std::size_t>(decision.leader)].effect : "none";
  report["adaptive_test"] = {{"levels", levels},
                             {"pilot_levels_per_well", pilot_levels},
                             {"adaptive_levels", adaptive_levels},
                             {"decided", decision.decided},
                             {"stop_reason", decision.reason},
                             {"leader", leader},
                             {"leader_reduced_chi2", decision.reduced_chi2},
                             {"agrees_with_diagnosis", leader == result.verdict},
                             {"weights", weights_json(hypotheses)},
                             {"seconds", elapsed_s(started)}};
  OutputFiles outputs;
  outputs.write(o.out_dir + "/report.json",
                [&](std::ostream& out) { out << report.dump(2) << '\n'; });
  if (result.final_form) {
    const nlohmann::json model = result.final_form->build(result.final_theta).to_json();
    outputs.write(o.out_dir + "/final_model.json",
                  [&](std::ostream& out) { out << model.dump(2) << '\n'; });
  }
  outputs.commit();
  std::printf("verdict: %s, shaker time %.1f s over %d level(s) (%d adaptive), %.1f s\n",
              result.verdict.c_str(), rig.shaker_time_s, levels, adaptive_levels,
              elapsed_s(started));
  if (leader != result.verdict) {
    std::printf(
        "note: the adaptive test's leader is %s (weight %.4f, chi2/dof %.3g); the diagnosis of "
        "the same recordings says %s\n",
        leader.c_str(), decision.leader_weight, decision.reduced_chi2, result.verdict.c_str());
  }
  std::printf("recordings, decisions.jsonl and report.json written to %s/\n", o.out_dir.c_str());
}

void run(const AdaptiveOptions& o) {
  validate(o);
  const auto started = std::chrono::steady_clock::now();
  const analysis::Model truth = analysis::model_from_spec(o.rig_model);
  analysis::AdmissibleSettings settings = admissible_settings(o);
  std::vector<double> pilot = parse_levels(o.pilot, "--pilot");
  std::vector<std::string> effects;
  if (!o.effects.empty()) {
    effects = split(o.effects, ',');
    const auto& vocabulary = analysis::effect_vocabulary();
    for (const std::string& e : effects) {
      if (std::find(vocabulary.begin(), vocabulary.end(), e) == vocabulary.end() || e == "none") {
        throw InputError("--effects: unknown effect \"" + e + "\"");
      }
    }
  }
  analysis::FitSetup setup;
  setup.base_model = analysis::model_from_spec(o.model);
  setup.stiffness = analysis::parse_stiffness_source(o.stiffness, "--stiffness");
  setup.cost = cost_settings(o.cost);

  std::error_code error;
  std::filesystem::create_directories(o.out_dir + "/recordings", error);
  if (error) throw InputError(o.out_dir + ": cannot create: " + error.message());
  std::ofstream log(o.out_dir + "/decisions.jsonl");
  if (!log) throw InputError(o.out_dir + "/decisions.jsonl: cannot write");

  Runner rig{truth, o, o.out_dir, {}, {}, {}, 0.0, 0};
  // The pilot: a short sweep up in each well, enough for a baseline to start from.
  bool current_positive = settings.positive_well;
  for (bool positive : {true, false}) {
    if (positive ? !settings.positive_well : !settings.negative_well) continue;
    if (rig.runs > 0) rig.shaker_time_s += o.well_change_s;
    rig.run(pilot, o.freq_hz, positive, "pilot");
    current_positive = positive;
  }
  std::printf("pilot: %zu level(s) per well, shaker time %.1f s\n", pilot.size(),
              rig.shaker_time_s);
  std::fflush(stdout);
  analysis::require_measured_levels(rig.campaign);
  const analysis::PreparedFit prepared = analysis::prepare_fit(rig.campaign, setup);
  analysis::HypothesisOptions hypothesis_options;
  hypothesis_options.cost = prepared.cost;
  hypothesis_options.initial_evaluations = o.initial_evaluations;
  hypothesis_options.refit_evaluations = o.refit_evaluations;
  hypothesis_options.effects = effects;
  hypothesis_options.threads = o.threads;
  hypothesis_options.global_evaluations = o.global_evaluations;
  hypothesis_options.seed = o.seed;
  // Every hypothesis, the baseline first, by a global search on the pilot from the form's start.
  const analysis::ModelForm& start_form = prepared.objective->form();
  std::vector<analysis::ModelHypothesis> hypotheses =
      analysis::initial_hypotheses(start_form, start_form.initial(), rig.campaign,
                                   analysis::edc_dataset(rig.campaign), hypothesis_options);
  std::printf("baseline and %zu candidate(s) fitted on the pilot and weighed in %.1f s\n",
              hypotheses.size() - 1, elapsed_s(started));

  const analysis::StopRule rule{o.leader_weight, o.min_discrimination, o.budget_s};
  analysis::NextPointOptions next_options;
  next_options.threads = o.threads;
  int adaptive_levels = 0;
  double refit_s = 0.0;  // of the refits after the last level (0 after the pilot)
  analysis::StopDecision decision;
  for (int decision_index = 0;; ++decision_index) {
    // The proposal first: what the best setting could still tell apart is part of the stop rule.
    decision = analysis::stop_decision(hypotheses, rule, rig.shaker_time_s);
    analysis::NextPoint next;
    double proposal_s = 0.0;
    if (!decision.stop && adaptive_levels < o.max_levels) {
      settings.current_positive_well = current_positive;
      const auto proposing = std::chrono::steady_clock::now();
      next = analysis::propose_next_point(hypotheses, settings, next_options);
      proposal_s = elapsed_s(proposing);
      if (next.found) {
        decision =
            analysis::stop_decision(hypotheses, rule, rig.shaker_time_s, next.max_discrimination);
      }
    }
    if (!decision.stop && adaptive_levels >= o.max_levels) {
      decision.stop = true;
      decision.reason = "max levels: " + std::to_string(o.max_levels) + " adaptive levels run; " +
                        decision.reason;
    } else if (!decision.stop && !next.found) {
      decision.stop = true;
      decision.reason = "no admissible setting: " + next.message + "; " + decision.reason;
    }
    log << decision_line(decision_index, elapsed_s(started), rig.shaker_time_s,
                         analysis::edc_dataset(rig.campaign).level_count(), hypotheses, decision,
                         next, proposal_s, refit_s)
               .dump()
        << '\n';
    log.flush();
    std::printf("[%6.1f s shaker] %s\n", rig.shaker_time_s,
                (decision.stop ? "stop: " + decision.reason : "next: " + next.reason).c_str());
    std::fflush(stdout);
    if (decision.stop) break;
    const analysis::SettingScore& p = next.best;
    if (p.positive_well != current_positive) rig.shaker_time_s += o.well_change_s;
    rig.run({p.f0_n}, p.freq_hz, p.positive_well, "level");
    current_positive = p.positive_well;
    ++adaptive_levels;
    const auto refitting = std::chrono::steady_clock::now();
    analysis::refit_hypotheses(hypotheses, analysis::edc_dataset(rig.campaign), hypothesis_options);
    refit_s = elapsed_s(refitting);
  }

  diagnose_and_report(rig, setup, hypotheses, decision, pilot.size(), adaptive_levels, o, started);
}

}  // namespace

void add_adaptive_test_command(CLI::App& app) {
  auto o = std::make_shared<AdaptiveOptions>();
  CLI::App* command = app.add_subcommand(
      "adaptive-test",
      "A stepped-sine test that chooses its next level: weigh the candidate effects after each "
      "level, propose and run the setting that best tells them apart, stop when one is clear; "
      "then the diagnosis");
  command->add_option("--source", o->source, "rig (the virtual rig, as fast as it computes)")
      ->capture_default_str();
  command->add_option("--rig-model", o->rig_model, "the rig's truth: paper | MODEL.json");
  command
      ->add_option("--out", o->out_dir,
                   "output directory (recordings/, decisions.jsonl, report.json)")
      ->required();
  command->add_option("--model", o->model, "base model of the form: paper | MODEL.json")
      ->capture_default_str();
  command->add_option("--stiffness", o->stiffness, "K(z): identified | rfs | model (as diagnose)")
      ->capture_default_str();
  command->add_option("--freq", o->freq_hz, "excitation frequency [Hz]")->capture_default_str();
  command
      ->add_option("--freq-span", o->freq_span_hz,
                   "admissible frequencies freq +- span [Hz] (0: freq only)")
      ->capture_default_str();
  command->add_option("--freq-step", o->freq_step_hz, "frequency grid step [Hz]")
      ->capture_default_str();
  command->add_option("--f0", o->f0, "admissible forcing amplitudes A:B [N] (the rig's limits)")
      ->capture_default_str();
  command->add_option("--f0-step", o->f0_step_n, "forcing grid step [N]")->capture_default_str();
  command->add_option("--wells", o->wells, "positive | negative | both")
      ->check(CLI::IsMember({"positive", "negative", "both"}))
      ->capture_default_str();
  command->add_option("--pilot", o->pilot, "pilot levels swept up in each well first [N]")
      ->capture_default_str();
  command->add_option("--hold", o->hold_s, "seconds per level (dwell)")->capture_default_str();
  command->add_option("--ramp", o->ramp_s, "amplitude ramp at the start of a level [s]")
      ->capture_default_str();
  command->add_option("--lead-in", o->lead_in_s, "seconds at rest before each run (settling)")
      ->capture_default_str();
  command->add_option("--well-change", o->well_change_s, "shaker seconds to change wells")
      ->capture_default_str();
  command->add_option("--budget", o->budget_s, "shaker-time budget [s]")->capture_default_str();
  command->add_option("--leader-weight", o->leader_weight, "stop when the leader's weight >= this")
      ->capture_default_str();
  command
      ->add_option("--min-discrimination", o->min_discrimination,
                   "with the leader at the noise, stop when no setting separates two plausible "
                   "models by more than this (1: one sigma of a measurement)")
      ->capture_default_str();
  command->add_option("--max-levels", o->max_levels, "adaptive levels at most")
      ->capture_default_str();
  command->add_option("--effects", o->effects,
                      "candidate effects weighed, comma-separated (default: all the form allows)");
  command
      ->add_option("--global-evaluations", o->global_evaluations,
                   "model evaluations of each hypothesis's global search on the pilot (0: none)")
      ->capture_default_str();
  command
      ->add_option("--initial-evaluations", o->initial_evaluations,
                   "model evaluations of each candidate's first fit on the pilot")
      ->capture_default_str();
  command
      ->add_option("--refit-evaluations", o->refit_evaluations,
                   "model evaluations of each warm refit after a level")
      ->capture_default_str();
  command->add_option("--seed", o->seed, "seed of the rig's noise and of the fits")
      ->capture_default_str();
  command->add_option("--threads", o->threads, "threads (0: all cores)")->capture_default_str();
  command->add_option("--max-seconds", o->max_seconds, "time bound of the final diagnosis [s]")
      ->capture_default_str();
  add_cost_options(command, o->cost);
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
