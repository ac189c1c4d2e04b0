// EDC identification on noise-free twin data of the paper's model, the identification targets:
// CMA-ES recovers θ in 3 of 4 seeds within 2000 evaluations; the paper's GA runs with its settings.
// Labelled slow: release build only (tests/CMakeLists.txt).
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "analysis/identification/campaign_model.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/model/reference_models.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"
#include "tests/analysis/identification/twin_data.h"

namespace oscilab::analysis {
namespace {

// Twin data of the paper's model; the truth is Table 3 (ModelForm::paper reads it back).
const EdcObjective& twin_objective() {
  static const EdcObjective objective(ModelForm::paper(paper_model()),
                                      testing::twin_dataset(paper_model()),
                                      testing::twin_settings());
  return objective;
}

// Identification target: the stronger method recovers f_d(z±*), k_s, c and v_t within 1 % in at
// least 3 of 4 seeds within 2000 model evaluations (noise-free data: the truth is the exact
// minimiser, so 1 % measures the optimiser alone).
TEST(EdcFitSlow, CmaesRecoversPaperFrictionInThreeOfFourSeeds) {
  const EdcObjective& objective = twin_objective();
  const Eigen::VectorXd truth = objective.form().initial();
  int recovered = 0;
  for (int seed = 1; seed <= 4; ++seed) {
    FitOptions options;
    options.seed = static_cast<std::uint64_t>(seed);
    options.compute_uncertainty = false;
    const FitResult fit = fit_edc(objective, options);
    EXPECT_EQ(fit.status, JobStatus::Ok) << fit.message;
    EXPECT_LE(fit.evaluations, 2000);
    const double worst = testing::worst_required_error(fit, truth);
    std::printf(
        "cmaes seed %d: %ld evaluations, %.2f s, chi2 %.3g, eq. (8) %.3g J, worst %.3f %%\n", seed,
        fit.evaluations, fit.seconds, fit.evaluation.weighted_cost, fit.evaluation.cost_j,
        100.0 * worst);
    if (worst < 0.01) ++recovered;
  }
  EXPECT_GE(recovered, 3);
}

// The paper's GA setting runs and reports its result as it is, even when it is worse.
TEST(EdcFitSlow, PaperGeneticAlgorithmRunsWithPaperSettings) {
  const EdcObjective& objective = twin_objective();
  FitOptions options;
  options.method = FitMethod::Genetic;
  options.compute_uncertainty = false;
  const FitResult fit = fit_edc(objective, options);
  EXPECT_EQ(fit.status, JobStatus::Ok) << fit.message;
  // 100 + 20 × (100 − 5 elite) evaluations.
  EXPECT_EQ(fit.evaluations, 2000);
  // The GA's best must beat a random start by far: the first generation's best is its history's
  // first entry, the final best is ≤ it, and the history is monotone.
  ASSERT_FALSE(fit.history.empty());
  for (std::size_t i = 1; i < fit.history.size(); ++i) {
    EXPECT_LE(fit.history[i].second, fit.history[i - 1].second);
  }
  EXPECT_LT(fit.evaluation.weighted_cost, fit.history.front().second);
  std::printf("paper GA: chi2 %.3g, eq. (8) %.3g J, worst parameter error %.1f %%, %.2f s\n",
              fit.evaluation.weighted_cost, fit.evaluation.cost_j,
              100.0 * testing::worst_required_error(fit, objective.form().initial()), fit.seconds);
}

// On data as the lab gets it: the paper's model on the virtual rig (sensor bias, noise,
// quantisation, table creep), both wells, 0.2 → 2.7 N, analysed by the project's own pipeline,
// fitted by CMA-ES with the σ budget (harmonic balance at H = 7, defect-corrected). The model side
// is then as accurate as the measurement, so the truth explains the data within its noise (reduced
// χ² at or below 1 + 3√(2/ν), three standard deviations of a correct model's), the fit explains it
// as well as the truth to within two standard deviations of χ² (√(2ν) ≈ 10: a difference the data
// cannot tell apart), both within 0.1 % mean deviation per well (measured: 0.03 % / 0.01 %; the
// old 1 % floor allowed 1.4 %), and the reported 95 % intervals hold the true f_d(z±*) and c.
//
// The budget is 4000 evaluations, what CMA-ES needs here: with seeds 1 to 8 it reached χ² 5.07
// every time (truth 7.54) and stopped by itself after 3 500 to 3 740 evaluations. At the default
// 2000 it stopped short along the weakly identified f_d(0) in 2 of the 8 seeds (χ² 75 and 79; with
// EDCs that differed only by rounding, 2 other seeds, χ² 140 and 178), so a test at 2000 passed or
// failed by its seed, not by the method.
TEST(EdcFitSlow, NoisyRigRecordsFitWithinTheirNoiseWithTruthInsideIntervals) {
  const Model truth = paper_model();
  SteppedSineSchedule schedule;
  schedule.levels_n = testing::paper_levels_n();
  std::vector<MeasurementChannels> records;
  for (bool positive : {true, false}) {
    daq::RigSpec spec;
    spec.positive_well = positive;
    spec.seed = positive ? 21 : 22;
    const daq::RigRecording rig = daq::record_stepped_sine(truth, schedule, spec);
    ASSERT_EQ(rig.status, TimeSimulator::Status::Ok) << rig.message;
    records.push_back(daq::measurement_channels(rig.recording));
  }
  const CampaignAnalysis campaign = analyze_campaign(records, PipelineSettings{});
  std::vector<std::string> notes;
  const Model base = campaign_model(truth, campaign, StiffnessSource::Model, notes);
  const EdcObjective objective(ModelForm::paper(base), edc_dataset(campaign));
  ASSERT_EQ(objective.level_count(), 52);

  FitOptions options;
  options.seed = 3;
  options.max_evaluations = 4000;
  const FitResult fit = fit_edc(objective, options);
  ASSERT_EQ(fit.status, JobStatus::Ok) << fit.message;
  const EdcEvaluation at_truth = objective.evaluate(objective.form().theta_of(truth));
  std::printf("noisy rig: fitted deviation %.3f %% / %.3f %%, truth %.3f %% / %.3f %%\n",
              fit.evaluation.mean_deviation_pct_positive,
              fit.evaluation.mean_deviation_pct_negative, at_truth.mean_deviation_pct_positive,
              at_truth.mean_deviation_pct_negative);
  const double dof = objective.level_count() - objective.form().size();
  std::printf("noisy rig: chi2 fitted %.4g, truth %.4g (%d levels)\n", fit.evaluation.weighted_cost,
              at_truth.weighted_cost, objective.level_count());
  EXPECT_LE(at_truth.weighted_cost / dof, 1.0 + 3.0 * std::sqrt(2.0 / dof));
  EXPECT_LE(fit.evaluation.weighted_cost, at_truth.weighted_cost + 2.0 * std::sqrt(2.0 * dof));
  EXPECT_LT(fit.evaluation.mean_deviation_pct_positive, 0.1);
  EXPECT_LT(fit.evaluation.mean_deviation_pct_negative, 0.1);

  const Eigen::VectorXd theta_true = objective.form().theta_of(truth);
  for (const ParameterUncertainty& p : fit.uncertainty.parameters) {
    const int i = static_cast<int>(&p - fit.uncertainty.parameters.data());
    std::printf("  %-12s true %.5g fitted %.5g, 95 %% [%.5g, %.5g]%s\n", p.name.c_str(),
                theta_true(i), p.value, p.lower_95, p.upper_95,
                p.weakly_identified ? " (weak)" : "");
    if (p.name == "fd_zminus_n" || p.name == "fd_zplus_n" || p.name == "c_ns_m") {
      EXPECT_GE(theta_true(i), p.lower_95) << p.name;
      EXPECT_LE(theta_true(i), p.upper_95) << p.name;
    }
  }
}

// The covariance's standard errors against a second method, the bootstrap over levels, on twin
// data with 2 % multiplicative noise (seeded): both estimate the same spread, so for the
// well-identified parameters they agree within a factor of 2.5 (a 30-replicate bootstrap's σ
// itself scatters by ~13 %, and the linearisation of the covariance is exact only to first
// order).
TEST(EdcFitSlow, CovarianceAndBootstrapAgreeOnNoisyTwinData) {
  const Model truth = paper_model();
  EdcDataset data = testing::twin_dataset(truth);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (EdcGroup& g : data.groups) {
    for (MeasuredLevel& level : g.levels) {
      level.edc_j *= 1.0 + noise(rng);
      level.edc_std_j = 0.02 * level.edc_j * 4.0;  // σ_mean = 2 % with 16 cycles
      level.cycles = 16;
    }
  }
  EdcCostSettings settings = testing::twin_settings();
  settings.model_error_rel = 0.0;  // the noise is all there is
  const EdcObjective objective(ModelForm::paper(truth), data, settings);
  FitOptions options;
  options.method = FitMethod::Local;  // from the truth: this test is about the uncertainty
  options.max_evaluations = 600;
  options.uncertainty.bootstrap_replicates = 30;
  const FitResult fit = fit_edc(objective, options);
  ASSERT_EQ(fit.uncertainty.bootstrap_replicates, 30);
  for (const ParameterUncertainty& p : fit.uncertainty.parameters) {
    std::printf("  %-12s se %.3g bootstrap %.3g%s\n", p.name.c_str(), p.standard_error,
                p.bootstrap_std, p.weakly_identified ? (" weak: " + p.note).c_str() : "");
    if (p.weakly_identified) continue;
    EXPECT_LT(p.bootstrap_std / p.standard_error, 2.5) << p.name;
    EXPECT_GT(p.bootstrap_std / p.standard_error, 1.0 / 2.5) << p.name;
  }
}

}  // namespace
}  // namespace oscilab::analysis
