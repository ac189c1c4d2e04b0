// oscilab-cli diagnose REC... --model-form paper --out DIR: where the fitted model and the
// measurement disagree, which physical effect is missing, and the model with it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "analysis/common/input_error.h"
#include "analysis/diagnosis/diagnosis.h"
#include "analysis/edc/well.h"
#include "analysis/figures/diagnosis_figures.h"
#include "analysis/figures/figure_png.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/identification/sigma_budget_report.h"
#include "analysis/model/model_json.h"
#include "analysis/pipeline/offline_analysis.h"
#include "app/cli/campaign_input.h"
#include "app/cli/commands.h"
#include "app/cli/cost_options.h"
#include "app/cli/output_files.h"
#include "app/cli/progress_bar.h"

namespace oscilab::cli {
namespace {

struct DiagnoseOptions {
  std::vector<std::string> recordings;
  std::string model_form = "paper";
  std::string model = "paper";
  std::string stiffness = "identified";
  std::string out_dir;
  unsigned long long seed = 1;
  int threads = 0;
  CostOptions cost;
  double bic_threshold = 10.0;
  double max_seconds = 120.0;
  int max_steps = 3;
  long baseline_evaluations = 1500;
  long candidate_evaluations = 600;
  bool edc_only = false;
  bool no_png = false;
};

void write_levels_csv(const analysis::DiagnosisResult& r, std::ostream& out) {
  out << "well,f0_n,amplitude_m,edc_mes_j,edc_baseline_j,edc_final_j,sigma_j,"
         "residual_baseline_sigma,residual_final_sigma\n";
  for (std::size_t i = 0; i < r.baseline_maps.levels.size(); ++i) {
    const auto& b = r.baseline_maps.levels[i];
    const auto& f = r.final_maps.levels[i];
    out << analysis::to_string(analysis::well_of(b.positive_well)) << ',' << b.f0_n << ','
        << b.amplitude_m << ',' << b.edc_mes_j << ',' << b.edc_mod_j << ',' << f.edc_mod_j << ','
        << b.sigma_j << ',' << b.residual_sigma << ',' << f.residual_sigma << '\n';
  }
}

std::string evidence_text(const std::vector<analysis::EvidenceChange>& evidence) {
  std::string out;
  char part[96];
  for (const analysis::EvidenceChange& e : evidence) {
    std::snprintf(part, sizeof part, "%s%s %+.0f%s", out.empty() ? "" : ", ", e.name.c_str(),
                  e.delta_chi2(),
                  e.supports()      ? " (supports)"
                  : e.contradicts() ? " (against)"
                                    : "");
    out += part;
  }
  return out;
}

// What the terminal shows: the σ budget's summary, the baseline and its fingerprints, every
// candidate of every step with its evidence and why it was accepted or not, the verdict.
void print_result(const analysis::DiagnosisResult& r, const analysis::EdcDataset& data,
                  double bic_threshold) {
  if (r.final_form) {
    // The final model's σ budget per level (no calibration: the result carries it).
    const analysis::EdcObjective final_objective(*r.final_form, data, r.final_cost);
    for (const std::string& line : analysis::sigma_budget_lines(final_objective)) {
      std::printf("%s\n", line.c_str());
    }
  }
  std::printf(
      "baseline (paper form): cost eq. (8) %.4g J, chi2 %.4g (chi2/dof %.3g; noise "
      "level %.3g), largest residual %.1f sigma\n",
      r.baseline.evaluation.cost_j, r.baseline.evaluation.weighted_cost,
      r.baseline_maps.reduced_chi2, r.noise_reduced_chi2, r.baseline_maps.max_abs_residual_sigma);
  for (const analysis::ResponseFingerprint& f : r.baseline_maps.response.items) {
    if (f.levels == 0) continue;
    std::printf("  fingerprint %-11s chi2 %.4g over %d levels (chi2/level %.3g)\n", f.name.c_str(),
                f.chi2, f.levels, f.chi2 / f.levels);
  }
  if (r.rebases > 0) {
    std::printf(
        "  a candidate's refit found a deeper basin of the model's own parameters %d time(s): the "
        "model was refitted from it and the step's candidates measured again\n",
        r.rebases);
  }
  for (const auto& step : r.steps) {
    if (step.effect == "none") {
      std::printf("step: nothing accepted (joint dBIC must be < -%.0f with the EDC improved)\n",
                  bic_threshold);
    } else {
      std::printf("step: %s accepted, joint dBIC %.1f, cost %.4g -> %.4g J, chi2 %.4g -> %.4g%s\n",
                  analysis::candidate_label(step.effect, step.embodiment).c_str(),
                  step.delta_bic_joint, step.cost_before_j, step.cost_after_j, step.weighted_before,
                  step.weighted_after,
                  step.withdrawn ? " -- withdrawn: its strength vanished after later effects" : "");
    }
    for (const auto& t : step.trials) {
      if (!t.solved) {
        std::printf("    %-30s not solved\n", t.effect.c_str());
        continue;
      }
      const std::string label = analysis::candidate_label(t.effect, t.embodiment);
      std::printf("    %-30s dBIC edc %9.1f joint %9.1f  [%s]  %s\n", label.c_str(), t.delta_bic,
                  t.delta_bic_joint, evidence_text(t.evidence).c_str(),
                  analysis::candidate_outcome(step, t, bic_threshold).c_str());
    }
  }
  std::printf("verdict: %s (%.1f s)%s\n", r.verdict.c_str(), r.seconds,
              r.incomplete ? " -- INCOMPLETE: stopped at --max-seconds" : "");
  if (r.gap_explained) {
    std::printf("gap explained: the final model's chi2/dof %.3g is within the noise level %.3g\n",
                r.final_maps.reduced_chi2, r.final_noise_reduced_chi2);
  } else {
    std::printf("GAP NOT EXPLAINED: %s\n", analysis::gap_open_message(r).c_str());
  }
}

void run(const DiagnoseOptions& o) {
  if (o.model_form != "paper") {
    throw InputError("--model-form: unknown form \"" + o.model_form + "\" (paper)");
  }
  if (!(o.max_seconds >= 0.0)) throw InputError("--max-seconds: must be ≥ 0");
  if (o.max_steps < 1) throw InputError("--max-steps: must be at least 1");
  if (o.baseline_evaluations < 10 || o.candidate_evaluations < 10) {
    throw InputError("--baseline-evaluations, --candidate-evaluations: must be at least 10");
  }
  if (o.baseline_evaluations > analysis::kMaxFitEvaluations ||
      o.candidate_evaluations > analysis::kMaxFitEvaluations) {
    throw InputError("--baseline-evaluations, --candidate-evaluations: at most " +
                     std::to_string(analysis::kMaxFitEvaluations));
  }
  if (o.threads < 0 || o.threads > analysis::kMaxThreads) {
    throw InputError("--threads: " + std::to_string(o.threads) + " must be 0 (all cores) to " +
                     std::to_string(analysis::kMaxThreads));
  }
  const analysis::CampaignAnalysis campaign = run_input_stage(o.recordings, {}, {});
  // A stepped-sine record none of whose levels measures anything is refused, as by analyze.
  analysis::require_measured_levels(campaign);
  analysis::FitSetup setup;
  setup.base_model = analysis::model_from_spec(o.model);
  setup.stiffness = analysis::parse_stiffness_source(o.stiffness, "--stiffness");
  setup.cost = cost_settings(o.cost);
  std::vector<std::string> notes;
  const analysis::ModelForm form = analysis::fit_form(campaign, setup, notes);
  analysis::DiagnosisOptions options;
  options.cost = setup.cost;
  options.max_seconds = o.max_seconds;
  options.use_fingerprints = !o.edc_only;
  options.bic_threshold = o.bic_threshold;
  options.max_steps = o.max_steps;
  options.baseline_evaluations = o.baseline_evaluations;
  options.candidate_evaluations = o.candidate_evaluations;
  options.seed = o.seed;
  options.threads = o.threads;
  analysis::DiagnosisResult result;
  {
    ProgressBar bar("diagnose");
    result = analysis::diagnose(
        campaign, form, options,
        [&bar](const analysis::DiagnosisProgress& p) { bar.show(p.fraction, p.describe()); });
  }

  print_result(result, analysis::edc_dataset(campaign), o.bic_threshold);

  nlohmann::json report = analysis::diagnosis_report_json(result, o.recordings, o.bic_threshold);
  report["notes"] = notes;
  // The folder only now that there is something to put in it; every file complete under a
  // temporary name before any takes its own, and a folder made here removed again when they fail.
  std::error_code error;
  const bool existed = std::filesystem::exists(o.out_dir, error);
  std::filesystem::create_directories(o.out_dir, error);
  if (error) throw InputError(o.out_dir + ": cannot create: " + error.message());
  try {
    OutputFiles outputs;
    outputs.write(o.out_dir + "/report.json",
                  [&](std::ostream& out) { out << report.dump(2) << '\n'; });
    outputs.write(o.out_dir + "/levels.csv",
                  [&](std::ostream& out) { write_levels_csv(result, out); });
    if (result.final_form) {
      const nlohmann::json model = result.final_form->build(result.final_theta).to_json();
      outputs.write(o.out_dir + "/final_model.json",
                    [&](std::ostream& out) { out << model.dump(2) << '\n'; });
    }
    if (!o.no_png) {
      outputs.write_to(o.out_dir + "/residuals.png", [&](const std::string& path) {
        figures::write_figure_png(figures::residual_figure(result), path);
      });
      outputs.write_to(o.out_dir + "/missing_energy.png", [&](const std::string& path) {
        figures::write_figure_png(figures::missing_energy_figure(result), path);
      });
    }
    outputs.commit();
  } catch (...) {
    if (!existed) std::filesystem::remove(o.out_dir, error);  // only when still empty
    throw;
  }
  std::printf("report, tables and figures written to %s/\n", o.out_dir.c_str());
}

}  // namespace

void add_diagnose_command(CLI::App& app) {
  auto o = std::make_shared<DiagnoseOptions>();
  CLI::App* command = app.add_subcommand(
      "diagnose",
      "Find where the fitted model and the measurement disagree, name the missing physical "
      "effect (docs/contracts.md §4), add it, refit and show the gap shrink (or say none)");
  command
      ->add_option("recordings", o->recordings,
                   "stepped-sine recordings of both wells (and random records for the RFS)")
      ->required();
  command->add_option("--model-form", o->model_form, "starting model form: paper")
      ->capture_default_str();
  command->add_option("--model", o->model, "base model (mass, stiffness): paper | MODEL.json")
      ->capture_default_str();
  command
      ->add_option("--stiffness", o->stiffness,
                   "K(z): identified (free coefficients, identified with the friction, starting "
                   "from the records' stiffness slice or the model's) | rfs (the slice's cubic, "
                   "held) | model (the model's, held)")
      ->capture_default_str();
  command->add_option("--out", o->out_dir, "output directory (report.json, figures)")->required();
  command->add_option("--seed", o->seed, "seed of the baseline's global search")
      ->capture_default_str();
  command->add_option("--threads", o->threads, "threads (0: all cores)")->capture_default_str();
  add_cost_options(command, o->cost);
  command
      ->add_option("--max-seconds", o->max_seconds,
                   "stop after this many seconds and write the result so far, marked incomplete "
                   "(0: no limit)")
      ->capture_default_str();
  command->add_flag("--edc-only", o->edc_only,
                    "compare candidates on the EDC alone (without the response fingerprints)");
  command->add_option("--bic-threshold", o->bic_threshold, "accept an effect when dBIC < -this")
      ->capture_default_str();
  command->add_option("--max-steps", o->max_steps, "effects added at most")->capture_default_str();
  command
      ->add_option("--baseline-evaluations", o->baseline_evaluations,
                   "model evaluations of the baseline fit (CMA-ES + polish)")
      ->capture_default_str();
  command
      ->add_option("--candidate-evaluations", o->candidate_evaluations,
                   "model evaluations of each candidate's refit")
      ->capture_default_str();
  command->add_flag("--no-png", o->no_png, "tables and report only");
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
