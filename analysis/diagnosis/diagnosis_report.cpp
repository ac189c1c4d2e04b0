#include "analysis/diagnosis/diagnosis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/common/json_number.h"
#include "analysis/edc/well.h"
#include "analysis/identification/sigma_budget_report.h"

// The diagnosis report (docs/contracts.md §3) and the words for each candidate's outcome.
namespace oscilab::analysis {
namespace {

nlohmann::json slope_json(const LogSlope& s) {
  if (!s.valid()) return {{"points", s.points}};
  return {{"points", s.points},
          {"slope", s.slope},
          {"standard_error", finite_or_null(s.standard_error)},
          {"interval_95", {finite_or_null(s.lower_95), finite_or_null(s.upper_95)}}};
}

nlohmann::json missing_energy_slope_json(const DiscrepancyMaps& maps) {
  return {{"low", slope_json(maps.slopes.missing_low)},
          {"high", slope_json(maps.slopes.missing_high)},
          {"all", slope_json(maps.slopes.missing_all)}};
}

nlohmann::json maps_json(const DiscrepancyMaps& maps) {
  nlohmann::json levels = nlohmann::json::array();
  for (const LevelDiscrepancy& d : maps.levels) {
    levels.push_back({{"well", to_string(well_of(d.positive_well))},
                      {"f0_n", d.f0_n},
                      {"amplitude_m", d.amplitude_m},
                      {"edc_mes_j", d.edc_mes_j},
                      {"edc_mod_j", d.edc_mod_j},
                      {"sigma_j", d.sigma_j},
                      {"residual_sigma", d.residual_sigma},
                      {"residual_cycle_sigma", finite_or_null(d.residual_cycles)}});
  }
  nlohmann::json stiffness = {{"available", maps.stiffness.available}};
  if (maps.stiffness.available) {
    stiffness["rms_n"] = maps.stiffness.rms_n;
    nlohmann::json tests = nlohmann::json::array();
    for (const auto& t : maps.stiffness.tests) {
      tests.push_back({{"power", t.power},
                       {"coefficient", t.coefficient},
                       {"f_statistic", t.f_statistic},
                       {"p_value", t.p_value}});
    }
    stiffness["power_tests"] = tests;
  }
  nlohmann::json response = nlohmann::json::array();
  for (const ResponseFingerprint& f : maps.response.items) {
    nlohmann::json residuals = nlohmann::json::array();
    for (double r : f.residual_sigma) residuals.push_back(finite_or_null(r));
    response.push_back(
        {{"name", f.name}, {"chi2", f.chi2}, {"levels", f.levels}, {"residual_sigma", residuals}});
  }
  return {{"max_abs_residual_sigma", maps.max_abs_residual_sigma},
          {"response_fingerprints", response},
          {"reduced_chi2", finite_or_null(maps.reduced_chi2)},
          {"edc_slope_measured",
           {{"low", slope_json(maps.slopes.measured_low)},
            {"high", slope_json(maps.slopes.measured_high)}}},
          {"missing_energy_slope", missing_energy_slope_json(maps)},
          {"missing_levels", maps.slopes.missing_levels},
          {"excess_levels", maps.slopes.excess_levels},
          {"stiffness_residual", stiffness},
          {"levels", levels}};
}

nlohmann::json evidence_json(const std::vector<EvidenceChange>& evidence) {
  nlohmann::json out = nlohmann::json::array();
  for (const EvidenceChange& e : evidence) {
    out.push_back({{"name", e.name},
                   {"chi2_before", e.chi2_before},
                   {"chi2_after", e.chi2_after},
                   {"delta_chi2", e.delta_chi2()},
                   {"supports", e.supports()},
                   {"contradicts", e.contradicts()}});
  }
  return out;
}

nlohmann::json parameters_json(const std::vector<std::pair<std::string, double>>& parameters) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : parameters) out[name] = value;
  return out;
}

}  // namespace

std::string candidate_label(const std::string& effect, const std::string& embodiment) {
  if (embodiment.empty() || embodiment == "added-term") return effect;
  std::string words = embodiment;
  std::replace(words.begin(), words.end(), '-', ' ');
  return effect + " (" + words + ")";
}

std::vector<LevelDiscrepancy> largest_residual_levels(const DiscrepancyMaps& maps,
                                                      std::size_t count) {
  std::vector<LevelDiscrepancy> out;
  for (const LevelDiscrepancy& d : maps.levels) {
    if (std::isfinite(d.residual_sigma)) out.push_back(d);
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return std::abs(a.residual_sigma) > std::abs(b.residual_sigma);
  });
  if (out.size() > count) out.resize(count);
  return out;
}

