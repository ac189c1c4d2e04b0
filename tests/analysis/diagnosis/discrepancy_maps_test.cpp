// Fingerprints of the model-gap workflow: power-law slopes, candidate catalogue, and the
// maps on twin data with a known missing energy.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "analysis/diagnosis/discrepancy_maps.h"
#include "analysis/diagnosis/effect_candidates.h"
#include "analysis/diagnosis/joint_refit.h"
#include "analysis/diagnosis/log_slope.h"
#include "analysis/model/reference_models.h"
#include "tests/analysis/identification/twin_data.h"

namespace oscilab::analysis {
namespace {

TEST(LogSlope, RecoversAnExactPowerLaw) {
  std::vector<double> x, y;
  for (int i = 1; i <= 8; ++i) {
    x.push_back(1e-4 * i);
    y.push_back(3.0 * std::pow(1e-4 * i, 3.0));
  }
  const LogSlope s = log_slope(x, y);
  EXPECT_EQ(s.points, 8);
  EXPECT_NEAR(s.slope, 3.0, 1e-12);
  EXPECT_LT(s.standard_error, 1e-10);
}

TEST(LogSlope, IntervalCoversTheTrueSlopeUnderNoise) {
  // 5 % log-normal scatter on y ∝ x²: over 200 seeded trials the 95 % interval holds the true
  // slope in 95 ± 3 % of them (binomial σ = 1.5 %: a ±2σ band).
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.05);
  int covered = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> x, y;
    for (int i = 1; i <= 10; ++i) {
      x.push_back(i * 1e-3);
      y.push_back(std::pow(i * 1e-3, 2.0) * std::exp(noise(rng)));
    }
    const LogSlope s = log_slope(x, y);
    if (s.lower_95 <= 2.0 && 2.0 <= s.upper_95) ++covered;
  }
  EXPECT_NEAR(covered / 200.0, 0.95, 0.03);
}

TEST(LogSlope, SkipsNonPositivePairs) {
  const LogSlope s = log_slope({1.0, -1.0, 2.0, 0.0}, {1.0, 1.0, 4.0, 3.0});
  EXPECT_EQ(s.points, 2);
  EXPECT_NEAR(s.slope, 2.0, 1e-12);
  EXPECT_TRUE(std::isinf(s.standard_error));  // two points: no spread to estimate
  EXPECT_FALSE(log_slope({1.0}, {1.0}).valid());
}

TEST(EffectCandidates, PaperFormGetsEveryEffectItDoesNotHold) {
  const ModelForm form = ModelForm::paper(paper_model());
  const EdcDataset data = testing::twin_dataset(paper_model(), {}, testing::few_levels_n());
  std::vector<std::string> names;
  int friction_regimes = 0;
  for (const auto& c : effect_candidates(form, data)) {
    names.push_back(c.effect);
    if (!c.term) {
      // A change of the law the form holds: presliding as the friction's own regime.
      EXPECT_EQ(c.embodiment, "friction-regime") << c.effect;
      EXPECT_EQ(c.changes_type, "position-dependent-friction");
      EXPECT_FALSE(c.can_vanish);
      const ModelForm extended = c.extend(form, c.scan.front());
      EXPECT_EQ(extended.size(), form.size() + 1);
      EXPECT_EQ(extended.build(extended.initial()).state_size(), 1);
      ++friction_regimes;
    } else {
      EXPECT_EQ(c.term->type() == "polynomial-stiffness", c.stiffness) << c.effect;
    }
    EXPECT_FALSE(c.scan.empty()) << c.effect;
    for (const auto& start : c.scan) {
      ASSERT_EQ(start.size(), static_cast<Eigen::Index>(c.free.size()));
      for (std::size_t i = 0; i < c.free.size(); ++i) {
        EXPECT_GE(start(i), c.free[i].lower) << c.effect;
        EXPECT_LE(start(i), c.free[i].upper) << c.effect;
      }
    }
  }
  // The paper's form has viscous damping and position-dependent friction already.
  // Presliding comes in two embodiments: an added Dahl element and the friction's own regime.
  const std::vector<std::string> expected = {
      "coulomb-friction",    "quadratic-damping",     "cubic-damping",
      "stribeck-friction",   "presliding-hysteresis", "presliding-hysteresis",
      "quadratic-stiffness", "cubic-stiffness",       "quintic-stiffness"};
  EXPECT_EQ(names, expected);
  EXPECT_EQ(friction_regimes, 1);
  // With the stiffness identified, its own powers are no missing effect: only the quintic stays.
  ModelForm identified = form;
  identified.free_stiffness();
  std::vector<std::string> stiffness_names;
  for (const auto& c : effect_candidates(identified, data)) {
    if (c.stiffness) stiffness_names.push_back(c.effect);
  }
  EXPECT_EQ(stiffness_names, std::vector<std::string>{"quintic-stiffness"});
  // Every candidate and `none` is in the contract's vocabulary.
  for (const auto& n : names) {
    EXPECT_NE(std::find(effect_vocabulary().begin(), effect_vocabulary().end(), n),
              effect_vocabulary().end());
  }
}

