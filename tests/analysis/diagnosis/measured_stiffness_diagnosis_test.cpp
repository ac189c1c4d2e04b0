// Diagnoses as a lab runs them: the mass known, the stiffness identified from the records (the
// random record's stiffness slice as the start, the coefficients free in the baseline with the
// friction), never the simulator's K(z). Virtual-rig campaigns (stepped sines 0.2 → 2.7 N at
// 9 Hz in both wells and a 60 s random record, sensor noise, bias, quantisation and creep),
// analysed by the pipeline; asserted against the truth only this test knows:
// - the paper's model without a hidden effect says `none`, and the gap is explained;
// - the friction's own presliding regime (its Coulomb part a Dahl state of presliding length
//   δ = 1 µm and 30 µm) is named presliding-hysteresis and the final model reaches the noise;
// - a control whose six friction parameters are moved (±30 %), recorded with twice the sensor
//   noise, with the fit started from the paper's values, says `none`;
// - a control whose baseline stops in a basin of its own stiffness, which a candidate's refit
//   finds, says `none` (the nested check);
// - an effect outside the vocabulary (a damper that engages beyond the positive well, c (z − z₊*)²
//   ż for z > z₊*) leaves the gap open and the report says so (`gap_explained` false).
// Labelled slow (whole diagnoses): release build only.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "analysis/diagnosis/diagnosis.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/model/position_dependent_friction.h"
#include "tests/analysis/diagnosis/hidden_effect_campaign.h"
#include "tests/analysis/identification/twin_data.h"

