#include "analysis/identification/edc_objective.h"

#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/reference_models.h"
#include "tests/analysis/identification/twin_data.h"

namespace oscilab::analysis {
namespace {

EdcDataset scaled(EdcDataset data, double factor) {
  for (EdcGroup& g : data.groups) {
    for (MeasuredLevel& level : g.levels) level.edc_j *= factor;
  }
  return data;
}

TEST(EdcObjective, TruthHasZeroCostOnItsOwnTwinData) {
  const Model truth = paper_model();
  const EdcObjective objective(ModelForm::paper(truth), testing::twin_dataset(truth),
                               testing::twin_settings());
  EXPECT_EQ(objective.level_count(), 52);
  const EdcEvaluation e = objective.evaluate(objective.form().initial());
  EXPECT_TRUE(e.ok) << e.message;
  // Same equations, same solver, same starting points: the same numbers to rounding.
  EXPECT_LT(e.cost_j, 1e-12);
  EXPECT_LT(e.weighted_cost, 1e-12);
  EXPECT_LT(e.mean_deviation_pct_positive, 1e-9);
}

TEST(EdcObjective, CostsAndDeviationsFollowTheirDefinitions) {
  const Model truth = paper_model();
  const EdcDataset twin = testing::twin_dataset(truth);
  // Measurement 10 % above the model everywhere: eq. (8) is 0.1 Σ S_mod, every whitened residual
  // is 0.1 S_mod / (0.01 · 1.1 S_mod) = 9.0909, and each level deviates by 0.1 / 1.1 of S_mes.
  const EdcObjective objective(ModelForm::paper(truth), scaled(twin, 1.1),
                               testing::twin_settings());
  const EdcEvaluation e = objective.evaluate(objective.form().initial());
  double sum = 0.0;
  for (const EdcGroup& g : twin.groups) {
    for (const MeasuredLevel& level : g.levels) sum += level.edc_j;
  }
  EXPECT_NEAR(e.cost_j, 0.1 * sum, 1e-12 * sum);
  EXPECT_NEAR(e.residuals(0), 0.1 / 0.011, 1e-9);
  EXPECT_NEAR(e.weighted_cost, 52 * std::pow(0.1 / 0.011, 2), 1e-6);
  EXPECT_NEAR(e.mean_deviation_pct_positive, 100.0 / 11.0, 1e-9);
  EXPECT_NEAR(e.mean_deviation_pct_negative, 100.0 / 11.0, 1e-9);
}

TEST(EdcObjective, SigmaCombinesCycleSpreadAndModelFloor) {
  EdcDataset data = testing::twin_dataset(paper_model(), {}, testing::few_levels_n());
  MeasuredLevel& level = data.groups[0].levels[0];
  level.edc_std_j = 0.04 * level.edc_j;
  level.cycles = 16;  // σ_mean = 0.04 S / 4 = 0.01 S; with the 1 % floor σ = √2 · 0.01 S
  level.noise_floor_j = 0.0;
  const EdcObjective objective(ModelForm::paper(paper_model()), data, testing::twin_settings());
  EXPECT_NEAR(objective.sigma_j()[0] / level.edc_j, std::sqrt(2.0) * 0.01, 1e-15);
  EXPECT_NEAR(objective.sigma_j()[1] / data.groups[0].levels[1].edc_j, 0.01, 1e-15);
}

TEST(EdcObjective, UnsolvableThetaIsAFiniteCostNotAnError) {
  const Model truth = paper_model();
  const EdcObjective objective(ModelForm::paper(truth),
                               testing::twin_dataset(truth, {}, testing::few_levels_n()),
                               testing::twin_settings());
  Eigen::VectorXd theta = objective.form().initial();
  theta(4) = 0.5;  // k_s < 1: no model; every level counts as S_mod = 0
  const EdcEvaluation e = objective.evaluate(theta);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("ks"), std::string::npos) << e.message;
  EXPECT_NEAR(e.weighted_cost, 10 * 1e4, 1e-6);  // each residual is S / (0.01 S) = 100
}

// A θ whose K(z) has no stable equilibrium left (an added cubic stiffness that cancels the
// form's): every level counts as S_mod = 0, with the reason, as for any unsolvable θ; the
// evaluation and its nearby steps say so instead of throwing (a diagnosis's candidate grid
// reaches such θ).
TEST(EdcObjective, ThetaWithoutAWellIsAFiniteCostNotAnError) {
  const Model truth = paper_model();
  ModelForm form = ModelForm::paper(truth);
  form.add_term(std::make_unique<PolynomialStiffness>(std::vector<double>{0, 0, 0, 0}),
                {{"c3", -2e6, 2e6}});
  const EdcObjective objective(form, testing::twin_dataset(truth, {}, testing::few_levels_n()),
                               testing::twin_settings());
  Eigen::VectorXd theta(form.size());
  theta << form.initial().head(6), -1.5e6;  // k3 ≈ 7.3e5 N/m³ of Table 1 turned negative
  const EdcEvaluation e = objective.evaluate(theta);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("equilibrium"), std::string::npos) << e.message;
  EXPECT_NEAR(e.weighted_cost, 10 * 1e4, 1e-6);
  EdcEvaluation at;
  std::vector<EdcEvaluation> around;
  EXPECT_FALSE(objective.evaluate_nearby(theta, {theta}, at, around));
  EXPECT_TRUE(around.empty());
}

