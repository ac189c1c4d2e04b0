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
  EdcCostSettings cost;              // σ budget (or a fixed floor) and harmonics of every fit
  long baseline_evaluations = 1500;  // CMA-ES + polish of the model form as given
  long candidate_evaluations = 600;  // grid and BOBYQA refits of all parameters per candidate
  long accepted_evaluations = 1000;  // the longer refit of the finalists
  /// Wall-clock bound of the whole diagnosis, s (≤ 0: none). At the deadline the running fits
  /// stop with their best so far; the result keeps the steps completed and is marked incomplete.
  double max_seconds = 120.0;
  /// Weigh the response fingerprints (amplitude, harmonic content) with the EDC when candidates
  /// are compared and accepted (joint ΔBIC); false: the EDC alone.
  bool use_fingerprints = true;
  /// Accept a candidate when ΔBIC = Δχ² + Δp ln n < −bic_threshold: 10 is "very strong"
  /// evidence on the scale of Kass & Raftery (1995, "Bayes factors").
  double bic_threshold = 10.0;
  int max_steps = 3;
  std::uint64_t seed = 1;
  int threads = 0;
};

/// One candidate refitted at a step.
/// How one piece of evidence moved when a candidate was added: Δχ² of the EDC or of a response
/// fingerprint (negative: the candidate explains more of it).
struct EvidenceChange {
  std::string name;  // "edc", "amplitude", "harmonic-2", "harmonic-3"
  double chi2_before = 0.0, chi2_after = 0.0;
  double delta_chi2() const { return chi2_after - chi2_before; }
  /// Supports the candidate: Δχ² < −9 (a 3σ improvement for one added parameter).
  bool supports() const { return delta_chi2() < -9.0; }
  /// Speaks against it: Δχ² > +9.
  bool contradicts() const { return delta_chi2() > 9.0; }
};

struct CandidateTrial {
  std::string effect;
  std::string embodiment;  // "added-term" or "friction-regime" (EffectCandidate::embodiment)
  double fingerprint_score = 0.0;  // lower ranks first
  double weighted_cost = 0.0;      // χ² after the refit
  double cost_j = 0.0;             // eq. (8) after the refit
  double delta_bic = 0.0;          // of the EDC alone: Δχ² + Δp ln n
  double delta_bic_joint = 0.0;  // EDC and fingerprints: Δχ²_EDC + Δχ²_fp + Δp ln(n + n_fp)
  double joint_chi2 = 0.0;       // χ²_EDC + χ²_fp after the refit
  std::vector<EvidenceChange> evidence;
  bool solved = true;
  Eigen::VectorXd theta;  // all parameters of the extended form
};

struct DiagnosisStep {
  std::string effect;              // the accepted effect
  std::string embodiment;          // how it entered (EffectCandidate::embodiment)
  std::string strength_parameter;  // the added term's strength (its first free parameter)
  /// The term's strength vanished (≤ 1e-3 of its bound) in the final model, after later effects
  /// were added: the effect is kept in the report but not named in the verdict.
  bool withdrawn = false;
  bool can_vanish = true;  // EffectCandidate::can_vanish of the accepted candidate
  double cost_before_j = 0.0, cost_after_j = 0.0;
  double weighted_before = 0.0, weighted_after = 0.0;
  double reduced_chi2_before = 0.0, reduced_chi2_after = 0.0;
  double delta_bic = 0.0;        // of the accepted model after its longer refit (EDC)
  double delta_bic_joint = 0.0;  // the accepted candidate's joint ΔBIC
  /// φ ≥ 1 that divided every Δχ² of the step (quasi-likelihood): 1 at the first step, then the
  /// current model's reduced joint χ² when it is above 1.
  double dispersion = 1.0;
  std::vector<EvidenceChange> evidence;  // of the accepted candidate
  DiscrepancyMaps maps_before;
  std::vector<CandidateTrial> trials;  // in the order tried (fingerprint ranking)
  std::vector<std::pair<std::string, double>> parameters_after;
};