namespace oscilab::analysis {
namespace {

// The diagnosis a lab runs: `diagnose --model paper --stiffness identified` (the paper's model as
// the starting point of the friction and the stiffness, the stiffness identified).
DiagnosisResult diagnose_as_a_lab(
    const Model& truth, std::uint64_t seed, double noise_scale = 1.0, double freq_hz = 9.0,
    int threads = 0, const std::vector<double>& levels_n = testing::paper_levels_n(),
    long baseline_evaluations = DiagnosisOptions{}.baseline_evaluations) {
  testing::CampaignSpec spec;
  spec.noise_scale = noise_scale;
  spec.freq_hz = freq_hz;
  const CampaignAnalysis campaign = testing::record_campaign(truth, seed, levels_n, spec);
  FitSetup setup;
  setup.stiffness = StiffnessSource::Identified;
  std::vector<std::string> notes;
  const ModelForm form = fit_form(campaign, setup, notes);
  for (const std::string& note : notes) std::printf("note: %s\n", note.c_str());
  DiagnosisOptions options;
  options.seed = seed;
  options.cost = setup.cost;
  options.max_seconds = 0.0;  // what is named, not how fast (as hidden_effect_detection_test)
  options.threads = threads;
  options.baseline_evaluations = baseline_evaluations;
  const DiagnosisResult r = diagnose(campaign, form, options);
  std::printf(
      "verdict %s, reduced chi2 %.4g -> %.4g (noise level %.3g), gap explained %d, %.1f s\n",
      r.verdict.c_str(), r.baseline_maps.reduced_chi2, r.final_maps.reduced_chi2,
      r.final_noise_reduced_chi2, r.gap_explained ? 1 : 0, r.seconds);
  for (const DiagnosisStep& s : r.steps) {
    std::printf("  step %s (%s)%s\n", s.effect.c_str(), s.embodiment.c_str(),
                s.withdrawn ? " withdrawn" : "");
  }
  return r;
}

TEST(MeasuredStiffnessDiagnosis, PaperModelWithoutEffectSaysNone) {
  const DiagnosisResult r = diagnose_as_a_lab(paper_model(), 1);
  EXPECT_EQ(r.verdict, "none");
  EXPECT_TRUE(r.gap_explained) << r.message;
  // The stiffness was free: the baseline's parameters hold the identified coefficients.
  bool identified = false;
  for (const std::string& name : r.baseline.names)
    identified = identified || name == "stiffness_c3_n_m3";
  EXPECT_TRUE(identified);
}

class FrictionRegimePresliding : public ::testing::TestWithParam<double> {};

TEST_P(FrictionRegimePresliding, IsNamedAndTheGapClosesToTheNoise) {
  const DiagnosisResult r = diagnose_as_a_lab(testing::paper_with_presliding(GetParam()), 1);
  EXPECT_EQ(r.verdict, "presliding-hysteresis");
  EXPECT_TRUE(r.gap_explained) << r.message;
  EXPECT_LE(r.final_maps.reduced_chi2, r.final_noise_reduced_chi2);
  // The baseline (the sliding law) misses the data, so it was refitted robustly, and the report
  // says what that cost: part of the baseline's time, which is part of the diagnosis's.
  const nlohmann::json baseline = diagnosis_report_json(r, {"a", "b", "c"}).at("baseline");
  EXPECT_TRUE(baseline.at("robust_refit").get<bool>());
  const double baseline_s = baseline.at("seconds").get<double>();
  const double robust_s = baseline.at("robust_refit_seconds").get<double>();
  EXPECT_GT(robust_s, 0.0);
  EXPECT_LT(robust_s, baseline_s);
  EXPECT_LT(baseline_s, r.seconds);
}

// 30 µm, and 1 µm, where the stuck contact rings at 28 times the forcing (255 Hz, next to the
// records' Nyquist frequency) and every evaluation runs at H = 43; the lengths between are the
// study's (scripts/diagnosis_power_study.sh, docs/diagnosis.md).
INSTANTIATE_TEST_SUITE_P(Lengths, FrictionRegimePresliding, ::testing::Values(1e-6, 3e-5),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return "delta_" +
                                  std::to_string(static_cast<int>(info.param * 1e6 + 0.5)) + "um";
                         });

TEST(MeasuredStiffnessDiagnosis, MovedFrictionControlStartedFarSaysNone) {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> factor(0.7, 1.3);
  const ModelForm form = ModelForm::paper(paper_model());
  Eigen::VectorXd theta = form.initial();
  for (int i = 0; i < theta.size(); ++i) theta[i] *= factor(rng);
  const Model truth = form.build(form.clamp(theta));
  const DiagnosisResult r = diagnose_as_a_lab(truth, 3, 2.0);
  EXPECT_EQ(r.verdict, "none");
  EXPECT_TRUE(r.gap_explained) << r.message;
}

// A control whose baseline search stops short of the form's own minimum, where a candidate's
// refit with all parameters free (a quintic stiffness's) goes on to it: refitted from that θ
// without the term, the form itself gets there, the nested check makes that the baseline and
// measures the candidates again, and nothing is named. The baseline's search is cut to 200
// evaluations (of 1500) so that it stops short whatever the last bits of the campaign: where the
// full search stops depends on them (the study's control of seed 65 stopped in a basin of its
// stiffness, χ²/ν 59 against the truth's 0.38, with one build and reached the deep basin with
// another). The study's control of seed 65: friction moved as its seed draws, 8.15 Hz, noise
// ×2.02; on its level grid and on the paper's (six levels differ in their last bit).
class ShortBaseline : public ::testing::TestWithParam<bool> {};

TEST_P(ShortBaseline, ABasinOfTheFormItselfIsNotCreditedToAnEffect) {
  std::mt19937_64 rng(65 * 7919);
  std::uniform_real_distribution<double> factor(0.7, 1.3);
  const ModelForm form = ModelForm::paper(paper_model());
  Eigen::VectorXd theta = form.initial();
  for (int i = 0; i < theta.size(); ++i) theta[i] *= factor(rng);
  std::vector<double> levels_n = testing::paper_levels_n();
  if (GetParam()) {  // the study's grid: 0.2 → 2.7 N in 26 even steps
    levels_n.clear();
    for (int i = 0; i < 26; ++i) levels_n.push_back(0.2 + 2.5 * i / 25);
  }
  const DiagnosisResult r =
      diagnose_as_a_lab(form.build(form.clamp(theta)), 65, 2.02, 8.15, 0, levels_n, 200);
  EXPECT_EQ(r.verdict, "none");
  EXPECT_TRUE(r.gap_explained) << r.message;
  EXPECT_GE(r.rebases, 1);  // the baseline was refitted from a candidate's basin
  EXPECT_LE(r.final_maps.reduced_chi2, r.final_noise_reduced_chi2);
}

INSTANTIATE_TEST_SUITE_P(Grids, ShortBaseline, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "study_grid" : "paper_grid";
                         });

TEST(MeasuredStiffnessDiagnosis, EffectOutsideTheVocabularyLeavesTheGapOpenAndSaysSo) {
  Model truth = paper_model();
  truth.add_term(std::make_unique<testing::OneSidedDamper>(2e6, truth.well(true).z_m));
  const DiagnosisResult r = diagnose_as_a_lab(truth, 2);
  EXPECT_FALSE(r.gap_explained);
  EXPECT_GT(r.final_maps.reduced_chi2, r.final_noise_reduced_chi2);
  EXPECT_NE(r.message.find("gap is not explained"), std::string::npos) << r.message;
  const nlohmann::json report = diagnosis_report_json(r, {"a", "b", "c"});
  EXPECT_FALSE(report.at("gap_explained").get<bool>());
  EXPECT_FALSE(report.at("gap").at("largest_residual_levels").empty());
}

}  // namespace
}  // namespace oscilab::analysis
