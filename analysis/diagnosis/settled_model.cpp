#include "analysis/diagnosis/settled_model.h"

#include "analysis/diagnosis/joint_refit.h"

namespace oscilab::analysis {

SettledModel settle_model(const ModelForm& form, const Eigen::VectorXd& theta,
                          const EdcDataset& data, const CampaignAnalysis& campaign,
                          const EdcCostSettings& base_cost, bool use_fingerprints,
                          int refit_evaluations, const CancelToken& cancel) {
  SettledModel out{form.with_initial(theta), theta, base_cost, nullptr, {}, {}, 0};
  Eigen::VectorXd calibrated_at;
  const auto calibrate = [&] {
    out.cost.budget = EdcObjective::calibrate_budget(out.form, data, base_cost, out.theta);
    out.objective = std::make_shared<const EdcObjective>(out.form, data, out.cost);
    out.evaluation = out.objective->evaluate(out.theta);
    out.maps = discrepancy_maps(*out.objective, out.theta, out.evaluation, campaign);
    calibrated_at = out.theta;
  };
  constexpr int kRounds = 3;
  for (int round = 0; round < kRounds && !cancel.cancelled(); ++round) {
    calibrate();
    const double before = joint_chi2(out.evaluation, out.maps.response, use_fingerprints);
    const JointRefit fit =
        joint_refit(*out.objective, out.theta, use_fingerprints, refit_evaluations, cancel);
    out.evaluations += fit.evaluations;
    if (fit.theta.size() == 0 || !(fit.joint_chi2 < before)) break;
    const double moved =
        (out.form.to_unit(fit.theta) - out.form.to_unit(out.theta)).cwiseAbs().maxCoeff();
    out.theta = fit.theta;
    out.form = out.form.with_initial(out.theta);
    out.evaluation = fit.evaluation;
    out.maps = discrepancy_maps(*out.objective, out.theta, out.evaluation, campaign);
    if (moved < 1e-3 || before - fit.joint_chi2 < 0.01 * before) break;
  }
  if (calibrated_at.size() != out.theta.size() || calibrated_at != out.theta) calibrate();
  return out;
}

}  // namespace oscilab::analysis
