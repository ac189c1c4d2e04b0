// Blind diagnoses of virtual-rig campaigns (stepped sines 0.2 → 2.7 N at 9 Hz in both wells and a
// 60 s random record, sensor noise, bias, quantisation and creep, analysed by the pipeline): the
// paper's model with one hidden effect at a mid strength, 0.3 × its reference strength
// (hidden_effect_campaign.h: the strengths of the first campaign, each several σ above detection),
// one seed each, two controls (the paper's model with its friction parameters moved by up to
// ±30 %) and a pair of effects hidden together. Built a second time with
// OSCILAB_HIDDEN_EFFECT_STRONG (analysis_diagnosis_strong_tests, label `study`): every effect at
// ten times that strength, 25 to 115 s each, run with `ctest -L study` and by the detection-power
// study, not by CI. Asserted per run, against the truth only this test knows:
// - the verdict names the hidden effect (`none` for a control);
// - the effect is named on its own first (one accepted step for it), and the EDC itself supports
//   it (Δχ² < −9);
// - the gap closes: the final reduced χ² is at most half the baseline's (measured: from hundreds or
//   thousands down to 0.1–0.3, below the noise level 1 + 3√(2/ν) ≈ 1.6).
// The detection-power study (scripts/diagnosis_power_study.sh, docs/diagnosis.md) sweeps strengths,
// frequencies, noise and seeds; this is its fast corner for CI. Labelled slow: release only.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/diagnosis/diagnosis.h"
#include "analysis/identification/campaign_model.h"
#include "tests/analysis/diagnosis/hidden_effect_campaign.h"
#include "tests/analysis/identification/twin_data.h"

#ifndef OSCILAB_HIDDEN_EFFECT_STRONG
#define OSCILAB_HIDDEN_EFFECT_STRONG 0  // 1: the ten-times-stronger effects only
#endif