TEST(EdcObjective, WeightsMultiplyTheSquaredResiduals) {
  const Model truth = paper_model();
  const EdcObjective objective(
      ModelForm::paper(truth),
      scaled(testing::twin_dataset(truth, {}, testing::few_levels_n()), 1.1),
      testing::twin_settings());
  std::vector<double> weights(10, 0.0);
  weights[3] = 2.0;
  const EdcEvaluation e = objective.evaluate(objective.form().initial(), &weights);
  EXPECT_NEAR(e.weighted_cost, 2.0 * std::pow(0.1 / 0.011, 2), 1e-8);
}

// The σ budget: each level's σ² is the sum of its three parts, the bias part is the estimator's
// stated relative bias, the cycles part is the level's standard error.
TEST(SigmaBudget, AddsCyclesBiasAndModelErrorInQuadrature) {
  HbmOptions converged;
  converged.harmonics = 31;
  EdcDataset data = testing::twin_dataset(paper_model(), converged, testing::few_levels_n());
  for (EdcGroup& g : data.groups) {
    for (MeasuredLevel& level : g.levels) {
      level.edc_std_j = 0.004 * level.edc_j;
      level.cycles = 16;  // σ_mean = 1e-3 S
    }
  }
  const EdcObjective objective(ModelForm::paper(paper_model()), data);
  const SigmaBudget& b = objective.budget();
  ASSERT_EQ(b.total_j.size(), 10u);
  std::size_t k = 0;
  for (const EdcGroup& g : data.groups) {
    for (const MeasuredLevel& level : g.levels) {
      EXPECT_NEAR(b.cycles_j[k], 1e-3 * level.edc_j, 1e-15);
      EXPECT_NEAR(b.bias_j[k], kEdcEstimatorBiasRel * level.edc_j, 1e-15);
      EXPECT_NEAR(
          b.total_j[k] * b.total_j[k],
          b.cycles_j[k] * b.cycles_j[k] + b.bias_j[k] * b.bias_j[k] + b.model_j[k] * b.model_j[k],
          1e-12 * b.total_j[k] * b.total_j[k]);
      EXPECT_DOUBLE_EQ(objective.sigma_j()[k], b.total_j[k]);
      ++k;
    }
  }
}

