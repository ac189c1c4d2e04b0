// Fingerprints of the model-gap workflow: power-law slopes, candidate catalogue, and the
// maps on twin data with a known missing energy.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "analysis/diagnosis/discrepancy_maps.h"
#include "analysis/diagnosis/effect_candidates.h"
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

}  // namespace
}  // namespace oscilab::analysis
