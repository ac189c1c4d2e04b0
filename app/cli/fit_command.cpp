// oscilab-cli fit REC... --model-form paper --method ga|cmaes|local ... --out FIT.json
// (docs/contracts.md §2): identification of the friction model from measured EDCs (§4, §5).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "analysis/common/input_error.h"
#include "analysis/diagnosis/campaign_fit.h"
#include "analysis/figures/fit_figures.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/identification/sigma_budget_report.h"
#include "analysis/model/model_json.h"
#include "analysis/pipeline/offline_analysis.h"
#include "app/cli/campaign_input.h"
#include "app/cli/commands.h"
#include "app/cli/cost_options.h"
#include "app/cli/option_parsing.h"
#include "app/cli/output_files.h"
#include "app/cli/progress_bar.h"
#include "daq/recording/fit_json.h"

namespace oscilab::cli {
namespace {

struct FitCommandOptions {
  std::vector<std::string> recordings;
  std::string model_form = "paper";
  std::string model = "paper";
  std::string method = analysis::fit_method_name(analysis::FitOptions{}.method);
  std::string stiffness = "model";
  std::string out_path;
  std::string figures_dir;
  // The search as the options set it, from analysis::FitOptions' defaults (method and elite are
  // set in run()).
  analysis::FitOptions search;
  CostOptions cost;
  double freq_hz = 0.0;
  bool no_png = false;
};

void print_table(const analysis::FitResult& fit, const analysis::EdcObjective& objective) {
  std::printf("\nidentified (%s, %ld evaluations, %.2f s):\n",
              analysis::fit_method_name(fit.method).c_str(), fit.evaluations, fit.seconds);
  std::printf("  %-12s %12s %12s %25s\n", "parameter", "value", "std error", "95 % interval");
  for (std::size_t i = 0; i < fit.names.size(); ++i) {
    const bool have = i < fit.uncertainty.parameters.size();
    const auto* u = have ? &fit.uncertainty.parameters[i] : nullptr;
    std::printf("  %-12s %12.5g", fit.names[i].c_str(), fit.theta(static_cast<int>(i)));
    if (u) {
      std::printf(" %12.3g   [%10.4g, %10.4g]", u->standard_error, u->lower_95, u->upper_95);
      if (u->weakly_identified) std::printf("  weakly identified: %s", u->note.c_str());
    }
    std::printf("\n");
  }
  std::printf("  cost eq. (8): %.5g J; chi2 %.5g (%s)\n", fit.evaluation.cost_j,
              fit.evaluation.weighted_cost, objective.weighted_cost_name().c_str());
  // A well without levels has no deviation (NaN): say so instead of printing "nan".
  const auto deviation = [](double pct) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f %%", pct);
    return std::isfinite(pct) ? std::string(text) : std::string("no levels");
  };
  std::printf("  mean deviation: %s (z+* well), %s (z-* well)\n",
              deviation(fit.evaluation.mean_deviation_pct_positive).c_str(),
              deviation(fit.evaluation.mean_deviation_pct_negative).c_str());
  if (fit.check_harmonics > 0) {
    std::printf("  harmonic balance: S_mod changes by at most %.2g %% from H = %d to H = %d",
                100.0 * fit.truncation_change_rel, objective.settings().hbm.harmonics,
                fit.check_harmonics);
    std::printf("\n");
    const std::string warning = analysis::truncation_warning(fit, objective);
    if (!warning.empty()) std::printf("  warning: %s (--harmonics)\n", warning.c_str());
  }
  if (fit.status != JobStatus::Ok) std::printf("  status: %s\n", fit.message.c_str());
}

void print_sigma_budget(const analysis::EdcObjective& objective) {
  for (const std::string& line : analysis::sigma_budget_lines(objective)) {
    std::printf("%s\n", line.c_str());
  }
}

void run(const FitCommandOptions& o) {
  if (o.model_form != "paper") {
    throw InputError("--model-form: unknown form \"" + o.model_form + "\" (paper)");
  }
  analysis::validate(o.search, "--");
  refuse_output_over_inputs(o.out_path, "--out", recordings_and_sidecars(o.recordings));
  analysis::FitOptions options = o.search;
  options.method = analysis::parse_fit_method(o.method);
  options.genetic.elite = analysis::default_elite(options.genetic.population);
  const analysis::StiffnessSource stiffness =
      analysis::parse_stiffness_source(o.stiffness, "--stiffness");
  if (!o.figures_dir.empty()) {
    std::error_code error;
    std::filesystem::create_directories(o.figures_dir, error);
    if (error) throw InputError(o.figures_dir + ": cannot create: " + error.message());
  }

  daq::MappingOverrides overrides;
  if (o.freq_hz > 0) overrides.excitation_freq_hz = o.freq_hz;
  const analysis::CampaignAnalysis campaign = run_input_stage(o.recordings, overrides, {});
  // A stepped-sine record none of whose levels measures anything is refused, as by analyze.
  analysis::require_measured_levels(campaign);
  analysis::FitSetup setup;
  setup.base_model = analysis::model_from_spec(o.model);
  setup.stiffness = stiffness;
  setup.cost = cost_settings(o.cost);
  const analysis::PreparedFit prepared = analysis::prepare_fit(campaign, setup);
  std::shared_ptr<const analysis::EdcObjective> fitted_objective = prepared.objective;
  const analysis::EdcObjective& prepared_objective = *prepared.objective;
  const analysis::EdcDataset& data = prepared_objective.data();
  const std::vector<std::string>& notes = prepared.notes;

  std::printf("fit: %d levels (", prepared_objective.level_count());
  for (std::size_t g = 0; g < data.groups.size(); ++g) {
    std::printf("%s%zu in the %s well at %.4g Hz", g ? ", " : "", data.groups[g].levels.size(),
                data.groups[g].positive_well ? "z+*" : "z-*", data.groups[g].freq_hz);
  }
  std::printf("), %zu left out\n", data.excluded.size());
  for (const auto& e : data.excluded) std::printf("  left out: %s\n", e.c_str());
  for (const auto& n : notes) std::printf("  note: %s\n", n.c_str());
  print_sigma_budget(prepared_objective);

  analysis::FitResult fit;
  {
    ProgressBar bar("fit");
    const ProgressFn draw = bar.callback();
    const long budget = analysis::evaluation_budget(options);
    analysis::CampaignFit result =
        analysis::fit_campaign(prepared, campaign, options, [&](const analysis::FitProgress& p) {
          if (draw && p.stage != analysis::FitStage::Uncertainty) {
            draw(std::min(1.0, static_cast<double>(p.evaluations) / static_cast<double>(budget)));
          }
        });
    fit = std::move(result.fit);
    fitted_objective = std::move(result.objective);
  }
  const analysis::EdcObjective& objective = *fitted_objective;
  print_table(fit, objective);

  daq::write_fit_json(o.out_path, fit, objective, o.recordings, notes);
  std::printf("fit written to %s\n", o.out_path.c_str());

  if (o.figures_dir.empty()) return;
  figures::write_fit_figures(o.figures_dir, fit, objective,
                             figures::fit_figure_data(objective, fit.theta, options.threads),
                             !o.no_png);
  std::printf("figures and tables written to %s/\n", o.figures_dir.c_str());
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto o = std::make_shared<FitCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "fit",
      "Identify the friction model from the EDCs of stepped-sine records (§4, §5): θ of eq. (9) "
      "by the paper's genetic algorithm or CMA-ES with a BOBYQA polish, with uncertainty");
  command->add_option("recordings", o->recordings, "stepped-sine recordings (both wells)")
      ->required();
  command->add_option("--model-form", o->model_form, "model form: paper (eq. (7), θ of eq. (9))")
      ->capture_default_str();
  command
      ->add_option("--model", o->model,
                   "base model (mass, stiffness, starting friction): paper | MODEL.json")
      ->capture_default_str();
  command->add_option("--method", o->method, "ga (the paper's), cmaes (with polish) or local")
      ->capture_default_str();
  command->add_option("--population", o->search.genetic.population, "GA population")
      ->capture_default_str();
  command->add_option("--generations", o->search.genetic.generations, "GA generations")
      ->capture_default_str();
  command->add_option("--mutation", o->search.genetic.mutation_rate, "GA mutation rate")
      ->capture_default_str();
  command->add_flag("--polish", o->search.polish_after_genetic, "polish the GA's best with BOBYQA");
  command
      ->add_option("--evaluations", o->search.max_evaluations,
                   "model evaluations of cmaes (search + polish) or local")
      ->capture_default_str();
  command->add_option("--seed", o->search.seed, "random seed (same seed, same result)")
      ->capture_default_str();
  command->add_option("--threads", o->search.threads, "threads (0: all cores)")
      ->capture_default_str();
  add_cost_options(command, o->cost);
  command
      ->add_option("--bootstrap", o->search.uncertainty.bootstrap_replicates,
                   "bootstrap replicates over levels (0: none)")
      ->capture_default_str();
  command
      ->add_option("--stiffness", o->stiffness,
                   "K(z): model (the model's, held) | rfs (the records' slice cubic, held) | "
                   "identified (free, identified with the friction from the slice on)")
      ->capture_default_str();
  command
      ->add_option("--freq", o->freq_hz,
                   "excitation frequency [Hz] (default: sidecar, else detected)")
      ->check(positive_number());
  command->add_option("--figures", o->figures_dir,
                      "directory for Figs. 13-16 as PNG and their data as CSV");
  command->add_flag("--no-png", o->no_png, "with --figures: the CSV tables only");
  command->add_option("--out", o->out_path, "FIT.json")->required();
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
