// oscilab-cli hbm: harmonic balance with continuation in the forcing amplitude (contract §2).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "analysis/common/input_error.h"
#include "analysis/hbm/continuation.h"
#include "analysis/model/model_json.h"
#include "app/cli/commands.h"
#include "app/cli/progress_bar.h"

namespace oscilab::cli {
namespace {

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
};

double parse_number(const std::string& text, const std::string& option) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value)) {
    throw InputError(option + ": \"" + text + "\" is not a number");
  }
  return value;
}

void run(const HbmCommandOptions& o) {
  const analysis::Model model = analysis::model_from_spec(o.model);
  const auto colon = o.f0.find(':');
  if (colon == std::string::npos) throw InputError("--f0: \"" + o.f0 + "\" is not A:B");
  analysis::ContinuationOptions options;
  options.start = parse_number(o.f0.substr(0, colon), "--f0");
  options.end = parse_number(o.f0.substr(colon + 1), "--f0");
  options.freq_hz = o.freq_hz;
  options.positive_well = o.well == "positive";
  options.hbm.harmonics = o.harmonics;
  options.hbm.subharmonic = o.subharmonic;
  options.hbm.samples = o.samples;
  options.floquet.steps_per_forcing_period = o.floquet_steps;
  options.stability = !o.no_stability;
  options.max_step = o.max_step;
  options.initial_step = std::min(options.initial_step, o.max_step);

  const auto start = std::chrono::steady_clock::now();
  analysis::Branch branch;
  {
    ProgressBar bar("hbm");
    branch = analysis::continue_branch(model, options, bar.callback());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  analysis::write_branch_csv(branch, o.out);
  std::printf("wrote %s: %zu points, %s well, %g Hz, f0 %g -> %g N, H = %d, nu = %d, N = %d\n",
              o.out.c_str(), branch.points.size(), o.well.c_str(), o.freq_hz, options.start,
              options.end, o.harmonics, o.subharmonic, branch.samples);
  std::printf("continuation: %d steps accepted, %d rejected, %d Newton iterations, %.1f ms\n",
              branch.steps_accepted, branch.steps_rejected, branch.newton_iterations,
              seconds * 1e3);
  if (branch.events.empty()) std::printf("no folds or bifurcations found\n");
  for (const analysis::BranchEvent& event : branch.events) {
    std::printf("%-16s f0 = %.6f N  amp = %.6g m\n", analysis::marker_name(event.kind), event.f0_n,
                event.amp_m);
  }
  if (branch.status != JobStatus::Ok) {
    throw InputError("hbm: continuation stopped early (points so far written): " + branch.message);
  }
  if (!branch.message.empty()) std::printf("note: %s\n", branch.message.c_str());
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
  command->add_option("--well", o->well, "stable equilibrium the branch grows from")
      ->check(CLI::IsMember({"positive", "negative"}))
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
  command->add_option("--max-step", o->max_step, "largest scaled arc-length step")
      ->capture_default_str();
  command->add_option("--out", o->out, "branch CSV to write")->required();
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
