#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/common/job.h"
#include "analysis/diagnosis/discrepancy_maps.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

struct DiagnosisOptions {
  EdcCostSettings cost;               // σ floor and harmonics of every fit
  long baseline_evaluations = 2000;   // CMA-ES + polish of the model form as given
  long candidate_evaluations = 1200;  // BOBYQA refits of all parameters per candidate
  long accepted_evaluations = 1500;   // the longer refit of the accepted candidate
  /// Accept a candidate when ΔBIC = Δχ² + Δp ln n < −bic_threshold: 10 is "very strong"
  /// evidence on the scale of Kass & Raftery (1995, "Bayes factors").
  double bic_threshold = 10.0;
  int max_steps = 3;
  std::uint64_t seed = 1;
  int threads = 0;
};

/// One candidate refitted at a step.
struct CandidateTrial {
  std::string effect;
  double fingerprint_score = 0.0;  // lower ranks first
  double weighted_cost = 0.0;      // χ² after the refit
  double cost_j = 0.0;             // eq. (8) after the refit
  double delta_bic = 0.0;
  bool solved = true;
  Eigen::VectorXd theta;  // all parameters of the extended form
};

struct DiagnosisStep {
  std::string effect;  // the accepted effect
  double cost_before_j = 0.0, cost_after_j = 0.0;
  double weighted_before = 0.0, weighted_after = 0.0;
  double reduced_chi2_before = 0.0, reduced_chi2_after = 0.0;
  double delta_bic = 0.0;
  DiscrepancyMaps maps_before;
  std::vector<CandidateTrial> trials;  // in the order tried (fingerprint ranking)
  std::vector<std::pair<std::string, double>> parameters_after;
};

/// Where the model and the measurement disagree, which effect is missing, and the model with it.
struct DiagnosisResult {
  JobStatus status = JobStatus::Ok;
  std::string message;
  FitResult baseline;
  DiscrepancyMaps baseline_maps, final_maps;
  std::vector<DiagnosisStep> steps;
  std::string verdict = "none";  // the first accepted effect, or none
  std::optional<ModelForm> final_form;
  Eigen::VectorXd final_theta;
  EdcEvaluation final_evaluation;
  /// χ²/ν at or below which the model explains the data within its noise: 1 + 3 √(2/ν), three
  /// standard deviations of the reduced χ² of a correct model.
  double noise_reduced_chi2 = 0.0;
  std::vector<std::string> excluded_levels;
  double seconds = 0.0;
  long evaluations = 0;
};

/// The model-gap workflow (issue 9): fit `form` to the campaign's EDCs, map the discrepancies,
/// refit the current model alone (the control every candidate is measured against), rank the
/// candidate effects by their fingerprints, refit every candidate with all parameters free,
/// accept the best by ΔBIC when the evidence is very strong, and repeat from the extended model
/// while something is accepted and the residual is above the noise. The verdict is `none`
/// when the baseline already explains the data within its noise or no candidate is accepted.
/// Progress is the fraction of the steps' work; `cancel` is polled inside every fit.
DiagnosisResult diagnose(const CampaignAnalysis& campaign, const ModelForm& form,
                         const DiagnosisOptions& options, const ProgressFn& progress = {},
                         const CancelToken& cancel = {});

/// The report of contracts.md §2: {"baseline": {"cost_j", ...}, "steps": [{"effect", "evidence",
/// "cost_before_j", "cost_after_j"}], "verdict", "final_model"}, with numbers as evidence.
nlohmann::json diagnosis_report_json(const DiagnosisResult& result,
                                     const std::vector<std::string>& records);

}  // namespace oscilab::analysis
