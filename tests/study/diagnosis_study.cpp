// Studies of the model-gap diagnosis on virtual-rig campaigns (not a test: scripts run it and
// docs/diagnosis.md quotes what it printed). Three modes, each writing CSV on stdout:
//
//   diagnosis_study bias SEEDS            the estimator's bias: measured EDC, |Z1| and harmonic
//                                         ratios of the paper's model against its converged
//                                         harmonic balance (H = 31), at 8, 9, 10 Hz, noise ×1, ×3
//   diagnosis_study power EFFECT SCALE FREQ NOISE SEED [LEVELS]
//                                         one blind diagnosis of the paper's model plus EFFECT at
//                                         SCALE × its reference strength (presliding-regime: the
//                                         friction's own presliding regime, SCALE = δ in µm;
//                                         one-sided-damper: outside the vocabulary)
//   diagnosis_study moved EFFECT SCALE FREQ NOISE SEED [LEVELS]
//                                         the same with the friction parameters θ moved as a
//                                         control's of that seed (the start is not the truth's)
//   diagnosis_study control SEED FREQ NOISE [LEVELS]
//                                         one blind diagnosis of the paper's model with its
//                                         friction parameters θ (eq. (9)) moved by up to ±30 %
//
//   diagnosis_study branches SEED FREQ NOISE [LEVELS]
//                                         a control's measured levels beside the truth's level
//                                         response (which branch each level was measured on)
//   diagnosis_study defect SEED FREQ NOISE [LEVELS [H]]
//                                         a control's truncation defect at the fit's H (7) against
//                                         its σ budget's reference, at the start θ and the truth's
//   diagnosis_study header                the result rows' CSV header
//
// LEVELS: stepped-sine levels per well, 0.2 → 2.7 N evenly (26 by default). Every diagnosis is
// run as a lab runs it, the stiffness identified from the records (`--stiffness identified`);
// OSCILAB_STUDY_TRUE_STIFFNESS=1 gives it the truth's K(z) instead (labelled in the output);
// OSCILAB_STUDY_HARMONICS=H sets the H of the fit's model evaluations (7 by default);
// OSCILAB_STUDY_TRACE=1 prints each phase's start time on stderr; OSCILAB_STUDY_MAX_STEPS=N
// stops after N candidate steps (0: the baseline alone).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>

#include "analysis/diagnosis/diagnosis.h"
#include "analysis/diagnosis/effect_candidates.h"
#include "analysis/edc/well.h"
#include "analysis/hbm/level_response.h"
#include "analysis/identification/campaign_model.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/model/position_dependent_friction.h"
#include "tests/analysis/diagnosis/hidden_effect_campaign.h"
#include "tests/analysis/identification/twin_data.h"