std::string gap_open_message(const DiagnosisResult& result) {
  char text[200];
  std::snprintf(text, sizeof text,
                "the gap is not explained: the final model's reduced chi2 %.3g stays above the "
                "noise level %.3g",
                result.final_maps.reduced_chi2, result.final_noise_reduced_chi2);
  std::string message = text;
  if (!result.largest_residual_levels.empty()) {
    message += "; largest residuals at";
    for (std::size_t i = 0; i < result.largest_residual_levels.size(); ++i) {
      const LevelDiscrepancy& d = result.largest_residual_levels[i];
      std::snprintf(text, sizeof text, "%s %.3g N (%s well, %+.1f sigma)", i == 0 ? "" : ",",
                    d.f0_n, to_string(well_of(d.positive_well)).c_str(), d.residual_sigma);
      message += text;
    }
  }
  message += result.verdict == "none"
                 ? "; no effect of the vocabulary explains it"
                 : "; the effects named explain part of it, an effect outside the vocabulary may "
                   "remain";
  return message;
}

std::string candidate_outcome(const DiagnosisStep& step, const CandidateTrial& trial,
                              double bic_threshold) {
  char text[160];
  if (!trial.solved) return "not solved (the refit stopped or the model had no solution)";
  if (trial.effect == step.effect && trial.embodiment == step.embodiment) return "accepted";
  const CandidateTrial* best = nullptr;
  for (const CandidateTrial& t : step.trials) {
    if (t.solved && (!best || t.delta_bic_joint < best->delta_bic_joint)) best = &t;
  }
  if (best && best != &trial && best->delta_bic_joint < trial.delta_bic_joint &&
      best->delta_bic_joint < -bic_threshold) {
    const std::string label = candidate_label(best->effect, best->embodiment);
    std::snprintf(text, sizeof text, "rejected: %s explains more (joint dBIC %.3g)", label.c_str(),
                  best->delta_bic_joint);
    return text;
  }
  if (!(trial.delta_bic_joint < -bic_threshold)) {
    std::snprintf(text, sizeof text, "rejected: joint dBIC %.3g is not below -%.3g",
                  trial.delta_bic_joint, bic_threshold);
    return text;
  }
  for (const EvidenceChange& e : trial.evidence) {
    if (e.name == "edc" && !(e.delta_chi2() < 0.0)) return "rejected: the EDC fit gets worse";
  }
  return "rejected";
}

namespace {

nlohmann::json deviations_json(const EdcEvaluation& e) {
  return {{"positive", finite_or_null(e.mean_deviation_pct_positive)},
          {"negative", finite_or_null(e.mean_deviation_pct_negative)}};
}

nlohmann::json supported_by_json(const std::vector<EvidenceChange>& evidence) {
  nlohmann::json supported = nlohmann::json::array();
  for (const EvidenceChange& e : evidence) {
    if (e.supports()) supported.push_back(e.name);
  }
  return supported;
}

nlohmann::json baseline_json(const DiagnosisResult& result) {
  const FitResult& b = result.baseline;
  std::vector<std::pair<std::string, double>> parameters;
  for (std::size_t i = 0; i < b.names.size(); ++i) {
    parameters.emplace_back(b.names[i], b.theta(static_cast<Eigen::Index>(i)));
  }
  return {{"cost_j", b.evaluation.cost_j},
          {"weighted_cost", b.evaluation.weighted_cost},
          {"reduced_chi2", result.baseline_maps.reduced_chi2},
          {"mean_deviation_pct", deviations_json(b.evaluation)},
          {"evaluations", b.evaluations},
          {"parameters", parameters_json(parameters)},
          {"maps", maps_json(result.baseline_maps)},
          {"restarted_at_bound", result.baseline_restarts > 0},
          {"restart_improved", result.baseline_restart_improved},
          {"robust_refit", result.baseline_robust_refit},
          {"robust_refit_improved", result.baseline_robust_refit_improved},
          {"seconds", result.baseline_seconds},
          {"robust_refit_seconds", result.baseline_robust_refit_seconds}};
}

// One step: the evidence before it, every candidate refitted with its outcome, and for an
// accepted effect the evidence after and its parameters.
nlohmann::json step_json(const DiagnosisStep& s, double bic_threshold) {
  nlohmann::json candidates = nlohmann::json::array();
  for (const CandidateTrial& t : s.trials) {
    candidates.push_back({{"effect", t.effect},
                          {"embodiment", t.embodiment},
                          {"fingerprint_score", t.fingerprint_score},
                          {"weighted_cost", t.weighted_cost},
                          {"cost_j", t.cost_j},
                          {"delta_bic", t.delta_bic},
                          {"delta_bic_joint", t.delta_bic_joint},
                          {"evidence", evidence_json(t.evidence)},
                          {"outcome", candidate_outcome(s, t, bic_threshold)},
                          {"solved", t.solved}});
  }
  nlohmann::json evidence = {
      {"weighted_cost_before", s.weighted_before},
      {"reduced_chi2_before", s.reduced_chi2_before},
      {"max_abs_residual_sigma_before", s.maps_before.max_abs_residual_sigma},
      {"missing_energy_slope", missing_energy_slope_json(s.maps_before)},
      {"candidates", candidates}};
  nlohmann::json step = {
      {"effect", s.effect}, {"evidence", evidence}, {"cost_before_j", s.cost_before_j}};
  if (s.effect == "none") {
    step["cost_after_j"] = s.cost_before_j;  // nothing was added
    return step;
  }
  step["evidence"]["delta_bic"] = s.delta_bic;
  step["evidence"]["delta_bic_joint"] = s.delta_bic_joint;
  step["evidence"]["changes"] = evidence_json(s.evidence);
  step["evidence"]["supported_by"] = supported_by_json(s.evidence);
  step["evidence"]["weighted_cost_after"] = s.weighted_after;
  step["evidence"]["reduced_chi2_after"] = s.reduced_chi2_after;
  step["cost_after_j"] = s.cost_after_j;
  step["embodiment"] = s.embodiment;
  step["evidence"]["dispersion"] = s.dispersion;
  step["withdrawn"] = s.withdrawn;
  if (s.withdrawn) {
    step["withdrawn_reason"] = "its strength " + s.strength_parameter +
                               " vanished in the final model after later effects were added";
  }
  step["parameters_after"] = parameters_json(s.parameters_after);
  return step;
}

// The gap the final model leaves: its reduced χ² against the noise level, and the levels of
// largest residual.
nlohmann::json gap_json(const DiagnosisResult& result) {
  nlohmann::json gap = {{"final_reduced_chi2", finite_or_null(result.final_maps.reduced_chi2)},
                        {"noise_reduced_chi2", result.final_noise_reduced_chi2}};
  nlohmann::json largest = nlohmann::json::array();
  for (const LevelDiscrepancy& d : result.largest_residual_levels) {
    largest.push_back({{"well", to_string(well_of(d.positive_well))},
                       {"f0_n", d.f0_n},
                       {"residual_sigma", d.residual_sigma}});
  }
  gap["largest_residual_levels"] = largest;
  return gap;
}

}  // namespace