namespace oscilab::analysis {
namespace {

struct Case {
  std::string effect;  // "none": a control
  double scale = 1.0;  // × the reference strength; the control's seed otherwise
};

DiagnosisResult diagnose_blind(const Model& truth, std::uint64_t seed,
                               std::vector<DiagnosisProgress>* reports = nullptr) {
  const CampaignAnalysis campaign =
      testing::record_campaign(truth, seed, testing::paper_levels_n());
  std::vector<std::string> notes;
  const Model base = campaign_model(paper_model(), campaign, StiffnessSource::Model, notes);
  DiagnosisOptions options;
  options.seed = seed;
  // No wall-clock bound here: this test checks what is named, not how fast (the study and its
  // timings say that); under a loaded CI machine a bound would make the verdict timing-dependent.
  options.max_seconds = 0.0;
  std::mutex mutex;
  return diagnose(campaign, ModelForm::paper(base), options, [&](const DiagnosisProgress& p) {
    const std::lock_guard lock(mutex);  // the reports are serialised; the test checks it too
    if (reports) reports->push_back(p);
  });
}

// The progress a diagnosis reported: its fraction never goes back and ends at 1; its phases come
// in their order (the baseline's search and settling, then per step the candidates, the
// finalists and the accepted model's settling); every candidate of a step is reported done; the
// baseline's evaluations are counted, at most what the baseline spent; an accepted effect is named
// while its model is settled.
void expect_honest_progress(const std::vector<DiagnosisProgress>& reports,
                            const DiagnosisResult& r) {
  ASSERT_FALSE(reports.empty());
  EXPECT_EQ(reports.back().phase, DiagnosisPhase::Done);
  EXPECT_DOUBLE_EQ(reports.back().fraction, 1.0);
  long baseline_evaluations = 0;
  std::vector<std::string> accepting;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const DiagnosisProgress& p = reports[i];
    EXPECT_FALSE(p.describe().empty());
    if (i > 0) {
      EXPECT_GE(p.fraction, reports[i - 1].fraction);
      const bool same_step = p.step == reports[i - 1].step;
      if (p.phase != DiagnosisPhase::Done && same_step) {
        EXPECT_GE(static_cast<int>(p.phase), static_cast<int>(reports[i - 1].phase))
            << to_string(reports[i - 1].phase) << " then " << to_string(p.phase);
      }
      if (p.phase != DiagnosisPhase::Done) {
        EXPECT_GE(p.step, reports[i - 1].step);
      }
    }
    if (p.phase == DiagnosisPhase::Baseline) baseline_evaluations = p.evaluations;
    if (p.phase == DiagnosisPhase::Accepting &&
        (accepting.empty() || accepting.back() != p.candidate)) {
      accepting.push_back(p.candidate);
    }
    if (p.phase == DiagnosisPhase::Finalists) {
      // The step's candidates all reported done before its finalists.
      EXPECT_EQ(reports[i - 1].candidates_done, reports[i - 1].candidates);
    }
  }
  EXPECT_GT(baseline_evaluations, 0);
  EXPECT_LE(baseline_evaluations, r.baseline.evaluations);
  // The global search moves the bar in fine steps (CMA-ES reports every generation), not from
  // 0 to its end at once.
  std::vector<double> baseline_fractions;
  for (const DiagnosisProgress& p : reports) {
    if (p.phase == DiagnosisPhase::Baseline) baseline_fractions.push_back(p.fraction);
  }
  baseline_fractions.erase(std::unique(baseline_fractions.begin(), baseline_fractions.end()),
                           baseline_fractions.end());
  EXPECT_GE(baseline_fractions.size(), 10u);
  std::vector<std::string> accepted;
  for (const DiagnosisStep& s : r.steps) {
    if (s.effect != "none") accepted.push_back(candidate_label(s.effect, s.embodiment));
  }
  EXPECT_EQ(accepting, accepted);
}

class HiddenEffectDetection : public ::testing::TestWithParam<Case> {};

TEST_P(HiddenEffectDetection, NamesTheEffectAndClosesTheGap) {
  const Case& c = GetParam();
  Model truth = paper_model();
  std::uint64_t seed = 1;
  if (c.effect == "none") {
    seed = static_cast<std::uint64_t>(c.scale);
    std::mt19937_64 rng(seed * 7919);
    std::uniform_real_distribution<double> factor(0.7, 1.3);
    const ModelForm form = ModelForm::paper(paper_model());
    Eigen::VectorXd theta = form.initial();
    for (int i = 0; i < theta.size(); ++i) theta[i] *= factor(rng);
    truth = form.build(form.clamp(theta));
  } else {
    truth = testing::truth_with_effect(c.effect, c.scale);
  }
  std::vector<DiagnosisProgress> reports;
  const DiagnosisResult r = diagnose_blind(truth, seed, &reports);
  expect_honest_progress(reports, r);
  std::printf("%s %g: verdict %s, reduced chi2 %.4g -> %.4g, %zu steps, %.1f s\n", c.effect.c_str(),
              c.scale, r.verdict.c_str(), r.baseline_maps.reduced_chi2, r.final_maps.reduced_chi2,
              r.steps.size(), r.seconds);
  EXPECT_FALSE(r.incomplete) << r.message;
  EXPECT_EQ(r.verdict, c.effect);
  if (c.effect == "none") return;
  ASSERT_FALSE(r.steps.empty());
  EXPECT_EQ(r.steps.front().effect, c.effect);
  bool edc_supports = false;
  for (const EvidenceChange& e : r.steps.front().evidence) {
    if (e.name == "edc") edc_supports = e.supports();
  }
  EXPECT_TRUE(edc_supports);
  EXPECT_LE(r.final_maps.reduced_chi2, 0.5 * r.baseline_maps.reduced_chi2);
}

// Two effects hidden together at their reference strengths, presliding hysteresis and quadratic
// damping: both are accepted, each in a step of its own, and the verdict is one of them. A law
// accepted on the way as a stand-in for both (measured: cubic damping first) must have vanished
// from the final model and be reported as withdrawn, not as the verdict. The final model closes
// the gap (reduced χ² at most half the baseline's; measured 3049 → 0.22).
#if !OSCILAB_HIDDEN_EFFECT_STRONG
TEST(HiddenEffectPair, BothEffectsAreNamedEachInItsOwnStep) {
  const Model truth = testing::truth_with_effect("presliding-hysteresis+quadratic-damping", 1.0);
  const DiagnosisResult r = diagnose_blind(truth, 1);
  std::vector<std::string> standing;
  for (const DiagnosisStep& s : r.steps) {
    std::printf("step %s%s\n", s.effect.c_str(), s.withdrawn ? " (withdrawn)" : "");
    if (s.effect != "none" && !s.withdrawn) standing.push_back(s.effect);
    if (s.withdrawn) {
      ASSERT_TRUE(r.final_form);
      for (int i = 0; i < r.final_form->size(); ++i) {
        if (r.final_form->parameters()[i].name == s.strength_parameter) {
          EXPECT_LE(std::abs(r.final_theta(i)),
                    1e-3 * std::max(std::abs(r.final_form->parameters()[i].lower),
                                    std::abs(r.final_form->parameters()[i].upper)));
        }
      }
    }
  }
  const auto named = [&](const std::string& effect) {
    return std::find(standing.begin(), standing.end(), effect) != standing.end();
  };
  EXPECT_TRUE(named("presliding-hysteresis"));
  EXPECT_TRUE(named("quadratic-damping"));
  EXPECT_TRUE(r.verdict == "presliding-hysteresis" || r.verdict == "quadratic-damping")
      << r.verdict;
  EXPECT_LE(r.final_maps.reduced_chi2, 0.5 * r.baseline_maps.reduced_chi2);
}

#endif

std::vector<Case> cases() {
  std::vector<Case> out;
  for (const char* effect :
       {"presliding-hysteresis", "quadratic-damping", "cubic-damping", "stribeck-friction",
        "quadratic-stiffness", "cubic-stiffness", "quintic-stiffness"}) {
    out.push_back({effect, OSCILAB_HIDDEN_EFFECT_STRONG ? 3.0 : 0.3});
  }
  if (!OSCILAB_HIDDEN_EFFECT_STRONG) {
    out.push_back({"none", 1.0});
    out.push_back({"none", 2.0});
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(Campaigns, HiddenEffectDetection, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::string name =
                               info.param.effect + "_" +
                               std::to_string(static_cast<int>(10 * info.param.scale + 0.5));
                           for (char& ch : name) ch = ch == '-' ? '_' : ch;
                           return name;
                         });

}  // namespace
}  // namespace oscilab::analysis
