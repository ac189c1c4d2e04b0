// EDC identification: the optimisers on noise-free twin data of the paper's model.
#include "analysis/identification/edc_fit.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "analysis/model/reference_models.h"
#include "tests/analysis/identification/twin_data.h"

namespace oscilab::analysis {
namespace {

// Twin data of the paper's model at five levels per well; the truth is Table 3.
const EdcObjective& twin_objective() {
  static const EdcObjective objective(
      ModelForm::paper(paper_model()),
      testing::twin_dataset(paper_model(), {}, testing::few_levels_n()), testing::twin_settings());
  return objective;
}

TEST(EdcFit, GeneticAlgorithmIsReproducibleForASeedAndThreadCount) {
  const EdcObjective& objective = twin_objective();
  FitOptions options;
  options.method = FitMethod::Genetic;
  options.genetic.population = 10;
  options.genetic.generations = 2;
  options.genetic.elite = 1;
  options.compute_uncertainty = false;
  options.seed = 7;
  options.threads = 2;
  const FitResult a = fit_edc(objective, options);
  options.threads = 1;
  const FitResult b = fit_edc(objective, options);
  options.seed = 8;
  const FitResult c = fit_edc(objective, options);
  EXPECT_EQ(a.evaluations, 10 + 2 * 9);
  EXPECT_EQ(a.evaluations, b.evaluations);
  EXPECT_EQ(a.evaluation.weighted_cost, b.evaluation.weighted_cost);  // bit for bit
  EXPECT_EQ(a.theta, b.theta);
  EXPECT_NE(a.theta, c.theta);  // another seed draws other populations
}

TEST(EdcFit, LocalPolishFromANeighbourReturnsToTheTruth) {
  // Start 10 % off the truth in every parameter; BOBYQA must come back within 0.1 %.
  const Model truth_model = paper_model();
  PaperFriction off;
  off.fd_zminus_n *= 1.1;
  off.fd_zplus_n *= 0.9;
  off.fd_zero_n *= 1.1;
  off.ks = 1.0 + 0.9 * (off.ks - 1.0);
  off.c_ns_m *= 1.1;
  off.vt_m_s *= 0.9;
  const EdcObjective objective(ModelForm::paper(paper_model(off)),
                               testing::twin_dataset(truth_model), testing::twin_settings());
  const Eigen::VectorXd truth = ModelForm::paper(truth_model).initial();
  FitOptions options;
  options.method = FitMethod::Local;
  options.max_evaluations = 600;
  options.compute_uncertainty = false;
  const FitResult fit = fit_edc(objective, options);
  EXPECT_LE(fit.evaluations, 600);
  EXPECT_LT(testing::worst_required_error(fit, truth), 1e-3);
}

TEST(EdcFit, CancelReturnsTheBestSoFarWithCancelledStatus) {
  const EdcObjective& objective = twin_objective();
  FitOptions options;
  options.compute_uncertainty = false;
  // Cancelled from the progress callback once 100 evaluations are done (the user's click, at a
  // point that does not depend on the machine's speed).
  CancelToken cancel;
  const FitResult fit = fit_edc(
      objective, options,
      [&](const FitProgress& p) {
        if (p.evaluations >= 100) cancel.cancel();
      },
      cancel);
  EXPECT_EQ(fit.status, JobStatus::Cancelled);
  EXPECT_GE(fit.evaluations, 100);
  EXPECT_LT(fit.evaluations, 2000);  // it stopped early
  EXPECT_EQ(fit.theta.size(), 6);    // and still holds a θ
  EXPECT_TRUE(std::isfinite(fit.evaluation.weighted_cost));
}

TEST(EdcFit, ProgressReportsMonotoneBestCost) {
  const EdcObjective& objective = twin_objective();
  FitOptions options;
  options.method = FitMethod::Genetic;
  options.genetic.population = 8;
  options.genetic.generations = 3;
  options.genetic.elite = 1;
  options.compute_uncertainty = false;
  std::vector<FitProgress> reports;
  fit_edc(objective, options, [&](const FitProgress& p) { reports.push_back(p); });
  ASSERT_EQ(reports.size(), 4u);  // generation 0 and three more
  for (std::size_t i = 1; i < reports.size(); ++i) {
    EXPECT_GT(reports[i].evaluations, reports[i - 1].evaluations);
    EXPECT_LE(reports[i].best_weighted_cost, reports[i - 1].best_weighted_cost);
  }
  EXPECT_EQ(reports.back().best_theta.size(), 6);
}

// The stages come in their order (search, then polish, then uncertainty), each reported at least
// once, and the evaluations never go back across a stage change.
TEST(EdcFit, ProgressNamesTheStagesInTheOrderTheyRun) {
  const EdcObjective& objective = twin_objective();
  FitOptions options;
  options.method = FitMethod::Genetic;
  options.genetic.population = 8;
  options.genetic.generations = 2;
  options.genetic.elite = 1;
  options.polish_after_genetic = true;
  options.polish.max_evaluations = 30;
  options.uncertainty.bootstrap_replicates = 0;
  std::vector<FitProgress> reports;
  fit_edc(objective, options, [&](const FitProgress& p) { reports.push_back(p); });
  ASSERT_FALSE(reports.empty());
  std::vector<FitStage> order;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    if (order.empty() || order.back() != reports[i].stage) order.push_back(reports[i].stage);
    if (i > 0) {
      EXPECT_GE(reports[i].evaluations, reports[i - 1].evaluations);
    }
  }
  const std::vector<FitStage> expected{FitStage::Search, FitStage::Polish, FitStage::Uncertainty};
  EXPECT_EQ(order, expected);
  EXPECT_STREQ(to_string(FitStage::Search), "search");
  EXPECT_STREQ(to_string(FitStage::Polish), "polish");
  EXPECT_STREQ(to_string(FitStage::Uncertainty), "uncertainty");
}

TEST(EdcFit, RejectsUnknownMethodNames) {
  EXPECT_EQ(parse_fit_method("ga"), FitMethod::Genetic);
  EXPECT_EQ(parse_fit_method("cmaes"), FitMethod::Cmaes);
  EXPECT_THROW(parse_fit_method("simplex"), InputError);
}

}  // namespace
}  // namespace oscilab::analysis
