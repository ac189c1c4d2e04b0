#include "analysis/identification/fit_setup.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "analysis/common/input_error.h"
#include "analysis/identification/edc_dataset.h"

namespace oscilab::analysis {

EdcCostSettings cost_settings(int harmonics, int max_harmonics, double model_error_rel,
                              const std::string& harmonics_name,
                              const std::string& max_harmonics_name) {
  // H = 200 is the largest ansatz the hbm command takes; the fit's default is 7 (Fig. 11).
  constexpr int kMaxHarmonics = 200;
  if (harmonics < 1) throw InputError(harmonics_name + ": must be at least 1");
  if (harmonics > kMaxHarmonics) {
    throw InputError(harmonics_name + ": " + std::to_string(harmonics) + " is more than " +
                     std::to_string(kMaxHarmonics));
  }
  if (max_harmonics < 1) throw InputError(max_harmonics_name + ": must be at least 1");
  // With the σ budget (no fixed floor) the defect correction climbs the references 15, 23, 31,
  // 47, 63 up to max_harmonics: a value outside 15 … 63 would silently mean no correction or
  // the same as 63. With a fixed floor it is not used.
  if (model_error_rel < 0.0 && (max_harmonics < 15 || max_harmonics > 63)) {
    throw InputError(max_harmonics_name + ": " + std::to_string(max_harmonics) +
                     " must be in 15 … 63 (the σ budget's reference harmonics)");
  }
  EdcCostSettings cost;
  cost.hbm.harmonics = harmonics;
  cost.max_harmonics = std::max(max_harmonics, harmonics);
  cost.model_error_rel = model_error_rel;
  return cost;
}

ModelForm fit_form(const CampaignAnalysis& campaign, const FitSetup& setup,
                   std::vector<std::string>& notes) {
  ModelForm form =
      ModelForm::paper(campaign_model(setup.base_model, campaign, setup.stiffness, notes));
  if (setup.stiffness == StiffnessSource::Identified) form.free_stiffness();
  return form;
}

PreparedFit prepare_fit(const CampaignAnalysis& campaign, const FitSetup& setup) {
  PreparedFit prepared;
  prepared.cost = setup.cost;
  const ModelForm form = fit_form(campaign, setup, prepared.notes);
  prepared.objective =
      std::make_shared<const EdcObjective>(form, edc_dataset(campaign), setup.cost);
  return prepared;
}

void validate(const FitOptions& options, const std::string& option_prefix) {
  const auto fail = [&](const std::string& name, const std::string& rule) {
    throw InputError(option_prefix + name + ": " + rule);
  };
  if (options.uncertainty.bootstrap_replicates < 0) fail("bootstrap", "must be ≥ 0");
  if (options.max_evaluations < kMinFitEvaluations) {
    fail("evaluations", "must be at least " + std::to_string(kMinFitEvaluations));
  }
  const double mutation = options.genetic.mutation_rate;
  if (!(mutation >= 0.0 && mutation <= 1.0)) fail("mutation", "must lie in [0, 1]");
  if (options.genetic.population < kMinGeneticPopulation) {
    fail("population", "must be at least " + std::to_string(kMinGeneticPopulation));
  }
  if (options.genetic.generations < 0) fail("generations", "must be ≥ 0");
  if (options.max_evaluations > kMaxFitEvaluations) {
    fail("evaluations", std::to_string(options.max_evaluations) + " is more than " +
                            std::to_string(kMaxFitEvaluations));
  }
  if (options.method == FitMethod::Genetic &&
      static_cast<double>(options.genetic.population) *
              (static_cast<double>(options.genetic.generations) + 1.0) >
          static_cast<double>(kMaxFitEvaluations)) {
    fail("population", std::to_string(options.genetic.population) + " over " +
                           std::to_string(options.genetic.generations) +
                           " generations is more than " + std::to_string(kMaxFitEvaluations) +
                           " evaluations");
  }
  if (options.uncertainty.bootstrap_replicates > kMaxFitEvaluations) {
    fail("bootstrap", "more than " + std::to_string(kMaxFitEvaluations) + " replicates");
  }
  if (options.threads < 0 || options.threads > kMaxThreads) {
    fail("threads", std::to_string(options.threads) + " must be 0 (all cores) to " +
                        std::to_string(kMaxThreads));
  }
}

StiffnessSource parse_stiffness_source(const std::string& name, const std::string& option_name) {
  if (name == "model") return StiffnessSource::Model;
  if (name == "rfs") return StiffnessSource::Rfs;
  if (name == "identified") return StiffnessSource::Identified;
  throw InputError(option_name + ": \"" + name + "\" is not model, rfs or identified");
}

int default_elite(int population) {
  return std::max(1, static_cast<int>(std::lround(0.05 * population)));
}

long evaluation_budget(const FitOptions& options) {
  return options.method == FitMethod::Genetic
             ? static_cast<long>(options.genetic.population) * (options.genetic.generations + 1)
             : options.max_evaluations;
}

std::string truncation_warning(const FitResult& fit, const EdcObjective& objective) {
  const double floor = objective.settings().model_error_rel;
  if (!(floor > 0.0) || fit.check_harmonics <= 0 || !(fit.truncation_change_rel > 0.5 * floor)) {
    return {};
  }
  char text[256];
  std::snprintf(text, sizeof text,
                "harmonic balance truncation: S_mod changes by %.2g %% from H = %d to H = %d, "
                "comparable to the %.2g %% model-error floor: the parameters may absorb it; "
                "raise the harmonics",
                100.0 * fit.truncation_change_rel, objective.settings().hbm.harmonics,
                fit.check_harmonics, 100.0 * floor);
  return text;
}

}  // namespace oscilab::analysis
