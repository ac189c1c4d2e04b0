// `oscilab-cli adaptive-test --source rig --rig-model MODEL.json --out DIR` (or `--source
// jack:ACC,POS --drive jack:PORT` for a shaker driven in real time): a stepped-sine test
// that chooses its own levels. A pilot sweep in each well, then a loop: weigh the baseline and
// the candidate effects (BIC weights of warm refits), stop when a leader is clear at the noise or
// the shaker time is spent, otherwise propose the setting that best tells the plausible models
// apart per second of shaker time, run it (virtual rig or shaker), analyse it as offline, repeat.
// The recordings, a decision log (one JSON line per decision) and the final diagnosis report.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "analysis/design/adaptive_test.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/model/model_json.h"
#include "app/cli/commands.h"
#include "app/cli/cost_options.h"
#include "app/cli/drive_options.h"
#include "app/cli/option_parsing.h"
#include "daq/drive/drive_event_json.h"
#include "daq/drive/jack_level_runner.h"
#include "daq/recording/adaptive_test_folder.h"
#include "daq/rig/rig_level_runner.h"

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
  // --source jack:ACC,POS --drive jack:PORT: a shaker driven in real time.
  std::string drive;
  daq::JackDriveClient::Options jack;
  double mass_kg = 0.0;  // 0: the base model's
  double settle_timeout_s = 30.0;
};

bool jack_source(const AdaptiveOptions& o) { return o.source.rfind("jack:", 0) == 0; }

// The ports of "jack:PORT" or "jack:A,B" (`count` of them), or InputError naming the option.
std::vector<std::string> jack_ports(const std::string& text, std::size_t count,
                                    const std::string& option) {
  const std::vector<std::string> ports = split(text.substr(5), ',');
  bool empty = false;
  for (const std::string& port : ports) empty = empty || port.empty();
  if (ports.size() != count || empty) {
    throw InputError(option + " " + text + ": give " +
                     (count == 1 ? std::string("jack:PORT")
                                 : std::string("jack:ACCELERATION_PORT,POSITION_PORT")));
  }
  return ports;
}

// What only this command knows (the source, the rig's level timing, the diagnosis's time
// bound); the rest is AdaptiveTestOptions::validate()'s, under these options' names.
void validate(const AdaptiveOptions& o) {
  if (o.source != "rig" && !jack_source(o)) {
    throw InputError("--source " + o.source +
                     ": rig (the virtual rig) or jack:ACCELERATION_PORT,POSITION_PORT (a shaker "
                     "driven through --drive jack:PORT)");
  }
  if (jack_source(o)) {
    jack_ports(o.source, 2, "--source");
    if (o.drive.rfind("jack:", 0) != 0) {
      throw InputError("--drive: required with --source jack:…, as jack:PLAYBACK_PORT");
    }
    jack_ports(o.drive, 1, "--drive");
    if (!(o.jack.acceleration_scale_m_s2 > 0.0) || !(o.jack.position_scale_m > 0.0)) {
      throw InputError(
          "--acceleration-scale, --position-scale: required with --source jack:… (SI per unit of "
          "the capture ports)");
    }
    if (o.wells == "both") {
      throw InputError(
          "--wells both: a real rig cannot move the mass between wells; give the well it sits "
          "in (positive or negative)");
    }
    if (!o.rig_model.empty()) throw InputError("--rig-model: only with --source rig");
  } else {
    if (o.rig_model.empty()) throw InputError("--rig-model: required with --source rig");
    if (!o.drive.empty()) throw InputError("--drive: only with --source jack:…");
  }
  if (!(o.ramp_s >= 0.0) || !std::isfinite(o.ramp_s) || !(o.ramp_s < o.hold_s)) {
    throw InputError("--hold, --ramp: hold must be positive and longer than the ramp");
  }
  if (!(o.max_seconds >= 0.0)) throw InputError("--max-seconds: must be >= 0");
}

// The core's option fields as this command's options, for its refusals.
const std::vector<std::pair<std::string, std::string>> kOptionOfField = {
    {"settings.f0_range_n", "--f0"},
    {"settings.f0_step_n", "--f0-step"},
    {"settings.freq_hz", "--freq"},
    {"settings.freq_span_hz", "--freq-span"},
    {"settings.freq_step_hz", "--freq-step"},
    {"settings.wells", "--wells"},
    {"settings.dwell_s", "--hold"},
    {"settings.settling_s", "--lead-in"},
    {"settings.well_change_s", "--well-change"},
    {"pilot_levels_n", "--pilot"},
    {"stop.leader_weight", "--leader-weight"},
    {"stop.min_discrimination", "--min-discrimination"},
    {"stop.budget_s", "--budget"},
    {"max_levels", "--max-levels"},
    {"hypotheses.global_evaluations", "--global-evaluations"},
    {"hypotheses.initial_evaluations", "--initial-evaluations"},
    {"hypotheses.refit_evaluations", "--refit-evaluations"},
    {"hypotheses.threads", "--threads"},
    {"hypotheses.effects", "--effects"}};

