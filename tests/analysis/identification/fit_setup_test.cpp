// The fit's set-up that the CLI, the app and the Python module share: the cost settings from the
// user's three choices, the checks of the search settings, the stiffness source's names, the GA's
// default elite and the progress budget, checked against the rules their documentation states.
#include "analysis/identification/fit_setup.h"

#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "tests/input_error_of.h"

namespace oscilab::analysis {
namespace {

using oscilab::testing::input_error_of;

TEST(FitSetup, CostSettingsKeepTheChoicesAndNeverCorrectBelowTheFittedHarmonics) {
  const EdcCostSettings cost = cost_settings(7, 63, -1.0, "--harmonics", "--max-harmonics");
  EXPECT_EQ(cost.hbm.harmonics, 7);
  EXPECT_EQ(cost.max_harmonics, 63);
  EXPECT_EQ(cost.model_error_rel, -1.0);  // the σ budget
  // A reference below H would correct towards a coarser balance: it is raised to H.
  const EdcCostSettings raised = cost_settings(21, 15, 0.02, "--harmonics", "--max-harmonics");
  EXPECT_EQ(raised.max_harmonics, 21);
  EXPECT_EQ(raised.model_error_rel, 0.02);
}

TEST(FitSetup, CostSettingsNameTheChoiceAsTheFrontEndSpellsIt) {
  EXPECT_EQ(input_error_of([] { cost_settings(0, 63, -1.0, "--harmonics", "--max-harmonics"); }),
            "--harmonics: must be at least 1");
  EXPECT_EQ(input_error_of([] { cost_settings(7, 0, -1.0, "harmonics", "max_harmonics"); }),
            "max_harmonics: must be at least 1");
}

TEST(FitSetup, TheElitesIsFivePercentOfThePopulationAndAtLeastOne) {
  EXPECT_EQ(default_elite(100), 5);  // the paper's population
  EXPECT_EQ(default_elite(30), 2);   // 1.5 rounds to 2
  EXPECT_EQ(default_elite(10), 1);   // 0.5 rounds away from zero
  EXPECT_EQ(default_elite(4), 1);    // 0.2: at least one
}

TEST(FitSetup, TheProgressBudgetIsEveryGenerationOfTheGaOrTheEvaluationLimit) {
  FitOptions options;
  options.method = FitMethod::Genetic;
  options.genetic.population = 100;
  options.genetic.generations = 20;
  EXPECT_EQ(evaluation_budget(options), 2100);  // the initial population and 20 generations
  options.method = FitMethod::Cmaes;
  options.max_evaluations = 2000;
  EXPECT_EQ(evaluation_budget(options), 2000);
}

TEST(FitSetup, TheDefaultSearchIsValidAndSoAreTheBoundaryValues) {
  EXPECT_EQ(input_error_of([] { validate(FitOptions{}, "--"); }), "");
  FitOptions edge;
  edge.max_evaluations = kMinFitEvaluations;
  edge.genetic.population = kMinGeneticPopulation;
  edge.genetic.generations = 0;
  edge.genetic.mutation_rate = 1.0;
  edge.uncertainty.bootstrap_replicates = 0;
  EXPECT_EQ(input_error_of([&] { validate(edge, ""); }), "");
  edge.genetic.mutation_rate = 0.0;
  EXPECT_EQ(input_error_of([&] { validate(edge, ""); }), "");
}

// Each bad choice is named as the front end spells it: "--" before it on the command line.
TEST(FitSetup, ValidateNamesTheFirstBadChoiceAsTheFrontEndSpellsIt) {
  const auto error_with = [](const std::function<void(FitOptions&)>& change,
                             const std::string& prefix) {
    FitOptions options;
    change(options);
    return input_error_of([&] { validate(options, prefix); });
  };
  EXPECT_EQ(error_with([](FitOptions& o) { o.max_evaluations = 9; }, "--"),
            "--evaluations: must be at least 10");
  EXPECT_EQ(error_with([](FitOptions& o) { o.genetic.mutation_rate = 1.5; }, "--"),
            "--mutation: must lie in [0, 1]");
  EXPECT_EQ(error_with([](FitOptions& o) { o.genetic.mutation_rate = -0.1; }, ""),
            "mutation: must lie in [0, 1]");
  EXPECT_EQ(error_with([](FitOptions& o) { o.genetic.mutation_rate = std::nan(""); }, ""),
            "mutation: must lie in [0, 1]");
  EXPECT_EQ(error_with([](FitOptions& o) { o.genetic.population = 1; }, ""),
            "population: must be at least 2");
  EXPECT_EQ(error_with([](FitOptions& o) { o.genetic.generations = -1; }, "--"),
            "--generations: must be ≥ 0");
  EXPECT_EQ(error_with([](FitOptions& o) { o.uncertainty.bootstrap_replicates = -1; }, "--"),
            "--bootstrap: must be ≥ 0");
  // Several bad choices: the first in the command line's order of checks is named.
  EXPECT_EQ(error_with(
                [](FitOptions& o) {
                  o.genetic.population = 0;
                  o.max_evaluations = 0;
                },
                "--"),
            "--evaluations: must be at least 10");
}

// Absurd budgets would run for days or allocate a population beyond memory: refused up front.
TEST(FitSetup, ValidateRefusesBudgetsAndThreadCountsBeyondTheLimits) {
  const auto error_with = [](const std::function<void(FitOptions&)>& change) {
    FitOptions options;
    change(options);
    return input_error_of([&] { validate(options, "--"); });
  };
  EXPECT_EQ(error_with([](FitOptions& o) { o.max_evaluations = kMaxFitEvaluations; }), "");
  EXPECT_EQ(error_with([](FitOptions& o) { o.max_evaluations = 1'000'000'000'000; }),
            "--evaluations: 1000000000000 is more than 10000000");
  EXPECT_EQ(error_with([](FitOptions& o) {
              o.method = FitMethod::Genetic;
              o.genetic.population = 100000;
              o.genetic.generations = 100;
            }),
            "--population: 100000 over 100 generations is more than 10000000 evaluations");
  EXPECT_EQ(error_with([](FitOptions& o) { o.threads = -1; }),
            "--threads: -1 must be 0 (all cores) to 1024");
  EXPECT_EQ(error_with([](FitOptions& o) { o.threads = kMaxThreads; }), "");
}

TEST(FitSetup, CostSettingsRefuseAReferenceOutsideTheSigmaBudgetsLadder) {
  // The σ budget's defect correction climbs H_ref = 15, 23, 31, 47, 63: 5 would mean none.
  EXPECT_EQ(input_error_of([] { cost_settings(7, 5, -1.0, "--harmonics", "--max-harmonics"); }),
            "--max-harmonics: 5 must be in 15 … 63 (the σ budget's reference harmonics)");
  EXPECT_EQ(input_error_of([] { cost_settings(7, 64, -1.0, "--harmonics", "--max-harmonics"); }),
            "--max-harmonics: 64 must be in 15 … 63 (the σ budget's reference harmonics)");
  EXPECT_EQ(input_error_of([] { cost_settings(7, 15, -1.0, "--harmonics", "--max-harmonics"); }),
            "");
  // A fixed model-error floor uses no reference: any positive value is accepted.
  EXPECT_EQ(input_error_of([] { cost_settings(3, 3, 0.05, "harmonics", "max_harmonics"); }), "");
  EXPECT_EQ(input_error_of([] { cost_settings(201, 63, -1.0, "--harmonics", "--max-harmonics"); }),
            "--harmonics: 201 is more than 200");
}

TEST(FitSetup, StiffnessSourceNamesRoundTripAndOthersAreRejectedByName) {
  EXPECT_EQ(parse_stiffness_source("model", "--stiffness"), StiffnessSource::Model);
  EXPECT_EQ(parse_stiffness_source("rfs", "--stiffness"), StiffnessSource::Rfs);
  EXPECT_EQ(parse_stiffness_source("identified", "--stiffness"), StiffnessSource::Identified);
  EXPECT_EQ(input_error_of([] { parse_stiffness_source("RFS", "stiffness"); }),
            "stiffness: \"RFS\" is not model, rfs or identified");
  EXPECT_EQ(input_error_of([] { parse_stiffness_source("", "--stiffness"); }),
            "--stiffness: \"\" is not model, rfs or identified");
}

}  // namespace
}  // namespace oscilab::analysis