// Twin data whose measured EDC exceeds the model's by ΔS = a Z³ (a quadratic damping's law): the
// missing-energy slope over the levels must be 3 within its interval, and the residuals in σ
// must be ΔS/σ_k.
TEST(DiscrepancyMaps, MissingEnergySlopeNamesTheLaw) {
  const Model truth = paper_model();
  EdcDataset data = testing::twin_dataset(truth);
  const ModelForm form = ModelForm::paper(truth);
  // Amplitudes: take |Z1| ∝ S^(1/2) as a stand-in (the slope test needs only a positive
  // amplitude per level); ΔS = 0.05 S_max (Z/Z_max)³ dominates the σ floor at the top levels.
  double s_max = 0.0;
  for (const auto& g : data.groups)
    for (const auto& m : g.levels) s_max = std::max(s_max, m.edc_j);
  for (auto& g : data.groups) {
    for (auto& m : g.levels) {
      m.amplitude_m = std::sqrt(m.edc_j / s_max) * 1e-2;
      m.edc_j += 0.05 * s_max * std::pow(m.amplitude_m / 1e-2, 3.0);
    }
  }
  const EdcObjective objective(form, data, testing::twin_settings());
  const EdcEvaluation e = objective.evaluate(form.initial());
  const DiscrepancyMaps maps = discrepancy_maps(objective, form.initial(), e, CampaignAnalysis{});
  ASSERT_GE(maps.slopes.missing_all.points, 5);
  EXPECT_NEAR(maps.slopes.missing_all.slope, 3.0, 0.05);
  EXPECT_FALSE(maps.stiffness.available);  // no stiffness slice in an empty campaign
  for (const auto& d : maps.levels) {
    EXPECT_NEAR(d.residual_sigma, (d.edc_mes_j - d.edc_mod_j) / d.sigma_j, 1e-12);
  }
  EXPECT_GT(maps.max_abs_residual_sigma, 3.0);
}

// One level far off (as a level just across a fold from the model is): twin data of the paper's
// model with the negative well's 2.1 N level three times its value (67 σ), each refit started at
// the truth, the exact minimiser of the other levels. The plain least-squares refit is pulled
// towards the far level; the refit under the Cauchy loss must stay where the plain refit of the
// same data without that level stays (a second, outlier-free fit as the reference), and its plain
// χ² must still count the far level.
TEST(JointRefit, CauchyLossLetsTheOtherLevelsPlaceTheta) {
  const ModelForm form = ModelForm::paper(paper_model());
  const EdcDataset clean = testing::twin_dataset(paper_model());
  constexpr int kFar = 19;  // 0.2 N + 19 × 0.1 N
  EdcDataset corrupted = clean;
  ASSERT_EQ(corrupted.groups.size(), 2U);
  ASSERT_FALSE(corrupted.groups[1].positive_well);
  MeasuredLevel& far = corrupted.groups[1].levels[kFar];
  ASSERT_NEAR(far.f0_n, 2.1, 1e-12);
  far.edc_j *= 3.0;
  EdcDataset without = clean;
  without.groups[1].levels.erase(without.groups[1].levels.begin() + kFar);

  const EdcCostSettings settings = testing::twin_settings();
  const EdcObjective with_far(form, corrupted, settings);
  const EdcObjective reference_objective(form, without, settings);
  const Eigen::VectorXd truth = form.initial();
  const Eigen::VectorXd start = truth;  // the exact minimiser of the clean levels
  const CancelToken none;
  const JointRefit plain = joint_refit(with_far, start, false, 600, none);
  const JointRefit robust = joint_refit(with_far, start, false, 600, none, 3.0);
  const JointRefit reference = joint_refit(reference_objective, start, false, 600, none);
  ASSERT_GT(plain.theta.size(), 0);
  ASSERT_GT(robust.theta.size(), 0);
  ASSERT_GT(reference.theta.size(), 0);

  // Distances in the unit cube of the form's bounds, over the parameters the EDC identifies
  // (f_d(0) is weak, §5: it is left out).
  const auto distance = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    const Eigen::VectorXd d = form.to_unit(a) - form.to_unit(b);
    double worst = 0.0;
    for (int i = 0; i < form.size(); ++i) {
      if (form.names()[static_cast<std::size_t>(i)] != "fd_zero_n") {
        worst = std::max(worst, std::abs(d(i)));
      }
    }
    return worst;
  };
  const double robust_off = distance(robust.theta, reference.theta);
  const double plain_off = distance(plain.theta, reference.theta);
  // The reference refit is the truth to the solver's tolerance (noise-free twin data).
  EXPECT_LT(distance(reference.theta, truth), 1e-3);
  // Measured: the Cauchy refit 4e-5 from the reference, the plain one 0.013 off (f_d(0) aside;
  // c 6.5 % high). The bounds: 1e-3 (the LM's tolerance is far below it) and 5e-3.
  EXPECT_LT(robust_off, 1e-3);
  EXPECT_GT(plain_off, 5e-3);
  // The best point's χ² is the plain one: the far level's are in it (at the truth, the χ² is that
  // level's alone: 4 444, its residual 67 σ).
  EXPECT_GT(robust.joint_chi2, 0.99 * with_far.evaluate(truth).weighted_cost);
  EXPECT_GT(robust.joint_chi2, plain.joint_chi2);
}

}  // namespace
}  // namespace oscilab::analysis