// Convergence under refinement: data of the paper's model from harmonic balance at H = 40 (off the
// budget's ladder of references 15, 23, 31, 47, 63, so the reference is another discretisation).
// The fit's model side runs at H = 7, whose truncation alone misses these EDCs by many σ (σ is only
// the 5e-4 estimator bias here: twin data has no cycles); the defect correction brings the truth
// within 1 σ at every level, as the budget promises (its model error is at most 0.3 of the
// measurement σ, and the correction is exact at the calibration θ, which is the truth here).
TEST(SigmaBudget, DefectCorrectionReachesTheReferenceAccuracy) {
  HbmOptions converged;
  converged.harmonics = 40;
  const Model truth = paper_model();
  const EdcDataset data = testing::twin_dataset(truth, converged, testing::few_levels_n());
  const EdcObjective corrected(ModelForm::paper(truth), data);
  const SigmaBudget& b = corrected.budget();
  EXPECT_EQ(b.harmonics, 7);
  EXPECT_GE(b.reference_harmonics, 15);
  EXPECT_TRUE(b.resolved);
  const EdcEvaluation e = corrected.evaluate(corrected.form().initial());
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_LT(e.residuals.cwiseAbs().maxCoeff(), 1.0);

  // The same σ without the correction: H = 7 alone.
  EdcCostSettings plain;
  plain.budget = b;
  for (double& c : plain.budget->correction_j) c = 0.0;
  const EdcObjective uncorrected(ModelForm::paper(truth), data, plain);
  const EdcEvaluation u = uncorrected.evaluate(uncorrected.form().initial());
  EXPECT_GT(u.residuals.cwiseAbs().maxCoeff(), 5.0);
  std::printf("max |residual|: %.3g sigma corrected to H = %d, %.3g sigma at H = 7 alone\n",
              e.residuals.cwiseAbs().maxCoeff(), b.reference_harmonics,
              u.residuals.cwiseAbs().maxCoeff());
}

// A fold moved by the truncation: the paper's model at one harmonic against its reference puts
// some levels next to a jump on different branches. Those levels (and only those) are flagged
// branch-ambiguous: no correction, σ_model at least the gap, fingerprints left out; every other
// level's correction is a truncation defect below the gap threshold. At H = 7 on the same data no
// level is flagged (its largest defect is a few per cent).
TEST(SigmaBudget, ALevelOnAnotherBranchAtTheReferenceGetsNoCorrection) {
  HbmOptions converged;
  converged.harmonics = 31;
  const Model truth = paper_model();
  const EdcDataset data = testing::twin_dataset(truth, converged);
  EdcCostSettings coarse;
  coarse.hbm.harmonics = 1;
  const EdcObjective one(ModelForm::paper(truth), data, coarse);
  const EdcObjective seven(ModelForm::paper(truth), data);
  int flagged = 0;
  const SigmaBudget& b = one.budget();
  ASSERT_EQ(b.branch_ambiguous.size(), b.correction_j.size());
  for (std::size_t k = 0; k < b.correction_j.size(); ++k) {
    if (b.branch_ambiguous[k]) {
      ++flagged;
      EXPECT_EQ(b.correction_j[k], 0.0);
      EXPECT_EQ(b.correction_z1_m[k], 0.0);
      EXPECT_GT(b.model_j[k], 0.0);
    }
    EXPECT_FALSE(seven.budget().branch_ambiguous[k]) << "level " << k;
  }
  const EdcEvaluation e = one.evaluate(one.form().initial());
  EXPECT_EQ(e.branch_ambiguous, b.branch_ambiguous);
  EXPECT_GE(flagged, 1);
  std::printf("H = 1: %d of %zu levels on another branch than at H_ref = %d\n", flagged,
              b.correction_j.size(), b.reference_harmonics);
}

TEST(SigmaBudget, AdoptsCorrectionsOnlyWhereTheyAreNotAmbiguous) {
  SigmaBudget own;
  own.correction_j = {1.0, 2.0};
  own.correction_z1_m = {1.0, 2.0};
  own.correction_h2 = own.correction_h3 = {0.0, 0.0};
  own.total_j = {5.0, 6.0};
  SigmaBudget other = own;
  other.correction_j = {10.0, 20.0};
  other.correction_z1_m = {10.0, 20.0};
  other.branch_ambiguous = {false, true};
  own.adopt_corrections(other);
  EXPECT_EQ(own.correction_j, (std::vector<double>{10.0, 2.0}));
  EXPECT_EQ(own.correction_z1_m, (std::vector<double>{10.0, 2.0}));
  EXPECT_EQ(own.total_j, (std::vector<double>{5.0, 6.0}));  // σ is its own
  SigmaBudget shorter = other;
  shorter.correction_j = {1.0};
  EXPECT_THROW(own.adopt_corrections(shorter), InputError);
}

