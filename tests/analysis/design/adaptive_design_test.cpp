// The adaptive test's core on twin data: BIC weights, the stop rule, the parameters' covariance
// against a second method, where the next point goes, and the weights as levels accumulate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "analysis/design/model_hypothesis.h"
#include "analysis/design/model_weights.h"
#include "analysis/design/next_point.h"
#include "analysis/design/response_prediction.h"
#include "analysis/hbm/level_response.h"
#include "analysis/identification/fit_uncertainty.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/velocity_power_damping.h"

namespace oscilab::analysis {
namespace {

// Twin data of one well at 9 Hz: the model's own EDC (the generator's H, so θ is an exact
// minimiser).
EdcDataset twin(const Model& truth, const std::vector<double>& levels_n) {
  const LevelResponse r = level_response(truth, 9.0, true, levels_n);
  return edc_dataset_from_values(9.0, r.f0_n, r.edc_j, {}, {});
}

// A σ of 0.2 % of each level's EDC, no defect correction: the twin's generator is the fit's model
// side, and 0.2 % is about what a 10 s level of the virtual rig measures at mid levels.
EdcCostSettings twin_cost() {
  EdcCostSettings cost;
  cost.model_error_rel = 2e-3;
  cost.adaptive_harmonics = false;
  return cost;
}

Model with_quadratic_damping(double c2) {
  Model m = paper_model();
  m.add_term(std::make_unique<VelocityPowerDamping>(2, c2));
  return m;
}

// The viscous c of the model's form as the one free parameter.
ModelForm viscous_form(const Model& model) {
  for (std::size_t i = 0; i < model.terms().size(); ++i) {
    if (model.terms()[i]->type() == "viscous-damping") {
      const double c = model.terms()[i]->parameter("c_ns_m");
      return ModelForm::of_terms(model, {{i, {"c_ns_m", 0.5 * c, 2.0 * c, false}}});
    }
  }
  throw std::runtime_error("no viscous damping");
}

ModelHypothesis fixed_hypothesis(const std::string& effect, const Model& model,
                                 const EdcDataset& data, double weight) {
  const ModelForm form = viscous_form(model);
  ModelHypothesis h(effect, effect == "none" ? "" : "added-term", form, form.initial());
  h.objective = std::make_shared<const EdcObjective>(form, data, twin_cost());
  h.solved = true;
  h.weight = weight;
  return h;
}

TEST(BicWeights, AreTheSoftmaxOfMinusHalfDeltaBic) {
  // ΔBIC = 2 ln 99 is posterior odds 99 : 1 (Kass & Raftery 1995).
  const std::vector<double> w = bic_weights({100.0, 100.0 + 2.0 * std::log(99.0)});
  EXPECT_NEAR(w[0], 0.99, 1e-12);
  EXPECT_NEAR(w[1], 0.01, 1e-12);
  // Shifting every BIC changes nothing; an unsolved model gets nothing; huge gaps do not overflow.
  const std::vector<double> shifted = bic_weights({1e6, 1e6 + 2.0 * std::log(99.0), INFINITY});
  EXPECT_NEAR(shifted[0], 0.99, 1e-12);
  EXPECT_EQ(shifted[2], 0.0);
  const std::vector<double> far = bic_weights({0.0, 1e5});
  EXPECT_EQ(far[0], 1.0);
  EXPECT_EQ(far[1], 0.0);
}

TEST(StopRule, StopsOnAClearLeaderAtTheNoiseOrOnTheBudget) {
  const EdcDataset data = twin(paper_model(), {0.3, 0.9, 1.5});
  std::vector<ModelHypothesis> h;
  h.push_back(fixed_hypothesis("none", paper_model(), data, 0.995));
  h.push_back(fixed_hypothesis("quadratic-damping", with_quadratic_damping(6.0), data, 0.005));
  // 30 levels, 1 parameter: ν = 29, noise level 1 + 3 √(2/29) = 1.788.
  for (ModelHypothesis& x : h) x.levels = 30;
  h[0].edc_chi2 = 29.0;
  h[1].edc_chi2 = 200.0;
  StopDecision d = stop_decision(h, {0.99, 600.0}, 100.0);
  EXPECT_NEAR(d.noise_reduced_chi2, 1.0 + 3.0 * std::sqrt(2.0 / 29.0), 1e-12);
  EXPECT_TRUE(d.stop);
  EXPECT_TRUE(d.decided);
  EXPECT_EQ(d.leader, 0);
  // The leader's misfit above the noise: not decided, and only the budget stops it.
  h[0].edc_chi2 = 29.0 * 2.0;
  d = stop_decision(h, {0.99, 600.0}, 100.0);
  EXPECT_FALSE(d.stop);
  d = stop_decision(h, {0.99, 600.0}, 600.0);
  EXPECT_TRUE(d.stop);
  EXPECT_FALSE(d.decided);
  EXPECT_NE(d.reason.find("budget"), std::string::npos) << d.reason;
  // A leader at the noise without a clear weight stops when no setting could still separate two
  // plausible models by a measurement's σ, and not while one could.
  h[0].edc_chi2 = 29.0;
  h[0].weight = 0.6;
  h[1].weight = 0.4;
  EXPECT_FALSE(stop_decision(h, {}, 100.0).stop);  // no proposal made: the weight alone decides
  EXPECT_FALSE(stop_decision(h, {}, 100.0, 3.0).stop);
  d = stop_decision(h, {}, 100.0, 0.5);
  EXPECT_TRUE(d.decided);
  EXPECT_TRUE(d.nothing_left);
  // As many parameters as levels (ν = 0): no noise level, never decided, and the reason says why.
  for (ModelHypothesis& x : h) x.levels = 1;
  d = stop_decision(h, {}, 100.0, 0.5);
  EXPECT_TRUE(std::isnan(d.noise_reduced_chi2));
  EXPECT_FALSE(d.decided);
  EXPECT_NE(d.reason.find("cannot be judged yet (levels 1, parameters 1:"), std::string::npos)
      << d.reason;
}

TEST(UnitCovariance, MatchesTheFitUncertaintyOfAWellMeasuredParameter) {
  // Second method: fit_uncertainty's central-difference covariance of c on 26 levels, mapped
  // to the unit cube. The prior's 12 is negligible beside JᵀJ here; forward against central
  // differences and the prior together stay within 2 %.
  std::vector<double> levels;
  for (int i = 0; i <= 25; ++i) levels.push_back(0.2 + 0.1 * i);
  const EdcDataset data = twin(paper_model(), levels);
  const ModelForm form = viscous_form(paper_model());
  const EdcObjective objective(form, data, twin_cost());
  const Eigen::MatrixXd cu = unit_covariance(objective, form.initial(), false);
  UncertaintyOptions options;
  const FitUncertainty u = fit_uncertainty(objective, form.initial(), options);
  ASSERT_TRUE(u.ok) << u.message;
  const double range = form.parameters()[0].upper - form.parameters()[0].lower;
  const double expected = u.covariance(0, 0) / (range * range);
  std::printf("unit variance of c: %.4g, fit_uncertainty's %.4g\n", cu(0, 0), expected);
  EXPECT_NEAR(cu(0, 0) / expected, 1.0, 0.02);
}

TEST(NextPoint, GoesToTheTopWhenTheModelsDifferOnlyThere) {
  // Quadratic damping's energy grows as Z³ against viscous damping's Z² (docs/diagnosis.md):
  // two models that differ only by c₂ ż|ż| agree at low levels and part at the top.
  const EdcDataset data = twin(paper_model(), {0.3, 0.6, 0.9});
  std::vector<ModelHypothesis> h;
  h.push_back(fixed_hypothesis("none", paper_model(), data, 0.5));
  h.push_back(fixed_hypothesis("quadratic-damping", with_quadratic_damping(6.0), data, 0.5));
  AdmissibleSettings settings;
  settings.negative_well = false;
  const NextPoint next = propose_next_point(h, settings, {});
  ASSERT_TRUE(next.found) << next.message;
  std::printf("%s\n", next.reason.c_str());
  const std::vector<double> grid = settings.f0_grid();
  ASSERT_EQ(grid.size(), 26u);
  // The best admissible level is in the top tenth of the rig's range.
  EXPECT_GE(next.best.f0_n, settings.f0_max_n - 0.1 * (settings.f0_max_n - settings.f0_min_n));
  EXPECT_NE(next.reason.find("quadratic-damping"), std::string::npos);
  // The criterion grows from the bottom to the top by orders of magnitude.
  const SettingScore& low = next.settings.front();
  ASSERT_TRUE(low.admissible);
  std::printf("criterion at %.1f N: %.3g, at the best %.2f N: %.3g\n", low.f0_n, low.criterion,
              next.best.f0_n, next.best.criterion);
  EXPECT_LT(low.criterion, 1e-2 * next.best.criterion);
}

TEST(NextPoint, ScoresNothingWhereTheModelsCoincide) {
  // The "candidate" with c₂ = 0 is the baseline: every prediction agrees to rounding.
  const EdcDataset data = twin(paper_model(), {0.3, 0.6, 0.9});
  std::vector<ModelHypothesis> h;
  h.push_back(fixed_hypothesis("none", paper_model(), data, 0.5));
  h.push_back(fixed_hypothesis("quadratic-damping", with_quadratic_damping(0.0), data, 0.5));
  AdmissibleSettings settings;
  settings.negative_well = false;
  const NextPoint next = propose_next_point(h, settings, {});
  ASSERT_TRUE(next.found);
  for (const SettingScore& s : next.settings) {
    if (s.admissible) {
      EXPECT_LT(s.criterion, 1e-12) << s.f0_n;
    }
  }
}

TEST(NextPoint, ExploresWhereAnUnconstrainedCandidateCouldShow) {
  // The candidate's c₂ is free and fitted at 0 on three low levels, where |ż|ż barely acts: its
  // mean predictions equal the baseline's everywhere, but its spread grows with the amplitude
  // (8/3 c₂ ω² Z³). Box–Hill's variance term sends the test to the top, where a level would show
  // whether c₂ is there.
  const EdcDataset data = twin(paper_model(), {0.3, 0.6, 0.9});
  std::vector<ModelHypothesis> h;
  h.push_back(fixed_hypothesis("none", paper_model(), data, 0.5));
  const Model candidate = with_quadratic_damping(0.0);
  std::size_t viscous = 0;
  while (candidate.terms()[viscous]->type() != "viscous-damping") ++viscous;
  const std::size_t quadratic = candidate.terms().size() - 1;
  const double c = candidate.terms()[viscous]->parameter("c_ns_m");
  const ModelForm form =
      ModelForm::of_terms(candidate, {{viscous, {"c_ns_m", 0.5 * c, 2.0 * c, false}},
                                      {quadratic, {"c2_ns2_m2", 0.0, 20.0, false}}});
  ModelHypothesis q("quadratic-damping", "added-term", form, form.initial());
  q.objective = std::make_shared<const EdcObjective>(form, data, twin_cost());
  q.solved = true;
  q.weight = 0.5;
  h.push_back(std::move(q));
  AdmissibleSettings settings;
  settings.negative_well = false;
  const NextPoint next = propose_next_point(h, settings, {});
  ASSERT_TRUE(next.found);
  std::printf("%s; discrimination %.3g\n", next.reason.c_str(), next.best.pair_discrimination);
  EXPECT_GE(next.best.f0_n, settings.f0_max_n - 0.1 * (settings.f0_max_n - settings.f0_min_n));
  EXPECT_LT(next.best.separation_sigma, 1e-6);  // the means agree: only the spread speaks
  EXPECT_GT(next.max_discrimination, 1.0);      // so the stop rule would not stop here
}

TEST(NextPoint, NeverProposesASettingWhoseResponseJumpsWells) {
  // At 6 Hz, below the positive well's 8.6 Hz, a forcing of a few newtons drives the paper's mass
  // over the saddle (z = 4.55 mm, between the wells at −30.3 and +23.7 mm): from there on a sweep
  // up leaves its well, and no setting there may be proposed, however well it would separate.
  const EdcDataset data = twin(paper_model(), {0.3, 0.6, 0.9});
  std::vector<ModelHypothesis> h;
  h.push_back(fixed_hypothesis("none", paper_model(), data, 0.5));
  h.push_back(fixed_hypothesis("quadratic-damping", with_quadratic_damping(6.0), data, 0.5));
  AdmissibleSettings settings;
  settings.negative_well = false;
  settings.freq_hz = 6.0;
  settings.f0_max_n = 6.0;
  settings.f0_step_n = 0.2;
  const NextPoint next = propose_next_point(h, settings, {});
  ASSERT_TRUE(next.found);
  double first_out = INFINITY;
  for (const SettingScore& s : next.settings) {
    if (!s.admissible) first_out = std::min(first_out, s.f0_n);
  }
  ASSERT_TRUE(std::isfinite(first_out)) << "no level of the sweep reached the saddle";
  std::printf("first inadmissible level %.2f N; proposed %.2f N (%s)\n", first_out, next.best.f0_n,
              next.reason.c_str());
  EXPECT_LT(next.best.f0_n, first_out);
  for (const SettingScore& s : next.settings) {
    if (s.f0_n >= first_out) {
      EXPECT_FALSE(s.admissible) << s.f0_n;  // a sweep beyond a jump stays out
      EXPECT_NE(s.why_not.find("jumps wells"), std::string::npos) << s.why_not;
    }
  }
  // Second look at the first level out, by the harmonic balance's own sampled extent of the
  // orbit: its lowest point (mean − half the peak-to-peak) is at or below the saddle, the
  // unstable equilibrium between the wells.
  double saddle = NAN;
  for (const Equilibrium& e : paper_model().equilibria()) {
    if (!e.stable) saddle = e.z_m;
  }
  const LevelResponse r = level_response(with_quadratic_damping(6.0), 6.0, true, {first_out});
  const LevelResponse b = level_response(paper_model(), 6.0, true, {first_out});
  const double lowest =
      std::min(r.coefficients[0][0] - r.amp_m[0], b.coefficients[0][0] - b.amp_m[0]);
  EXPECT_LE(lowest, saddle + 0.05 * b.amp_m[0]);  // the extent is of the sampled orbit: 5 %
}

TEST(ModelHypotheses, WeightsMoveToTheTrueModelAsItsLevelsAccumulate) {
  // Twin data of the paper's model with quadratic damping at the campaign's reference strength
  // (c₂ = 6 N s²/m²), measured from low levels up; the paper's form and two candidates.
  const Model truth = with_quadratic_damping(6.0);
  const std::vector<double> all = {0.3, 0.6, 0.9, 1.2, 1.5, 1.8, 2.1, 2.4, 2.7};
  HypothesisOptions options;
  options.cost = twin_cost();
  options.effects = {"quadratic-damping", "cubic-damping"};
  options.initial_evaluations = 150;
  options.refit_evaluations = 60;
  const ModelForm form = ModelForm::paper(paper_model());
  std::vector<double> levels(all.begin(), all.begin() + 3);
  std::vector<ModelHypothesis> h =
      initial_hypotheses(form, form.initial(), twin(truth, levels), options);
  ASSERT_EQ(h.size(), 3u);
  const auto weight_of = [&](const std::string& effect) {
    for (const ModelHypothesis& x : h) {
      if (x.effect == effect) return x.weight;
    }
    return -1.0;
  };
  std::vector<double> trace = {weight_of("quadratic-damping")};
  for (std::size_t k = 3; k < all.size(); ++k) {
    levels.push_back(all[k]);
    refit_hypotheses(h, twin(truth, levels), options);
    trace.push_back(weight_of("quadratic-damping"));
  }
  for (std::size_t i = 0; i < trace.size(); ++i) {
    std::printf("levels %zu: weight of quadratic-damping %.4f\n", i + 3, trace[i]);
  }
  EXPECT_LT(trace.front(), 0.9);  // three low levels cannot tell
  EXPECT_GT(trace.back(), 0.99);
  const StopDecision d = stop_decision(h, {}, 0.0);
  EXPECT_EQ(h[static_cast<std::size_t>(d.leader)].effect, "quadratic-damping");
  EXPECT_TRUE(d.decided) << d.reason;
}

}  // namespace
}  // namespace oscilab::analysis
