#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/identification/model_form.h"
#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

/// One model an adaptive test weighs: the baseline form (effect "none") or the baseline extended
/// by one candidate effect of the diagnosis's vocabulary (effect_candidates), with its parameters
/// as last refitted and its evidence on the levels measured so far.
struct ModelHypothesis {
  ModelHypothesis(std::string effect_name, std::string embodiment_name, ModelForm model_form,
                  Eigen::VectorXd start);

  std::string effect;      // "none" for the baseline
  std::string embodiment;  // EffectCandidate::embodiment; "" for the baseline
  ModelForm form;
  Eigen::VectorXd theta;
  /// The objective of the last refit (its dataset, σ budget and defect correction).
  std::shared_ptr<const EdcObjective> objective;
  bool solved = false;
  std::string message;      // why not solved, when a fit failed
  double edc_chi2 = 0.0;    // χ² of the EDC alone
  double joint_chi2 = 0.0;  // EDC plus, when weighed, the response fingerprints
  int levels = 0;           // EDC residuals n
  int residuals = 0;        // n plus the fingerprints' residuals when weighed
  /// BIC = χ²_joint + p ln(residuals) (Schwarz 1978, "Estimating the dimension of a model").
  double bic = 0.0;
  double weight = 0.0;  // softmax of −ΔBIC/2 over the hypotheses (bic_weights)
  long evaluations = 0;

  int parameters() const { return form.size(); }
  /// χ²_EDC / ν with ν = n − p (NaN when ν ≤ 0).
  double reduced_edc_chi2() const;
  /// "baseline", or the effect as people read it ("presliding-hysteresis (friction regime)").
  std::string label() const;
};

struct HypothesisOptions {
  /// The cost settings of every fit, without a budget: each update calibrates one σ budget at the
  /// baseline's θ and shares it, so that the hypotheses' χ² stay comparable (as the diagnosis
  /// compares its candidates), and gives each hypothesis its own defect correction at its θ.
  EdcCostSettings cost;
  bool use_fingerprints = true;
  /// Model evaluations of each candidate's first fit (its own parameters on a grid and at its
  /// scan points, then Levenberg–Marquardt from the three best) and of every warm-started refit
  /// after a new level.
  int initial_evaluations = 400;
  /// With the campaign given: each hypothesis is first fitted by the global search a fit runs
  /// (fit_campaign: CMA-ES and polish on the EDC, then settled on the EDC and the fingerprints)
  /// with this many evaluations, and Levenberg–Marquardt starts from it and from its best grid
  /// point. A candidate started from the baseline's θ alone stays in the basin the baseline's
  /// parameters found to mimic the missing effect: measured on a virtual-rig pilot of the
  /// paper's model with quadratic damping (four levels per well), χ² 2.6 by this search against
  /// 2550 from the grid and scan points. 0: no global search.
  long global_evaluations = 400;
  std::uint64_t seed = 1;  // of the global searches
  int refit_evaluations = 300;
  /// The largest reference H of each hypothesis's own defect correction (the shared budget's
  /// reference climbs to cost.max_harmonics).
  int correction_max_harmonics = 31;
  /// The effects to weigh (names of the vocabulary); empty: every candidate the form allows.
  std::vector<std::string> effects;
  int threads = 0;  // 0: all hardware threads
};

/// The baseline (the form at `theta`, typically a fitted or settled baseline) and every
/// candidate effect the form does not hold (effect_candidates), each fitted to `data` from its
/// scan points with the baseline's parameters at θ, then weighed (bic_weights). Progress is the
/// fraction of hypotheses fitted; `cancel` is polled inside every fit (a cancelled hypothesis is
/// left unsolved, weight 0). Throws InputError as EdcObjective does (an empty dataset).
std::vector<ModelHypothesis> initial_hypotheses(const ModelForm& form, const Eigen::VectorXd& theta,
                                                const EdcDataset& data,
                                                const HypothesisOptions& options,
                                                const ProgressFn& progress = {},
                                                const CancelToken& cancel = {});

/// The same, each hypothesis first fitted by a global search on the campaign
/// (HypothesisOptions::global_evaluations), `data` its EDC dataset (edc_dataset).
std::vector<ModelHypothesis> initial_hypotheses(const ModelForm& form, const Eigen::VectorXd& theta,
                                                const CampaignAnalysis& campaign,
                                                const EdcDataset& data,
                                                const HypothesisOptions& options,
                                                const ProgressFn& progress = {},
                                                const CancelToken& cancel = {});

/// After new levels: every hypothesis refitted on `data` by Levenberg–Marquardt warm-started from
/// its last θ (joint_refit), its BIC and the weights updated. The first hypothesis must be the
/// baseline (the shared σ budget is calibrated at its θ).
void refit_hypotheses(std::vector<ModelHypothesis>& hypotheses, const EdcDataset& data,
                      const HypothesisOptions& options, const ProgressFn& progress = {},
                      const CancelToken& cancel = {});

}  // namespace oscilab::analysis