TEST(EdcObjective, RejectsLevelsWithNoSpreadAndNoFloor) {
  EdcCostSettings settings;
  settings.model_error_rel = 0.0;
  EXPECT_THROW(
      EdcObjective(ModelForm::paper(paper_model()),
                   testing::twin_dataset(paper_model(), {}, testing::few_levels_n()), settings),
      InputError);
}

// The nearby evaluations (one Newton step per level from θ's solutions) against the derivative of
// the solved evaluations by central differences: the implicit-function derivative is exact to
// first order, so the two agree to the central difference's own error, O(h²) of the parameter
// step plus the Newton tolerance (1e-11 N) over the step, both far below 1e-4 of the derivative.
// For the sliding law and for the friction in its presliding regime at δ = 3 µm (H raised to
// resolve the stuck contact's ringing, the exact march's Jacobian).
void expect_nearby_derivatives_match(const Model& truth) {
  const EdcObjective objective(ModelForm::paper(truth),
                               testing::twin_dataset(paper_model(), {}, testing::few_levels_n()),
                               testing::twin_settings());
  const Eigen::VectorXd theta = objective.form().initial();
  constexpr double kNearbyStep = 1e-7, kCentralStep = 1e-5;  // relative to each parameter
  std::vector<Eigen::VectorXd> nearby;
  for (int j = 0; j < theta.size(); ++j) {
    nearby.push_back(theta);
    nearby.back()[j] += kNearbyStep * theta[j];
  }
  EdcEvaluation at;
  std::vector<EdcEvaluation> around;
  ASSERT_TRUE(objective.evaluate_nearby(theta, nearby, at, around));
  ASSERT_EQ(around.size(), nearby.size());
  EXPECT_NEAR(at.weighted_cost, objective.evaluate(theta).weighted_cost, 1e-12);
  for (int j = 0; j < theta.size(); ++j) {
    Eigen::VectorXd up = theta, down = theta;
    up[j] += kCentralStep * theta[j];
    down[j] -= kCentralStep * theta[j];
    const EdcEvaluation e_up = objective.evaluate(up), e_down = objective.evaluate(down);
    ASSERT_TRUE(e_up.ok && e_down.ok);
    const Eigen::VectorXd central =
        (e_up.residuals - e_down.residuals) / (2.0 * kCentralStep * theta[j]);
    const Eigen::VectorXd linear = (around[j].residuals - at.residuals) / (kNearbyStep * theta[j]);
    EXPECT_LE((linear - central).norm(), 1e-4 * central.norm() + 1e-6)
        << objective.form().names()[j] << ": |d| " << central.norm();
    for (std::size_t k = 0; k < at.z1_abs_m.size(); ++k) {
      const double d_central =
          (e_up.z1_abs_m[k] - e_down.z1_abs_m[k]) / (2.0 * kCentralStep * theta[j]);
      const double d_linear = (around[j].z1_abs_m[k] - at.z1_abs_m[k]) / (kNearbyStep * theta[j]);
      EXPECT_NEAR(d_linear, d_central, 1e-4 * std::abs(d_central) + 1e-12)
          << objective.form().names()[j] << " level " << k;
    }
  }
}

TEST(EdcObjective, NearbyEvaluationsFollowTheSolvedDerivative) {
  expect_nearby_derivatives_match(paper_model());
}

TEST(EdcObjective, NearbyEvaluationsFollowTheSolvedDerivativeInThePreslidingRegime) {
  Model truth = paper_model();
  truth.set_parameter(1, "presliding_length_m", 3e-6);
  expect_nearby_derivatives_match(truth);
}

}  // namespace
}  // namespace oscilab::analysis