namespace {

using namespace oscilab::analysis;

int bias_study(int seeds) {
  std::printf(
      "freq_hz,noise_scale,seed,well,f0_n,edc_mes_j,edc_true_j,sigma_cycles_j,"
      "z1_mes_m,z1_true_m,z1_se_m,h2_mes,h2_true,h2_se,h3_mes,h3_true,h3_se\n");
  const Model truth = paper_model();
  HbmOptions converged;
  converged.harmonics = 31;
  for (double freq : {8.0, 9.0, 10.0}) {
    for (double noise : {1.0, 3.0}) {
      for (int seed = 1; seed <= seeds; ++seed) {
        testing::CampaignSpec spec;
        spec.freq_hz = freq;
        spec.noise_scale = noise;
        spec.random_record = false;
        const CampaignAnalysis campaign = testing::record_campaign(
            truth, static_cast<std::uint64_t>(seed), testing::paper_levels_n(), spec);
        const EdcDataset data = edc_dataset(campaign);
        for (const EdcGroup& g : data.groups) {
          std::vector<double> f0;
          for (const MeasuredLevel& l : g.levels) f0.push_back(l.f0_n);
          const LevelResponse r = level_response(truth, g.freq_hz, g.positive_well, f0, converged);
          for (std::size_t i = 0; i < r.edc_j.size(); ++i) {
            const MeasuredLevel& l = g.levels[i];
            const Eigen::VectorXd& x = r.coefficients[i];
            const double a1 = std::hypot(x[1], x[2]);
            std::printf(
                "%g,%g,%d,%s,%.6g,%.9g,%.9g,%.4g,%.9g,%.9g,%.4g,%.6g,%.6g,%.4g,%.6g,%.6g,%.4g\n",
                freq, noise, seed, to_string(well_of(g.positive_well)).c_str(), l.f0_n, l.edc_j,
                r.edc_j[i], l.sigma_of_mean_j(), l.amplitude_m, a1, l.z1_abs_se_m, l.h2_ratio,
                harmonic_amplitude(x, 2) / a1, l.h2_ratio_se, l.h3_ratio,
                harmonic_amplitude(x, 3) / a1, l.h3_ratio_se);
          }
        }
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

void print_header() {
  std::printf(
      "case,effect,scale,freq_hz,noise_scale,seed,verdict,correct,status,seconds,"
      "baseline_reduced_chi2,noise_reduced_chi2,steps,accepted,levels,stiffness,gap_explained,"
      "final_reduced_chi2,embodiment,truth_reduced_chi2,baseline_reaches_truth\n");
}

bool true_stiffness() {
  const char* flag = std::getenv("OSCILAB_STUDY_TRUE_STIFFNESS");
  return flag && std::string(flag) == "1";
}

// The verdict a correct diagnosis gives for a hidden effect: its vocabulary name (the friction's
// presliding regime is presliding-hysteresis), none for an effect outside the vocabulary (whose
// test is gap_explained false). A quadratic or cubic stiffness term is the identified cubic
// K(z)'s own: with the stiffness identified it is absorbed into K(z)'s coefficients, and the
// right answer is none with the gap explained; only with the true stiffness held is it an effect.
std::string expected_verdict(const std::string& effect) {
  if (effect == "presliding-regime") return "presliding-hysteresis";
  if (effect == "one-sided-damper") return "-";
  if (!true_stiffness() && (effect == "quadratic-stiffness" || effect == "cubic-stiffness")) {
    return "none";
  }
  return effect;
}

// Whether the settled baseline reached the minimum: its EDC χ² against the χ² of the true
// parameters, both under the final model's σ budget, which must not exceed it by more than
// 2 √(2ν) (two standard deviations of χ² with ν degrees of freedom). Only for a control, whose
// truth the baseline's form holds exactly.
struct TruthComparison {
  double truth_reduced_chi2 = std::nan("");
  int reaches = -1;  // 1 yes, 0 no, -1 not a control
};

void print_result(const std::string& kind, const std::string& effect, double scale, double freq,
                  double noise, int seed, int levels, const DiagnosisResult& r,
                  const TruthComparison& truth = {}) {
  std::string accepted, embodiment = "-";
  for (const DiagnosisStep& s : r.steps) {
    if (s.effect != "none") accepted += (accepted.empty() ? "" : "+") + s.effect;
    if (s.effect == r.verdict && !s.embodiment.empty()) embodiment = s.embodiment;
  }
  const std::string expected = expected_verdict(effect);
  const bool correct = effect == "one-sided-damper"
                           ? !r.gap_explained
                           : r.verdict == expected && (expected != "none" || r.gap_explained);
  std::printf(
      "%s,%s,%g,%g,%g,%d,%s,%d,%s,%.1f,%.4g,%.4g,%zu,%s,%d,%s,%d,%.4g,%s,%.4g,%d\n", kind.c_str(),
      effect.c_str(), scale, freq, noise, seed, r.verdict.c_str(), correct ? 1 : 0,
      r.incomplete ? "incomplete" : "complete", r.seconds, r.baseline_maps.reduced_chi2,
      r.noise_reduced_chi2, r.steps.size(), accepted.empty() ? "-" : accepted.c_str(), levels,
      true_stiffness() ? "true" : "identified", r.gap_explained ? 1 : 0, r.final_maps.reduced_chi2,
      embodiment.c_str(), truth.truth_reduced_chi2, truth.reaches);
  std::fflush(stdout);
}

// `count` levels per well, evenly from 0.2 to 2.7 N (the paper's grid at 26).
std::vector<double> level_grid(int count) {
  std::vector<double> levels;
  for (int i = 0; i < count; ++i) levels.push_back(0.2 + 2.5 * i / (count - 1));
  return levels;
}

struct BlindRun {
  DiagnosisResult result;
  TruthComparison truth;
};

// The virtual rig's campaign of `truth` (stepped sines in both wells on the study's grid and a
// random record), recorded with the seed's noise at `freq` Hz and `noise` × the sensor noise.
CampaignAnalysis record_control(const Model& truth, int seed, double freq, double noise,
                                int levels) {
  testing::CampaignSpec spec;
  spec.freq_hz = freq;
  spec.noise_scale = noise;
  return testing::record_campaign(truth, static_cast<std::uint64_t>(seed), level_grid(levels),
                                  spec);
}

BlindRun run_blind(const Model& truth, int seed, double freq, double noise, int levels,
                   bool compare_with_truth) {
  const CampaignAnalysis campaign = record_control(truth, seed, freq, noise, levels);
  // As a lab: the mass known, K(z) identified from the records starting from their stiffness
  // slice; the friction started from the paper's values (the truth of none but the control's
  // centre). With the true stiffness only when asked (labelled `true` in the output).
  FitSetup setup;
  std::vector<std::string> notes;
  ModelForm form = ModelForm::paper(paper_model());
  if (true_stiffness()) {
    // The paper's K(z) of Table 1, the truth's but for a hidden stiffness power, held fixed.
    form = ModelForm::paper(campaign_model(paper_model(), campaign, StiffnessSource::Model, notes));
  } else {
    setup.stiffness = StiffnessSource::Identified;
    form = fit_form(campaign, setup, notes);
  }
  DiagnosisOptions options;
  options.seed = static_cast<std::uint64_t>(seed);
  const char* seconds = std::getenv("OSCILAB_DIAGNOSE_MAX_SECONDS");
  if (seconds) options.max_seconds = std::atof(seconds);
  if (const char* steps = std::getenv("OSCILAB_STUDY_MAX_STEPS")) {
    options.max_steps = std::clamp(std::atoi(steps), 0, 10);
  }
  if (const char* h = std::getenv("OSCILAB_STUDY_HARMONICS")) {
    options.cost.hbm.harmonics = std::clamp(std::atoi(h), 1, 63);
  }
  // The study script runs JOBS diagnoses at once on cores / JOBS threads each (OMP_NUM_THREADS),
  // so that they do not compete for the cores and each one's time is its own.
  if (const char* threads = std::getenv("OMP_NUM_THREADS")) {
    options.threads = std::clamp(std::atoi(threads), 0, 1024);
  }
  // OSCILAB_STUDY_TRACE=1: each change of phase or step on stderr with the seconds since the
  // start and the evaluations spent (where a diagnosis spends its time).
  DiagnosisProgressFn trace;
  if (const char* flag = std::getenv("OSCILAB_STUDY_TRACE"); flag && std::string(flag) == "1") {
    const auto start = std::chrono::steady_clock::now();
    trace = [start, last = std::string()](const DiagnosisProgress& p) mutable {
      const std::string now = std::string(to_string(p.phase)) + " " + std::to_string(p.step);
      if (now == last) return;
      last = now;
      const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
      std::fprintf(stderr, "%7.1f s  %-16s evaluations %ld\n", elapsed.count(), now.c_str(),
                   p.evaluations);
    };
  }
  BlindRun run{diagnose(campaign, form, options, trace), {}};
  const DiagnosisResult& result = run.result;
  if (const char* path = std::getenv("OSCILAB_STUDY_REPORT")) {
    std::ofstream(path) << diagnosis_report_json(result, {"virtual rig"}).dump(2) << '\n';
  }
  if (compare_with_truth && result.status == oscilab::JobStatus::Ok && !result.incomplete) {
    // Both χ² under one σ budget (the final model's): the baseline's settled θ and the truth's.
    const EdcObjective objective(form, edc_dataset(campaign), result.final_cost);
    const double nu = std::max(1, objective.level_count() - form.size());
    const double truth_chi2 = objective.evaluate(form.theta_of(truth)).weighted_cost;
    const double baseline_chi2 = objective.evaluate(result.baseline.theta).weighted_cost;
    run.truth.truth_reduced_chi2 = truth_chi2 / nu;
    run.truth.reaches = baseline_chi2 <= truth_chi2 + 2.0 * std::sqrt(2.0 * nu) ? 1 : 0;
  }
  return run;
}

int power_study(const std::string& effect, double scale, double freq, double noise, int seed,
                int levels) {
  print_header();
  const Model truth = testing::truth_with_effect(effect, scale);
  print_result("power", effect, scale, freq, noise, seed, levels,
               run_blind(truth, seed, freq, noise, levels, false).result);
  return 0;
}

// The paper's model with θ of eq. (9) moved by a uniform factor in [0.7, 1.3] each, drawn from
// the seed: the diagnosis starts from the paper's friction, not from this truth's.
Model moved_friction(int seed) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(seed) * 7919);
  std::uniform_real_distribution<double> factor(0.7, 1.3);
  const ModelForm form = ModelForm::paper(paper_model());
  Eigen::VectorXd theta = form.initial();
  for (int i = 0; i < theta.size(); ++i) theta[i] *= factor(rng);
  return form.build(form.clamp(theta));
}

int control_study(int seed, double freq, double noise, int levels) {
  print_header();
  const BlindRun run = run_blind(moved_friction(seed), seed, freq, noise, levels, true);
  print_result("control", "none", 0.0, freq, noise, seed, levels, run.result, run.truth);
  return 0;
}

// A hidden effect on top of friction moved as a control's (the seed's): the start is then not
// the truth's friction.
int moved_study(const std::string& effect, double scale, double freq, double noise, int seed,
                int levels) {
  print_header();
  const Model truth = testing::truth_with_effect(effect, scale, moved_friction(seed));
  print_result("moved", effect, scale, freq, noise, seed, levels,
               run_blind(truth, seed, freq, noise, levels, false).result);
  return 0;
}

// A control's campaign (as `control` records it), each usable level's measurement beside the
// truth's harmonic balance at that level: which branch the rig's steps reached.
int branches_study(int seed, double freq, double noise, int levels) {
  const Model truth = moved_friction(seed);
  const CampaignAnalysis campaign = record_control(truth, seed, freq, noise, levels);
  const EdcDataset data = edc_dataset(campaign);
  std::printf(
      "well,f0_n,edc_mes_j,sigma_j,edc_truth_j,edc_truth_h31_j,amp_mes_m,amp_truth_m,"
      "z_mean_truth_m\n");
  for (const EdcGroup& g : data.groups) {
    std::vector<double> f0;
    for (const MeasuredLevel& l : g.levels) f0.push_back(l.f0_n);
    const LevelResponse r = level_response(truth, g.freq_hz, g.positive_well, f0);
    HbmOptions fine;
    fine.harmonics = 31;
    const LevelResponse r31 = level_response(truth, g.freq_hz, g.positive_well, f0, fine);
    for (const LevelResponse* response : {&r, &r31}) {
      if (!response->message.empty())
        std::printf("# H %d: %s\n", response->harmonics, response->message.c_str());
    }
    for (std::size_t i = 0; i < g.levels.size() && i < r.edc_j.size(); ++i) {
      const MeasuredLevel& l = g.levels[i];
      std::printf("%s,%.4f,%.6g,%.3g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                  to_string(well_of(g.positive_well)).c_str(), l.f0_n, l.edc_j, l.sigma_of_mean_j(),
                  r.edc_j[i], i < r31.edc_j.size() ? r31.edc_j[i] : NAN, l.amplitude_m, r.amp_m[i],
                  r.coefficients[i][0]);
    }
  }
  for (const std::string& e : data.excluded) std::printf("# excluded: %s\n", e.c_str());
  return 0;
}

// A control's σ budget at the diagnosis's start (the identified stiffness, the paper's friction)
// and at the truth's θ: how far the fit's H misses its harmonic-balance reference, per level in
// units of the measurement's σ (cycles and bias). One row per θ.
int defect_study(int seed, double freq, double noise, int levels, int harmonics) {
  const Model truth = moved_friction(seed);
  const CampaignAnalysis campaign = record_control(truth, seed, freq, noise, levels);
  FitSetup setup;
  setup.stiffness = StiffnessSource::Identified;
  std::vector<std::string> notes;
  const ModelForm form = fit_form(campaign, setup, notes);
  const EdcDataset data = edc_dataset(campaign);
  EdcCostSettings cost;
  cost.hbm.harmonics = harmonics;
  std::printf(
      "seed,freq_hz,noise_scale,levels,theta,harmonics,reference_harmonics,max_defect_sigma,"
      "levels_over_3,levels_over_10,levels_over_30,n\n");
  for (const auto& [label, theta] :
       {std::pair<const char*, Eigen::VectorXd>{"start", form.initial()},
        std::pair<const char*, Eigen::VectorXd>{"truth", form.theta_of(truth)}}) {
    const SigmaBudget b = EdcObjective::calibrate_budget(form, data, cost, theta);
    double largest = 0.0;
    int over3 = 0, over10 = 0, over30 = 0;
    for (std::size_t k = 0; k < b.correction_j.size(); ++k) {
      const double r = std::abs(b.correction_j[k]) / std::hypot(b.cycles_j[k], b.bias_j[k]);
      largest = std::max(largest, r);
      over3 += r > 3.0;
      over10 += r > 10.0;
      over30 += r > 30.0;
    }
    std::printf("%d,%.2f,%.2f,%d,%s,%d,%d,%.3g,%d,%d,%d,%zu\n", seed, freq, noise, levels, label,
                b.harmonics, b.reference_harmonics, largest, over3, over10, over30,
                b.correction_j.size());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "header" && argc == 2) {
    print_header();
    return 0;
  }
  if (mode == "bias" && argc == 3) return bias_study(std::atoi(argv[2]));
  if (mode == "power" && (argc == 7 || argc == 8)) {
    const int levels = argc == 8 ? std::atoi(argv[7]) : 26;
    if (levels < 5) return 2;
    return power_study(argv[2], std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5]),
                       std::atoi(argv[6]), levels);
  }
  if (mode == "moved" && (argc == 7 || argc == 8)) {
    const int levels = argc == 8 ? std::atoi(argv[7]) : 26;
    if (levels < 5) return 2;
    return moved_study(argv[2], std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5]),
                       std::atoi(argv[6]), levels);
  }
  if (mode == "control" && (argc == 5 || argc == 6)) {
    const int levels = argc == 6 ? std::atoi(argv[5]) : 26;
    if (levels < 5) return 2;
    return control_study(std::atoi(argv[2]), std::atof(argv[3]), std::atof(argv[4]), levels);
  }
  if (mode == "branches" && (argc == 5 || argc == 6)) {
    const int levels = argc == 6 ? std::atoi(argv[5]) : 26;
    if (levels < 5) return 2;
    return branches_study(std::atoi(argv[2]), std::atof(argv[3]), std::atof(argv[4]), levels);
  }
  if (mode == "defect" && (argc == 5 || argc == 6 || argc == 7)) {
    const int levels = argc >= 6 ? std::atoi(argv[5]) : 26;
    const int harmonics = argc == 7 ? std::atoi(argv[6]) : 7;
    if (levels < 5 || harmonics < 1 || harmonics > 63) return 2;
    return defect_study(std::atoi(argv[2]), std::atof(argv[3]), std::atof(argv[4]), levels,
                        harmonics);
  }
  std::fprintf(
      stderr,
      "usage: diagnosis_study header | bias SEEDS | power EFFECT SCALE FREQ NOISE SEED "
      "[LEVELS] | moved EFFECT SCALE FREQ NOISE SEED [LEVELS] | control SEED FREQ NOISE "
      "[LEVELS] | branches SEED FREQ NOISE [LEVELS] | defect SEED FREQ NOISE [LEVELS [H]]\n");
  return 2;
}
