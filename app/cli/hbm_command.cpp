// oscilab-cli hbm: harmonic balance with continuation in the forcing amplitude (contract §2).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/figures/figure_png.h"
#include "analysis/figures/hbm_figures.h"
#include "analysis/hbm/branch_switching.h"
#include "analysis/hbm/continuation.h"
#include "analysis/model/model_json.h"
#include "analysis/simulation/amplitude_sweep.h"
#include "analysis/simulation/bifurcation_map.h"
#include "app/cli/commands.h"
#include "app/cli/option_parsing.h"
#include "app/cli/output_files.h"
#include "app/cli/progress_bar.h"

namespace oscilab::cli {
namespace {

// A figure written under a temporary name and renamed into place when complete.
void write_png_output(const figures::Figure& figure, const std::string& target) {
  OutputFiles output;
  output.write_to(target,
                  [&](const std::string& path) { figures::write_figure_png(figure, path); });
  output.commit();
}

struct HbmCommandOptions {
  std::string model = "paper";
  double freq_hz = 9.0;
  std::string f0 = "0.1:3.7";
  std::string well = "positive";
  int harmonics = 7;
  int subharmonic = 1;
  int samples = 0;
  int floquet_steps = 1024;
  bool no_stability = false;
  double max_step = 0.1;
  std::string out;
  std::string map;  // time-simulation bifurcation map CSV (Fig. 17)
  double map_step = 0.05;
  int map_hold = 200;
  int map_sampled = 32;
  std::string sweep;  // time-integration amplitude sweep CSV (Fig. 12)
  double sweep_time = 400.0;
  std::string png;  // figure prefix
  bool follow_period_doubling = false;
};

using analysis::Well;
using figures::CsvBranch;
using figures::NamedBranch;

// Follows the period-doubling cascade of `branch` (analysis::follow_period_doublings), says what
// each switch found, and appends the new branches to `out` and `csv`.
void follow_period_doublings(const analysis::Model& model, const analysis::Branch& branch,
                             const analysis::ContinuationOptions& options, Well well,
                             std::vector<std::unique_ptr<analysis::Branch>>& out,
                             std::vector<CsvBranch>& csv) {
  const std::string name = to_string(well);
  const auto start = std::chrono::steady_clock::now();
  std::vector<analysis::PeriodDoublingSwitch> switches;
  {
    ProgressBar bar("period doublings " + name);
    switches = analysis::follow_period_doublings(model, branch, options, bar.callback());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (analysis::PeriodDoublingSwitch& doubled : switches) {
    const int period = doubled.subharmonic;
    if (doubled.status != JobStatus::Ok && doubled.branch.points.empty()) {
      std::printf("period-%d branch (%s well): not followed: %s\n", period, name.c_str(),
                  doubled.message.c_str());
      return;
    }
    std::printf(
        "period-%d branch (%s well): starts at f0 = %.6f N (harmonic-balance pitchfork; "
        "Floquet flip at %.6f N), %zu points to f0 = %.6f N\n",
        period, name.c_str(), doubled.f0_pitchfork_n, doubled.f0_flip_n,
        doubled.branch.points.size(), doubled.branch.points.back().f0_n);
    for (const analysis::BranchEvent& e : doubled.branch.events) {
      if (e.point_index == 0) continue;  // the start itself
      std::printf("  %-16s f0 = %.6f N  amp = %.6g m\n", analysis::marker_name(e.kind), e.f0_n,
                  e.amp_m);
    }
    if (doubled.status != JobStatus::Ok) {
      std::printf("  stopped early (points so far written): %s\n", doubled.message.c_str());
    }
    out.push_back(std::make_unique<analysis::Branch>(std::move(doubled.branch)));
    csv.push_back({out.back().get(), well, period});
  }
  if (!switches.empty()) std::printf("period doublings followed in %.1f ms\n", seconds * 1e3);
}

// The continuation's options from the command's: the f0 range, the frequency, the HBM and Floquet
// settings, the step bound.
analysis::ContinuationOptions continuation_options(const HbmCommandOptions& o) {
  analysis::ContinuationOptions options;
  const auto colon = o.f0.find(':');
  if (colon == std::string::npos) throw InputError("--f0: \"" + o.f0 + "\" is not A:B");
  options.start = parse_number(o.f0.substr(0, colon), "--f0");
  options.end = parse_number(o.f0.substr(colon + 1), "--f0");
  options.freq_hz = o.freq_hz;
  options.hbm.harmonics = o.harmonics;
  options.hbm.subharmonic = o.subharmonic;
  options.hbm.samples = o.samples;
  options.floquet.steps_per_forcing_period = o.floquet_steps;
  options.stability = !o.no_stability;
  if (o.follow_period_doubling && o.no_stability) {
    throw InputError(
        "--follow-period-doubling: period doublings are found from the Floquet "
        "multipliers; drop --no-stability");
  }
  options.max_step = o.max_step;
  options.initial_step = std::min(options.initial_step, o.max_step);
  return options;
}

// The branch of each well, its summary printed.
std::vector<analysis::Branch> continue_in_wells(const analysis::Model& model,
                                                analysis::ContinuationOptions options,
                                                const std::vector<Well>& wells,
                                                const HbmCommandOptions& o) {
  std::vector<analysis::Branch> branches;
  for (const Well well : wells) {
    options.positive_well = well == Well::Positive;
    const auto start = std::chrono::steady_clock::now();
    analysis::Branch branch;
    {
      ProgressBar bar("hbm " + to_string(well));
      branch = analysis::continue_branch(model, options, bar.callback());
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s well: %zu points, %g Hz, f0 %g -> %g N, H = %d, nu = %d, N = %d\n",
                to_string(well).c_str(), branch.points.size(), o.freq_hz, options.start,
                options.end, o.harmonics, o.subharmonic, branch.samples);
    std::printf("continuation: %d steps accepted, %d rejected, %d Newton iterations, %.1f ms\n",
                branch.steps_accepted, branch.steps_rejected, branch.newton_iterations,
                seconds * 1e3);
    if (branch.events.empty()) std::printf("no folds or bifurcations found\n");
    for (const analysis::BranchEvent& event : branch.events) {
      std::printf("%-16s f0 = %.6f N  amp = %.6g m\n", analysis::marker_name(event.kind),
                  event.f0_n, event.amp_m);
    }
    branches.push_back(std::move(branch));
  }
  return branches;
}

// --sweep: the time-integrated amplitude sweep beside the branch of the first well.
void write_sweep(const analysis::Model& model, const analysis::AmplitudeSweepOptions& sweep_options,
                 const analysis::Branch& first_branch, Well well, const char* title,
                 const HbmCommandOptions& o) {
  analysis::AmplitudeSweep sweep;
  {
    ProgressBar bar("sweep");
    sweep = analysis::amplitude_sweep(model, sweep_options, bar.callback());
  }
  write_output_file(o.sweep,
                    [&](std::ostream& out) { analysis::write_amplitude_sweep_csv(sweep, out); });
  std::printf("wrote %s: sweep 0 -> %g -> 0 N, %g s each way (%g N/s), %s well\n", o.sweep.c_str(),
              sweep_options.f0_max_n, o.sweep_time, sweep_options.f0_max_n / o.sweep_time,
              to_string(well).c_str());
  std::printf("jump up   at f0 = %.4f N  (%.4g -> %.4g m)\n", sweep.jump_up.f0_n,
              sweep.jump_up.amp_before_m, sweep.jump_up.amp_after_m);
  std::printf("jump down at f0 = %.4f N  (%.4g -> %.4g m)\n", sweep.jump_down.f0_n,
              sweep.jump_down.amp_before_m, sweep.jump_down.amp_after_m);
  if (sweep.status != JobStatus::Ok) throw InputError("hbm --sweep: " + sweep.message);
  if (!o.png.empty()) {
    char sweep_title[512];
    std::snprintf(sweep_title, sizeof sweep_title,
                  "%s, time integration: f0 swept 0 -> %g -> 0 N at %.3g N/s", title,
                  sweep_options.f0_max_n, sweep_options.f0_max_n / o.sweep_time);
    write_png_output(figures::sweep_figure(sweep_title, first_branch, sweep), o.png + "-sweep.png");
    std::printf("wrote %s-sweep.png\n", o.png.c_str());
  }
}

// --map: the bifurcation map by time simulation, drawn over the branches.
void write_map(const analysis::Model& model, const analysis::BifurcationMapOptions& map_options,
               const std::vector<NamedBranch>& named, const char* title,
               const HbmCommandOptions& o) {
  analysis::BifurcationMap map;
  {
    ProgressBar bar("map");
    map = analysis::bifurcation_map(model, map_options, bar.callback());
  }
  write_output_file(o.map,
                    [&](std::ostream& out) { analysis::write_bifurcation_map_csv(map, out); });
  std::printf("wrote %s: %zu levels, %d periods each, last %d sampled at t = nT\n", o.map.c_str(),
              map.levels.size(), o.map_hold, o.map_sampled);
  for (const Well well : {Well::Positive, Well::Negative}) {
    int previous = 0;
    for (const analysis::BifurcationMapLevel& level : map.levels_of(well == Well::Positive)) {
      if (level.distinct_points != previous) {
        std::printf("%s well: %d distinct point%s from f0 = %.4g N\n", to_string(well).c_str(),
                    level.distinct_points, level.distinct_points == 1 ? "" : "s", level.f0_n);
        previous = level.distinct_points;
      }
    }
  }
  if (map.status != JobStatus::Ok) throw InputError("hbm --map: " + map.message);
  if (!o.png.empty()) {
    char map_title[512];
    std::snprintf(map_title, sizeof map_title,
                  "%s: bifurcation map, time simulation stepped %g N, %d periods per level", title,
                  o.map_step, o.map_hold);
    write_png_output(figures::map_figure(map_title, named, map), o.png + "-map.png");
    std::printf("wrote %s-map.png\n", o.png.c_str());
  }
}

void run(const HbmCommandOptions& o) {
  const analysis::Model model = analysis::model_from_spec(o.model);
  analysis::ContinuationOptions options = continuation_options(o);
  const std::optional<Well> only_well = analysis::parse_well(o.well);  // none: both
  std::vector<Well> wells;
  if (only_well != Well::Negative) wells.push_back(Well::Positive);
  if (only_well != Well::Positive) wells.push_back(Well::Negative);
  // Every option is checked before the branch is computed and written: a refused --sweep or
  // --map leaves no branch CSV behind.
  analysis::AmplitudeSweepOptions sweep_options;
  sweep_options.freq_hz = o.freq_hz;
  sweep_options.f0_max_n = options.end;
  sweep_options.up_s = sweep_options.down_s = o.sweep_time;
  sweep_options.positive_well = wells[0] == Well::Positive;
  if (!o.sweep.empty()) sweep_options.validate();
  analysis::BifurcationMapOptions map_options;
  map_options.freq_hz = o.freq_hz;
  map_options.start_n = options.start;
  map_options.end_n = options.end;
  map_options.step_n = o.map_step;
  map_options.hold_periods = o.map_hold;
  map_options.sampled_periods = o.map_sampled;
  map_options.positive_well = only_well != Well::Negative;
  map_options.negative_well = only_well != Well::Positive;
  if (!o.map.empty()) map_options.validate();
  std::vector<analysis::Branch> branches = continue_in_wells(model, options, wells, o);
  std::vector<CsvBranch> csv;
  std::vector<std::unique_ptr<analysis::Branch>> doubled;
  for (std::size_t i = 0; i < branches.size(); ++i) {
    csv.push_back({&branches[i], wells[i], o.subharmonic});
    if (o.follow_period_doubling) {
      options.positive_well = wells[i] == Well::Positive;
      if (branches[i].events_of(analysis::PointMarker::PeriodDoubling).empty())
        std::printf("%s well: no period doubling to follow\n", to_string(wells[i]).c_str());
      follow_period_doublings(model, branches[i], options, wells[i], doubled, csv);
    }
  }
  // Each file complete under a temporary name before it takes its own (a full disk leaves none).
  write_output_file(o.out, [&](std::ostream& out) {
    figures::write_branches_csv(csv, wells.size() > 1, o.follow_period_doubling, out);
  });
  std::printf("wrote %s\n", o.out.c_str());
  for (const analysis::Branch& branch : branches) {
    if (branch.status != JobStatus::Ok) {
      throw InputError("hbm: continuation stopped early (points so far written): " +
                       branch.message);
    }
    if (!branch.message.empty()) std::printf("note: %s\n", branch.message.c_str());
  }

  std::vector<NamedBranch> named;
  for (std::size_t i = 0; i < branches.size(); ++i) {
    named.push_back({wells[i] == Well::Positive ? "z+* well" : "z-* well", &branches[i]});
  }
  char title[160];
  std::snprintf(title, sizeof title, "%s model, %.4g Hz, H = %d%s", o.model.c_str(), o.freq_hz,
                o.harmonics,
                o.subharmonic > 1 ? (", nu = " + std::to_string(o.subharmonic)).c_str() : "");
  if (!o.png.empty()) {
    write_png_output(figures::branch_figure(title, named), o.png + "-branch.png");
    std::printf("wrote %s-branch.png\n", o.png.c_str());
  }

  if (!o.sweep.empty()) write_sweep(model, sweep_options, branches[0], wells[0], title, o);
  if (!o.map.empty()) write_map(model, map_options, named, title, o);
}

}  // namespace

void add_hbm_command(CLI::App& app) {
  auto o = std::make_shared<HbmCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "hbm",
      "Harmonic balance with pseudo-arclength continuation in the forcing amplitude f0 "
      "(§4.2): the branch with EDC (eq. (13)), Floquet stability, folds and period "
      "doublings, as a branch CSV");
  command->add_option("--model", o->model, "paper | illustrative | MODEL.json")
      ->capture_default_str();
  command->add_option("--freq", o->freq_hz, "excitation frequency [Hz]")->capture_default_str();
  command->add_option("--f0", o->f0, "forcing amplitude range A:B [N]")->capture_default_str();
  command
      ->add_option("--well", o->well,
                   "stable equilibrium the branch grows from; both: one branch per well, the "
                   "CSV gets a well column")
      ->check(CLI::IsMember({"positive", "negative", "both"}))
      ->capture_default_str();
  command->add_option("--harmonics", o->harmonics, "H: harmonics of the forcing frequency")
      ->check(CLI::Range(1, 200))
      ->capture_default_str();
  command
      ->add_option("--subharmonic", o->subharmonic,
                   "nu: base frequency omega/nu (1, 2, 4 ...) for period-nu T responses")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command->add_option("--samples", o->samples, "AFT time samples per period (0: 16 nu H)")
      ->capture_default_str();
  command
      ->add_option("--floquet-steps", o->floquet_steps,
                   "RK4 steps per forcing period of the monodromy integration")
      ->check(CLI::Range(8, 1 << 20))
      ->capture_default_str();
  command->add_flag("--no-stability", o->no_stability, "skip Floquet multipliers");
  command->add_flag("--follow-period-doubling", o->follow_period_doubling,
                    "at each period doubling switch onto the period-2 branch (ansatz 2 nu) and "
                    "continue it over the --f0 range (and once more at its first period doubling: "
                    "period 4); its points are appended to the CSV, which gets a period column "
                    "(1, 2, 4 ... forcing periods); needs stability");
  command->add_option("--max-step", o->max_step, "largest scaled arc-length step")
      ->capture_default_str();
  command->add_option("--out", o->out, "branch CSV to write")->required();
  command->add_option("--map", o->map,
                      "also write the bifurcation map by time simulation (Fig. 17): a stepped "
                      "sine over the --f0 range in the selected well(s), z once per forcing "
                      "period at t = nT; CSV f0_n,well,z_m,period");
  command->add_option("--map-step", o->map_step, "map: level step [N]")->capture_default_str();
  command->add_option("--map-hold", o->map_hold, "map: forcing periods per level")
      ->check(CLI::Range(2, 1000000))
      ->capture_default_str();
  command->add_option("--map-sampled", o->map_sampled, "map: last periods of a level recorded")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_option("--sweep", o->sweep,
                      "also write an amplitude sweep by time integration (Fig. 12): f0 ramped "
                      "0 -> B -> 0 linearly (B: end of --f0) in the (first) well; CSV "
                      "f0_n,direction,amp_m,t_s, one row per forcing period");
  command->add_option("--sweep-time", o->sweep_time, "sweep: duration of each direction [s]")
      ->capture_default_str();
  command->add_option("--png", o->png,
                      "also write figures PREFIX-branch.png (amplitude, EDC, harmonics; "
                      "unstable parts dashed), PREFIX-sweep.png with --sweep and PREFIX-map.png "
                      "with --map");
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
