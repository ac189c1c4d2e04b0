#pragma once

#include <memory>

#include <Eigen/Core>

#include "analysis/common/job.h"
#include "analysis/diagnosis/discrepancy_maps.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/identification/model_form.h"
#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

/// A model settled on the measurement: its σ budget calibrated at θ (the model error and the
/// defect correction are the fitted model's), then a Levenberg–Marquardt refit on the joint
/// whitened residuals (the EDC and, if asked, the response fingerprints), repeated while θ moves
/// (the correction was calibrated at the old θ; at most three rounds), then the budget once more
/// at the final θ. What a diagnosis measures every candidate against, and how a fit with an
/// identified stiffness frees K(z) after its global search.
struct SettledModel {
  ModelForm form;  // the form starting at theta
  Eigen::VectorXd theta;
  EdcCostSettings cost;  // the base settings with the budget calibrated at theta
  std::shared_ptr<const EdcObjective> objective;
  EdcEvaluation evaluation;
  DiscrepancyMaps maps;
  long evaluations = 0;  // of the refits
};

/// Settles `form` at `theta` (see SettledModel). `base_cost` is the cost settings without a
/// budget (each calibration makes one); `refit_evaluations` bounds each Levenberg–Marquardt refit.
/// `cancel` is polled inside the refits and the calibrations.
SettledModel settle_model(const ModelForm& form, const Eigen::VectorXd& theta,
                          const EdcDataset& data, const CampaignAnalysis& campaign,
                          const EdcCostSettings& base_cost, bool use_fingerprints,
                          int refit_evaluations, const CancelToken& cancel = {});

}  // namespace oscilab::analysis