// The admissible f0 range "A:B".
std::pair<double, double> parse_range(const std::string& text, const std::string& option) {
  const std::vector<std::string> parts = split(text, ':');
  if (parts.size() != 2) throw InputError(option + ": \"" + text + "\" is not A:B");
  const double a = parse_number(parts[0], option), b = parse_number(parts[1], option);
  if (!(a > 0.0) || !(b >= a)) throw InputError(option + ": need 0 < A <= B, got " + text);
  return {a, b};
}

// The command line's options as the core's: the settings the loop may choose from (the f0 grid,
// the frequencies around --freq, the wells, what each costs in shaker time), the pilot, the stop
// rule, the fits and the final diagnosis.
analysis::AdaptiveTestOptions adaptive_test_options(const AdaptiveOptions& o) {
  analysis::AdaptiveTestOptions options;
  analysis::AdmissibleSettings& settings = options.settings;
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
  options.pilot_levels_n = parse_levels(o.pilot, "--pilot");
  options.stop = analysis::StopRule{o.leader_weight, o.min_discrimination, o.budget_s};
  options.max_levels = o.max_levels;
  options.setup.base_model = analysis::model_from_spec(o.model);
  options.setup.stiffness = analysis::parse_stiffness_source(o.stiffness, "--stiffness");
  options.setup.cost = cost_settings(o.cost);
  options.hypotheses.initial_evaluations = o.initial_evaluations;
  options.hypotheses.refit_evaluations = o.refit_evaluations;
  options.hypotheses.global_evaluations = o.global_evaluations;
  options.hypotheses.seed = o.seed;
  options.hypotheses.threads = o.threads;
  if (!o.effects.empty()) options.hypotheses.effects = split(o.effects, ',');
  options.next.threads = o.threads;
  options.diagnosis.max_seconds = o.max_seconds;
  options.diagnosis.seed = o.seed;
  options.diagnosis.threads = o.threads;
  analysis::validate_as_named(options, kOptionOfField);
  return options;
}

// The runner of --source: the virtual rig, or the shaker behind the JACK drive.
std::unique_ptr<analysis::LevelRunner> make_runner(const AdaptiveOptions& o,
                                                   const analysis::AdaptiveTestOptions& options) {
  const std::string folder = o.out_dir + "/recordings";
  if (!jack_source(o)) {
    return std::make_unique<daq::RigLevelRunner>(
        analysis::model_from_spec(o.rig_model), folder,
        daq::RigLevelRunner::Schedule{o.hold_s, o.ramp_s, o.lead_in_s}, o.seed);
  }
  daq::JackLevelRunner::Options jack;
  jack.drive = o.jack;
  const std::vector<std::string> inputs = jack_ports(o.source, 2, "--source");
  jack.drive.acceleration_port = inputs[0];
  jack.drive.position_port = inputs[1];
  jack.drive.drive_port = jack_ports(o.drive, 1, "--drive")[0];
  jack.drive.controller.ramp_s = o.ramp_s;
  jack.mass_kg = o.mass_kg > 0.0 ? o.mass_kg : options.setup.base_model.mass_kg();
  jack.positive_well = o.wells == "positive";
  jack.hold_s = o.hold_s;
  jack.lead_in_s = o.lead_in_s;
  jack.settle_timeout_s = o.settle_timeout_s;
  jack.folder = folder;
  return std::make_unique<daq::JackLevelRunner>(jack);
}

const std::vector<std::string>& runner_paths(const analysis::LevelRunner& runner) {
  if (const auto* jack = dynamic_cast<const daq::JackLevelRunner*>(&runner)) return jack->paths();
  return dynamic_cast<const daq::RigLevelRunner&>(runner).paths();
}