nlohmann::json diagnosis_report_json(const DiagnosisResult& result,
                                     const std::vector<std::string>& records,
                                     double bic_threshold) {
  nlohmann::json out;
  out["format"] = "oscilab-diagnosis/1";
  out["records"] = records;
  out["status"] = result.status != JobStatus::Ok ? "cancelled"
                  : result.incomplete            ? "incomplete"
                                                 : "ok";
  if (!result.message.empty()) out["message"] = result.message;
  out["sigma_budget"] = result.sigma_budget;
  out["baseline"] = baseline_json(result);
  nlohmann::json steps = nlohmann::json::array();
  for (const DiagnosisStep& s : result.steps) steps.push_back(step_json(s, bic_threshold));
  out["steps"] = steps;
  out["verdict"] = result.verdict;
  for (const DiagnosisStep& s : result.steps) {
    if (s.effect == result.verdict) out["verdict_supported_by"] = supported_by_json(s.evidence);
  }
  if (result.verdict == "none") {
    out["verdict_reason"] =
        result.final_maps.reduced_chi2 <= result.noise_reduced_chi2
            ? "the model form explains the data within its noise (reduced chi2 at or below the "
              "noise level)"
        : result.incomplete
            ? "stopped at the time limit before a candidate was accepted"
            : "no candidate effect improves the fit by the required evidence (dBIC threshold)";
  }
  out["noise_reduced_chi2"] = result.noise_reduced_chi2;
  // Whether the final model explains the data within its noise (scripts read this field).
  out["gap_explained"] = result.gap_explained;
  out["gap"] = gap_json(result);
  if (result.final_form) {
    out["final_model"] = result.final_form->build(result.final_theta).to_json();
    out["final"] = {{"cost_j", result.final_evaluation.cost_j},
                    {"weighted_cost", result.final_evaluation.weighted_cost},
                    {"reduced_chi2", result.final_maps.reduced_chi2},
                    {"mean_deviation_pct", deviations_json(result.final_evaluation)},
                    {"parameters", parameters_json(result.final_form->named(result.final_theta))},
                    {"maps", maps_json(result.final_maps)}};
  }
  out["rebases"] = result.rebases;
  out["excluded_levels"] = result.excluded_levels;
  out["seconds"] = result.seconds;
  out["evaluations"] = result.evaluations;
  return out;
}

}  // namespace oscilab::analysis
