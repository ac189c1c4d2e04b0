#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/hbm/harmonic_balance.h"
#include "analysis/hbm/level_response.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/model_form.h"

namespace oscilab::analysis {

/// Relative bias of the stepped-sine EDC (edc_mean_j: per-cycle harmonic fits, docs/analysis.md)
/// against the converged harmonic balance of the true model, measured on virtual-rig records of
/// the paper's model at 8, 9 and 10 Hz with sensor noise ×1 and ×3
/// (scripts/estimator_bias_study.sh): the ρ for which the deviations' mean square equals σ_cycles²
/// + (ρ S)², 4.6e-4 over 1248 levels (3.2e-4 … 5.4e-4 per condition, not growing with the noise),
/// rounded up. It stands in each level's σ for what the chain gets wrong that the level's cycles do
/// not show.
inline constexpr double kEdcEstimatorBiasRel = 5e-4;

/// Each level's σ_k and where it comes from (docs/identification.md, "σ budget"):
///
///   σ_k² = σ_cycles,k² + σ_bias,k² + σ_model,k²
///
/// σ_cycles the standard error of S_k^mes from its cycles (not below the sensor-noise floor),
/// σ_bias = kEdcEstimatorBiasRel · S_k^mes, σ_model the model side's numerical error at level k.
///
/// The model side runs at the fit's H (fast) with a defect correction: at the calibration θ,
/// δ_k = S_k(H_ref) − S_k(H) is added to every S_k(H; θ), so the fit sees the reference's
/// accuracy at H's cost as long as δ varies little with θ (the calibration is repeated at the
/// fitted θ: after the baseline and after each accepted effect of a diagnosis). H_ref climbs the
/// ladder 15, 23, 31, 47, 63 until |S_k(H_ref) − S_k(2H_ref + 1)| ≤ target × the measurement σ
/// (cycles and bias) at every level, and that difference is σ_model. The response's |Z1| and
/// harmonic ratios get the same correction. With a fixed floor ρ (EdcCostSettings::model_error_rel
/// ≥ 0) σ_model = ρ S_k^mes, σ_bias = 0 and no correction, as fits did before the budget existed.
struct SigmaBudget {
  int harmonics = 0;            // H of the fit's model evaluations
  int reference_harmonics = 0;  // H_ref of the correction (0: none); σ_model from 2H_ref + 1
  double model_error_target = 0.0;
  bool resolved = true;  // every level's model error met the target within max H
  std::vector<double> cycles_j, bias_j, model_j, total_j;             // per level, group order
  std::vector<double> correction_j;                                   // δ_k added to S_k(H)
  std::vector<double> correction_z1_m, correction_h2, correction_h3;  // the same for the response
  /// Per level: S(H) and S(H_ref) at the calibration θ lie on different branches (a fold between
  /// them moved by the truncation), so their difference is a branch gap, not a truncation defect:
  /// the level gets no correction and the gap in σ_model (kBranchGapRel), and its fingerprints
  /// are left out of the joint χ².
  std::vector<bool> branch_ambiguous;
  /// The defect corrections (and branch flags) of `other`, calibrated at another θ of the same
  /// levels, where they are not ambiguous there; this budget's σ is kept, so that χ² measured
  /// against it stay comparable. Throws InputError when the level counts differ.
  void adopt_corrections(const SigmaBudget& other);
};

/// A level's |S(H_ref) − S(H)| beyond this share of the larger of the two is a branch gap (the
/// EDC changes by a factor 2 to 4 across the folds of the paper's oscillator, 8 to 10.5 Hz); the
/// truncation defects of H = 7 measured on the same campaigns are at most 6 % (diagnosis study,
/// `defect` and the σ budgets of its controls).
inline constexpr double kBranchGapRel = 0.25;

/// How a fit weighs the levels.
struct EdcCostSettings {
  /// Fixed relative model-error floor of each level's σ. Negative (the default): no floor; the
  /// σ budget derives each level's σ from its cycles, the estimator's measured bias and the
  /// model side's estimated truncation error (SigmaBudget).
  double model_error_rel = -1.0;
  /// The reference of the defect correction: H_ref climbs 15, 23, 31, 47, 63 (up to
  /// max_harmonics) until every level's model error is at most model_error_target × its
  /// measurement σ (cycles and bias): 0.3 adds at most 4.4 % to σ. adaptive = false: H_ref = H
  /// (no correction; σ_model is |S(H) − S(2H + 1)|).
  bool adaptive_harmonics = true;
  double model_error_target = 0.3;
  int max_harmonics = 63;
  HbmOptions hbm;  // H of the fit's evaluations: 7, as the paper's Fig. 11
  /// A budget computed before (the diagnosis computes it once per model and shares it): used as
  /// is, with its harmonics, instead of calibrating anew. Must match the dataset's level count.
  std::optional<SigmaBudget> budget;
  /// Polled by the calibration between its harmonic-balance sweeps: a cancelled calibration
  /// returns at once, its budget marked unresolved (the job is ending anyway).
  CancelToken cancel;
};

/// The model's EDCs at every measured level and how far they are from the measurement.
struct EdcEvaluation {
  bool ok = true;       // every level was predicted
  std::string message;  // why not, when !ok
  /// S_k^mod per group and level (0 where the model could not be solved).
  std::vector<std::vector<double>> edc_mod_j;
  /// Eq. (8): ε = Σ_k |S_k^mes − S_k^mod| over all levels of both wells, J.
  double cost_j = 0.0;
  /// Σ_k w_k r_k², r_k = (S_k^mes − S_k^mod) / σ_k: the cost the fit minimises.
  double weighted_cost = 0.0;
  Eigen::VectorXd residuals;  // r_k, groups in order
  /// The model's harmonic content per level in group order (NaN where not solved): |Z1| and the
  /// ratios |Z2|/|Z1|, |Z3|/|Z1| of its harmonic-balance solution, for the fingerprints.
  std::vector<double> z1_abs_m, h2_ratio, h3_ratio;
  /// The budget's SigmaBudget::branch_ambiguous, per level in group order.
  std::vector<bool> branch_ambiguous;
  /// Mean |S^mes − S^mod| / S^mes per well in %, as the paper's §5 (6 % z₊*, 12 % z₋*); NaN for
  /// a well without levels.
  double mean_deviation_pct_positive = 0.0;
  double mean_deviation_pct_negative = 0.0;
};

/// The identification cost of §4: θ → model (ModelForm) → each well's levels on the branch
/// reached by increasing f0 from rest (level_response, harmonic balance with eq. (13)) →
/// residuals against the measured EDCs.
///
/// Two costs: the paper's eq. (8), ε = Σ |S^mes − S^mod| (reported as cost_j), and the weighted
/// least-squares cost the optimisers minimise,
///
///   χ²(θ) = Σ_k w_k ((S_k^mes − S_k^mod(θ)) / σ_k)²,
///
/// with σ_k from the level's σ budget (SigmaBudget: cycles, estimator bias, model error). EDCs span
/// three decades from 0.2 to 2.7 N, so eq. (8) is blind to the low levels where v_t and k_s act
/// (§5.1); χ² weighs every level by its own precision. Weights w_k default to 1 (a bootstrap sets
/// them to resampling multiplicities).
///
/// Thread-safety: evaluate() is safe to call concurrently; the evaluation counter is atomic.
class EdcObjective {
 public:
  /// Throws InputError for an empty dataset or a form whose base model harmonic balance cannot
  /// handle. Without a given budget the σ budget is calibrated at the form's initial θ (one
  /// evaluation at H, then H_ref and 2H_ref + 1 per rung of the ladder).
  EdcObjective(ModelForm form, EdcDataset data, EdcCostSettings settings = {});