// The drive's events of a JACK test, one JSON line each, in DIR/drive_events.jsonl.
void write_drive_events(const analysis::LevelRunner& runner, const std::string& out_dir) {
  const auto* jack = dynamic_cast<const daq::JackLevelRunner*>(&runner);
  if (jack == nullptr) return;
  std::ofstream log(out_dir + "/drive_events.jsonl");
  for (const daq::DriveEvent& event : jack->events()) {
    log << daq::drive_event_json(event, jack->server_rate_hz()).dump() << '\n';
  }
  if (!log) throw InputError(out_dir + "/drive_events.jsonl: cannot write");
}

void run(const AdaptiveOptions& o) {
  validate(o);
  const analysis::AdaptiveTestOptions options = adaptive_test_options(o);

  // The runner first: a JACK drive that cannot start leaves no folder behind.
  const std::unique_ptr<analysis::LevelRunner> runner = make_runner(o, options);
  daq::AdaptiveTestFolder folder(o.out_dir);

  const auto on_decision = [&](const analysis::AdaptiveDecision& d,
                               const std::vector<analysis::ModelHypothesis>& hypotheses) {
    if (d.index == 0) {
      std::printf(
          "pilot: %zu level(s) per well; baseline and %zu candidate(s) fitted on it and "
          "weighed in %.1f s\n",
          options.pilot_levels_n.size(), hypotheses.size() - 1, d.time_s);
    }
    folder.log(d, hypotheses);
    std::printf(
        "[%6.1f s shaker] %s\n", d.shaker_time_s,
        (d.decision.stop ? "stop: " + d.decision.reason : "next: " + d.next.reason).c_str());
    std::fflush(stdout);
  };
  analysis::AdaptiveTestResult result;
  try {
    result = analysis::run_adaptive_test(*runner, options, on_decision);
  } catch (const daq::DriveAborted& aborted) {
    write_drive_events(*runner, o.out_dir);
    throw InputError(drive_abort_line(aborted.event(), o.jack.controller, "--source"));
  } catch (const InputError&) {
    write_drive_events(*runner, o.out_dir);  // what the drive did up to the failure
    throw;
  }
  write_drive_events(*runner, o.out_dir);

  folder.write_results(result, runner_paths(*runner));
  const std::string& verdict = result.diagnosis.verdict;
  std::printf("verdict: %s, shaker time %.1f s over %d level(s) (%d adaptive), %.1f s\n",
              verdict.c_str(), result.shaker_time_s, result.levels, result.adaptive_levels,
              result.seconds);
  if (result.leader() != verdict) {
    std::printf(
        "note: the adaptive test's leader is %s (weight %.4f, chi2/dof %.3g); the diagnosis of "
        "the same recordings says %s\n",
        result.leader().c_str(), result.decision.leader_weight, result.decision.reduced_chi2,
        verdict.c_str());
  }
  std::printf("recordings, decisions.jsonl and report.json written to %s/\n", o.out_dir.c_str());
}

}  // namespace

void add_adaptive_test_command(CLI::App& app) {
  auto o = std::make_shared<AdaptiveOptions>();
  o->jack.acceleration_scale_m_s2 = o->jack.position_scale_m = 0.0;  // required with jack:
  CLI::App* command = app.add_subcommand(
      "adaptive-test",
      "A stepped-sine test that chooses its next level: weigh the candidate effects after each "
      "level, propose and run the setting that best tells them apart, stop when one is clear; "
      "then the diagnosis");
  command
      ->add_option("--source", o->source,
                   "rig (the virtual rig, as fast as it computes) or jack:ACCELERATION_PORT,"
                   "POSITION_PORT (a shaker in real time, driven through --drive)")
      ->capture_default_str();
  command->add_option("--drive", o->drive,
                      "jack:PLAYBACK_PORT: the shaker amplifier's input (with --source jack:)");
  command->add_option("--jack-server", o->jack.server, "JACK server name (default: the default)");
  command
      ->add_option("--acceleration-scale", o->jack.acceleration_scale_m_s2,
                   "m/s² per unit of the accelerometer's port (with --source jack:)")
      ->check(positive_number());
  command
      ->add_option("--position-scale", o->jack.position_scale_m,
                   "m per unit of the vibrometer's port (with --source jack:)")
      ->check(positive_number());
  command
      ->add_option("--mass", o->mass_kg,
                   "the oscillator's mass [kg] (with --source jack:; default: the model's)")
      ->check(positive_number());
  command
      ->add_option("--settle-timeout", o->settle_timeout_s,
                   "seconds after a ramp for a level to come on target (with --source jack:)")
      ->check(CLI::Range(0.1, 3600.0))
      ->capture_default_str();
  add_drive_controller_options(*command, o->jack.controller);
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