/// Where the model and the measurement disagree, which effect is missing, and the model with it.
struct DiagnosisResult {
  JobStatus status = JobStatus::Ok;
  std::string message;
  bool incomplete = false;      // stopped at max_seconds: the steps done so far, no more
  nlohmann::json sigma_budget;  // of the final model (sigma_budget_json)
  EdcCostSettings final_cost;   // the final model's cost settings, its σ budget included
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
  /// The same noise level for the final model's parameter count, and whether the final model's
  /// reduced χ² (EDC) is at or below it: false means a gap the diagnosis could not explain with
  /// its vocabulary (the message says so, and where the residual is largest).
  double final_noise_reduced_chi2 = 0.0;
  bool gap_explained = true;
  std::vector<LevelDiscrepancy> largest_residual_levels;  // of the final model, largest |r| first
  std::vector<std::string> excluded_levels;
  /// The settled baseline had a friction parameter at a bound, so its refit was restarted from
  /// space-filling points (1 when it was); whether a restart found a lower joint χ².
  int baseline_restarts = 0;
  bool baseline_restart_improved = false;
  bool baseline_robust_refit = false;           // the unexplained baseline refitted robustly
  bool baseline_robust_refit_improved = false;  // and that found a lower χ²
  /// Wall time of the baseline (search, settling, restarts, robust refit) and of its robust
  /// refit alone: where an unexplained baseline spends the diagnosis's time bound.
  double baseline_seconds = 0.0;
  double baseline_robust_refit_seconds = 0.0;
  /// How often a step's winning candidate had only found a deeper basin of the current model's
  /// own parameters: the current model refitted from the winner's θ without its term took the
  /// term's evidence below the threshold or itself gained more than it, so the refit became the
  /// current model and the step was run again from there.
  int rebases = 0;
  double seconds = 0.0;
  long evaluations = 0;
};

/// Where a diagnosis is: its phases in the order they run. The global search of the baseline,
/// settling a model (σ budget calibrated at θ, joint refit), refitting the candidates of a step,
/// the finalists' longer refit, settling the model with the accepted effect.
enum class DiagnosisPhase { Baseline, Settling, Candidates, Finalists, Accepting, Done };
/// "baseline", "settling", "candidates", "finalists", "accepting", "done".
const char* to_string(DiagnosisPhase phase);

/// A progress report of a diagnosis (from its worker threads, one at a time).
struct DiagnosisProgress {
  DiagnosisPhase phase = DiagnosisPhase::Baseline;
  int step = 0;              // 1, 2 … of the candidate search (0 before the first step)
  int max_steps = 0;         // DiagnosisOptions::max_steps
  int candidates_done = 0;   // candidates of this step refitted so far
  int candidates = 0;        // candidates of this step
  std::string candidate;     // the candidate that finished last, or the accepted one
  long evaluations = 0;      // model evaluations so far (the running fits' included)
  long baseline_budget = 0;  // DiagnosisOptions::baseline_evaluations
  /// Share of the work done, never decreasing: the baseline's search 0 → 0.2 by its evaluations,
  /// its settling to 0.25, then each of at most max_steps steps an equal share (its candidates by
  /// the evaluations they spent, the finalists, the accepted model's settling). A diagnosis that
  /// stops early jumps to 1.
  double fraction = 0.0;
  /// In words: "step 1 of at most 3: 4 of 9 candidates refitted (last: cubic-damping)".
  std::string describe() const;
};
using DiagnosisProgressFn = std::function<void(const DiagnosisProgress&)>;

/// The model-gap workflow: fit `form` to the campaign's EDCs, map the discrepancies,
/// refit the current model alone (the control every candidate is measured against), rank the
/// candidate effects by their fingerprints, refit every candidate with all parameters free,
/// accept the best by ΔBIC when the evidence is very strong, and repeat from the extended model
/// while something is accepted and the residual is above the noise. The verdict is `none`
/// when the baseline already explains the data within its noise or no candidate is accepted.
/// Progress reports the phase, step and candidates (DiagnosisProgress); `cancel` is polled inside
/// every fit.
DiagnosisResult diagnose(const CampaignAnalysis& campaign, const ModelForm& form,
                         const DiagnosisOptions& options, const DiagnosisProgressFn& progress = {},
                         const CancelToken& cancel = {});

/// A candidate as people read it: the effect, and for an embodiment other than an added term how
/// it enters ("presliding-hysteresis (friction regime)"): what the CLI, the report's outcomes and
/// the app show.
std::string candidate_label(const std::string& effect, const std::string& embodiment);

/// The `count` levels of `maps` with the largest |residual_sigma|, largest first.
std::vector<LevelDiscrepancy> largest_residual_levels(const DiscrepancyMaps& maps,
                                                      std::size_t count);

/// In words: the final model still misses the data (its reduced χ² against the noise level, and
/// the levels where the residual is largest).
std::string gap_open_message(const DiagnosisResult& result);

/// Why a candidate of a step was accepted or not, in words ("accepted", "rejected: joint dBIC
/// -4.2 is not below -10", "rejected: quadratic-damping explains more (joint dBIC -5.7e4)", …):
/// what the CLI, the report and the app show beside each candidate.
std::string candidate_outcome(const DiagnosisStep& step, const CandidateTrial& trial,
                              double bic_threshold);

/// The report (docs/contracts.md): {"baseline": {"cost_j", ...}, "steps": [{"effect", "evidence",
/// "cost_before_j", "cost_after_j"}], "verdict", "final_model"}, with numbers as evidence.
nlohmann::json diagnosis_report_json(const DiagnosisResult& result,
                                     const std::vector<std::string>& records,
                                     double bic_threshold = 10.0);

}  // namespace oscilab::analysis
