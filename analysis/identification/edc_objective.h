#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/hbm/harmonic_balance.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/model_form.h"

namespace oscilab::analysis {

/// How a fit weighs the levels.
struct EdcCostSettings {
  /// Relative model-error floor of each level's σ (see EdcObjective). 1 %: harmonic balance at
  /// H = 7 reproduces the time simulation's steady EDC within 1.4 % (docs/hbm.md), and a stepped
  /// test's calibration is rarely better; it keeps the weights of near-noise-free levels finite.
  double model_error_rel = 0.01;
  HbmOptions hbm;  // H = 7 by default, as the paper's Fig. 11
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
///   χ²(θ) = Σ_k w_k ((S_k^mes − S_k^mod(θ)) / σ_k)²,   σ_k² = σ_mean,k² + (ρ S_k^mes)²,
///
/// with σ_mean the level's standard error from its cycles (MeasuredLevel::sigma_of_mean_j) and ρ
/// the model-error floor. EDCs span three decades from 0.2 to 2.7 N, so eq. (8) is blind to the
/// low levels where v_t and k_s act (§5.1); χ² weighs every level by its own precision. Weights
/// w_k default to 1 (a bootstrap sets them to resampling multiplicities).
///
/// Thread-safety: evaluate() is safe to call concurrently; the evaluation counter is atomic.
class EdcObjective {
 public:
  /// Throws InputError for an empty dataset or a form whose base model harmonic balance cannot
  /// handle.
  EdcObjective(ModelForm form, EdcDataset data, EdcCostSettings settings = {});

  const ModelForm& form() const { return form_; }
  const EdcDataset& data() const { return data_; }
  const EdcCostSettings& settings() const { return settings_; }
  int level_count() const { return static_cast<int>(sigma_j_.size()); }
  /// σ_k of each level in group order.
  const std::vector<double>& sigma_j() const { return sigma_j_; }
  /// A name for χ² as reports print it.
  std::string weighted_cost_name() const;

  /// All costs at θ. A θ outside a term's domain or a failed solve is not an error: the levels
  /// without a solution count as S^mod = 0 (a large, finite cost) and ok = false.
  EdcEvaluation evaluate(const Eigen::VectorXd& theta,
                         const std::vector<double>* level_weights = nullptr) const;
  /// The model's EDC at the given levels of one well (for plots and sensitivity curves).
  std::vector<double> edc_at(const Model& model, bool positive_well, double freq_hz,
                             const std::vector<double>& f0_n) const;

  long evaluations() const { return evaluations_->load(); }

 private:
  ModelForm form_;
  EdcDataset data_;
  EdcCostSettings settings_;
  std::vector<double> sigma_j_;
  std::shared_ptr<std::atomic<long>> evaluations_ = std::make_shared<std::atomic<long>>(0);
};

}  // namespace oscilab::analysis
