#pragma once

#include <memory>
#include <string>
#include <vector>

#include "analysis/identification/campaign_model.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/identification/model_form.h"
#include "analysis/model/model.h"
#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

/// What a user chooses for a friction fit besides the search itself: the base model (mass,
/// stiffness and starting friction; the paper's, Tables 1 and 3, unless told), where the
/// stiffness comes from, and how the levels are weighed (the σ budget by default). `fit`,
/// `diagnose`, the app's Fit and Diagnose and the bindings all start from one.
struct FitSetup {
  Model base_model = paper_model();
  StiffnessSource stiffness = StiffnessSource::Model;
  EdcCostSettings cost;
};

/// How a fit weighs the levels, from a user's three choices (the CLI's --harmonics,
/// --max-harmonics and --model-error, the app's form, Python's keywords): H of the model's
/// harmonic balance in every evaluation, the largest reference H of the σ budget's defect
/// correction (at least H), and a fixed relative model-error floor (negative: the σ budget).
/// The messages name the first two choices as the front end spells them ("--harmonics",
/// "--max-harmonics" on the command line). Throws InputError naming the choice for an H below 1.
EdcCostSettings cost_settings(int harmonics, int max_harmonics, double model_error_rel,
                              const std::string& harmonics_name,
                              const std::string& max_harmonics_name);

/// A fit's problem, ready to search: the objective over the campaign's levels and what was
/// changed on the way (campaign_model's notes: the recordings' mass, the RFS stiffness).
struct PreparedFit {
  std::shared_ptr<const EdcObjective> objective;
  std::vector<std::string> notes;
  EdcCostSettings cost;  // the set-up's cost settings, before the σ budget was calibrated
};

/// The paper's form (eq. (7), θ of eq. (9)) of the base model with the recordings' mass and the
/// chosen stiffness (campaign_model, whose notes are appended): what a fit or a diagnosis
/// searches over. Throws InputError as campaign_model does.
ModelForm fit_form(const CampaignAnalysis& campaign, const FitSetup& setup,
                   std::vector<std::string>& notes);

/// The one sequence from a campaign to a fit's objective: the base model with the recordings'
/// mass and the chosen stiffness (campaign_model), the paper's form of it (eq. (7), θ of
/// eq. (9)), the campaign's EDC levels (edc_dataset) and the objective (eq. (8) with the σ
/// budget). Throws InputError as those do (no mass, no usable level, bad cost settings).
PreparedFit prepare_fit(const CampaignAnalysis& campaign, const FitSetup& setup);

/// The fewest model evaluations and the smallest GA population a fit accepts (validate).
inline constexpr long kMinFitEvaluations = 10;
inline constexpr int kMinGeneticPopulation = 2;
/// The most model evaluations a fit accepts: an evaluation solves every level's harmonic balance
/// (about a millisecond), so 10^7 is hours on all cores, where the paper's GA takes 2000 and a
/// CMA-ES fit converges within a few thousand. The GA's population × (generations + 1) counts.
inline constexpr long kMaxFitEvaluations = 10'000'000;
/// The most worker threads a job accepts (0: all hardware threads); each holds its own
/// harmonic-balance workspace, and more threads than cores only cost memory.
inline constexpr int kMaxThreads = 1024;

/// Checks a fit's search settings as a user gives them (the CLI's --evaluations, --mutation,
/// --population, --generations, --bootstrap and --threads, the app's form, Python's keywords):
/// kMinFitEvaluations to kMaxFitEvaluations evaluations (the GA's population × (generations + 1)
/// too), a mutation rate in [0, 1], a population of at least kMinGeneticPopulation, no negative
/// generations or bootstrap replicates, 0 to kMaxThreads threads. Throws InputError
/// naming the first bad choice as the front end spells it: `option_prefix` before the name
/// ("--" on the command line, "" in Python), e.g. "--population: must be at least 2".
void validate(const FitOptions& options, const std::string& option_prefix);

/// The stiffness source a user names: "model" (the model's K(z)), "rfs" (the cubic of the
/// records' restoring-force slice) or "identified" (free coefficients, identified with the
/// friction). Throws InputError naming `option_name` for any other name.
StiffnessSource parse_stiffness_source(const std::string& name, const std::string& option_name);

/// The GA's elite for a population: 5 % of it, at least one (2000 evaluations for the paper's
/// population of 100 over 20 generations, genetic_algorithm.h).
int default_elite(int population);

/// How many evaluations a fit runs against, for a progress bar: population × (generations + 1)
/// for the GA (an upper bound: the elite is not re-evaluated), max_evaluations otherwise.
long evaluation_budget(const FitOptions& options);

/// One sentence when the fitted model's harmonic-balance truncation (fit.truncation_change_rel)
/// is more than half a fixed model-error floor, so that the parameters may absorb it; empty
/// otherwise, and always with the σ budget (its defect correction accounts for truncation).
std::string truncation_warning(const FitResult& fit, const EdcObjective& objective);

}  // namespace oscilab::analysis
