#include "analysis/diagnosis/campaign_fit.h"

#include <chrono>

#include "analysis/diagnosis/settled_model.h"
#include "analysis/identification/fit_uncertainty.h"

namespace oscilab::analysis {

CampaignFit fit_campaign(const PreparedFit& prepared, const CampaignAnalysis& campaign,
                         const FitOptions& options, const FitProgressFn& progress,
                         const CancelToken& cancel) {
  const EdcObjective& objective = *prepared.objective;
  const ModelForm& form = objective.form();
  if (!form.identifies_stiffness())
    return {fit_edc(objective, options, progress, cancel), prepared.objective};

  const auto start = std::chrono::steady_clock::now();
  // The search over the friction, K(z) held at its start, its σ budget calibrated there.
  EdcCostSettings base = prepared.cost;
  base.cancel = cancel;
  const EdcObjective held(form.holding_stiffness(form.initial()), objective.data(), base);
  FitOptions search = options;
  search.compute_uncertainty = false;
  search.check_truncation = false;
  const auto expanded = [&](const Eigen::VectorXd& friction) {
    return friction.size() == 0 ? friction : form.expand(friction, form.initial());
  };
  FitResult result = fit_edc(
      held, search,
      [&](const FitProgress& p) {
        if (!progress) return;
        FitProgress full = p;
        full.best_theta = expanded(p.best_theta);
        progress(full);
      },
      cancel);
  // K(z) freed on the EDC and the fingerprints.
  SettledModel settled =
      settle_model(form, expanded(result.theta), objective.data(), campaign, base, true,
                   static_cast<int>(std::max<long>(200, options.max_evaluations / 3)), cancel);
  result.names = form.names();
  result.theta = settled.theta;
  result.evaluation = settled.evaluation;
  result.evaluations += settled.evaluations;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (cancel.cancelled()) {
    result.status = JobStatus::Cancelled;
    result.message = "cancelled";
  } else if (!result.evaluation.ok) {
    result.status = JobStatus::NoConvergence;
    result.message =
        "the settled model could not be solved at every level: " + result.evaluation.message;
  }
  if (options.compute_uncertainty && !cancel.cancelled()) {
    if (progress) {
      progress({FitStage::Uncertainty, result.evaluations, result.evaluation.weighted_cost,
                result.theta});
    }
    UncertaintyOptions u = options.uncertainty;
    u.seed = options.seed;
    u.threads = options.threads;
    result.uncertainty = fit_uncertainty(*settled.objective, result.theta, u, cancel);
  }
  return {std::move(result), settled.objective};
}

}  // namespace oscilab::analysis