  /// The σ budget of `form` at θ: harmonics from the ladder and each level's σ components.
  static SigmaBudget calibrate_budget(const ModelForm& form, const EdcDataset& data,
                                      const EdcCostSettings& settings,
                                      const Eigen::VectorXd& theta);

  const ModelForm& form() const { return form_; }
  const EdcDataset& data() const { return data_; }
  const EdcCostSettings& settings() const { return settings_; }
  int level_count() const { return static_cast<int>(sigma_j_.size()); }
  /// σ_k of each level in group order.
  const std::vector<double>& sigma_j() const { return sigma_j_; }
  /// Where each σ_k comes from, and the harmonics the model side uses.
  const SigmaBudget& budget() const { return budget_; }
  /// A name for χ² as reports print it.
  std::string weighted_cost_name() const;

  /// All costs at θ. A θ outside a term's domain or a failed solve is not an error: the levels
  /// without a solution count as S^mod = 0 (a large, finite cost) and ok = false.
  EdcEvaluation evaluate(const Eigen::VectorXd& theta,
                         const std::vector<double>* level_weights = nullptr) const;
  /// `at` = evaluate(θ), and `at_nearby` the evaluations at the `nearby` θ (small changes of θ)
  /// linearised about θ's solutions (nearby_level_responses: one Newton step per level and nearby
  /// θ from θ's solution, exact to first order): a finite-difference Jacobian of the residuals at
  /// the cost of about two evaluations instead of one per parameter. False (at_nearby empty) when
  /// θ's evaluation failed or a step was singular: then evaluate each θ instead.
  bool evaluate_nearby(const Eigen::VectorXd& theta, const std::vector<Eigen::VectorXd>& nearby,
                       EdcEvaluation& at, std::vector<EdcEvaluation>& at_nearby) const;
  /// The model's EDC at the given levels of one well (for plots and sensitivity curves), with the
  /// budget's defect correction interpolated in f0 between the measured levels of that well and
  /// frequency (held at the ends; none for a well or frequency without measured levels).
  std::vector<double> edc_at(const Model& model, bool positive_well, double freq_hz,
                             const std::vector<double>& f0_n) const;

  long evaluations() const { return evaluations_->load(); }

 private:
  // One group's responses at θ, or why there are none.
  struct GroupResponse {
    std::optional<LevelResponse> response;
    std::string message;
  };
  std::vector<GroupResponse> respond(const Eigen::VectorXd& theta,
                                     std::optional<Model>& model) const;
  EdcEvaluation assemble(const std::vector<GroupResponse>& responses,
                         const std::vector<double>* level_weights) const;

  ModelForm form_;
  EdcDataset data_;
  EdcCostSettings settings_;
  std::vector<double> sigma_j_;
  SigmaBudget budget_;
  std::shared_ptr<std::atomic<long>> evaluations_ = std::make_shared<std::atomic<long>>(0);
};

}  // namespace oscilab::analysis
