#include "ui/identification/fit_job.h"

#include <algorithm>
#include <chrono>

#include <QMetaObject>
#include <QPointer>

#include "analysis/common/input_error.h"
#include "analysis/diagnosis/campaign_fit.h"
#include "daq/recording/campaign_reader.h"

namespace oscilab::ui {
namespace {

// The live EDC curve is redrawn at most 5 times a second.
constexpr auto kPreviewInterval = std::chrono::milliseconds(200);

// S^mod of the model at θ at every measured level, per group (0 where it is not solved), J. Runs
// on the fit's worker: about one model evaluation (the level responses of both wells, ~3 ms),
// through edc_at so that the fit's own evaluation count stays that of the search.
std::vector<std::vector<double>> model_edc(const analysis::EdcObjective& objective,
                                           const Eigen::VectorXd& theta) {
  std::vector<std::vector<double>> out;
  const analysis::Model model = objective.form().build(theta);  // InputError: caught by caller
  for (const analysis::EdcGroup& group : objective.data().groups) {
    std::vector<double> f0_n;
    for (const analysis::MeasuredLevel& level : group.levels) f0_n.push_back(level.f0_n);
    out.push_back(objective.edc_at(model, group.positive_well, group.freq_hz, f0_n));
  }
  return out;
}

}  // namespace

FitJob::FitJob(QObject* parent) : QObject(parent) {
  qRegisterMetaType<std::shared_ptr<const FitPreview>>();
}

bool FitJob::is_current(const FitPreview& preview) const {
  return work_.running() && preview.fit_number == fits_started_;
}

bool FitJob::start(std::vector<std::string> recordings, analysis::FitSetup setup,
                   analysis::FitOptions options) {
  if (work_.running()) return false;
  const long fit_number = ++fits_started_;
  auto outcome = std::make_shared<FitOutcome>();
  outcome->records = recordings;
  QPointer<FitJob> self(this);
  FitJob* job = this;  // outlives the worker (see work_)
  return work_.start(std::move(outcome), [paths = std::move(recordings), options, setup, self, job,
                                          fit_number](FitOutcome& outcome,
                                                      const ProgressFn& progress,
                                                      const CancelToken& cancel) {
    const analysis::CampaignAnalysis campaign = daq::analyze_recordings(paths, {}, {}, {}, cancel);
    if (campaign.status == JobStatus::Cancelled) return;  // reported as cancelled, no error
    analysis::FitSetup fit_setup = setup;
    fit_setup.cost.cancel = cancel;  // the σ budget's calibration stops with the job
    analysis::PreparedFit prepared = analysis::prepare_fit(campaign, fit_setup);
    const std::shared_ptr<const analysis::EdcObjective> objective = prepared.objective;
    outcome.objective = objective;
    outcome.notes = std::move(prepared.notes);
    const auto budget = static_cast<double>(analysis::evaluation_budget(options));
    // The convergence curve gets a point at most every 50 ms (20 redraws a second), the
    // live EDC curve of the best θ every 200 ms. The searches call this one at a time.
    const auto long_ago = std::chrono::steady_clock::now() - std::chrono::seconds(1);
    auto last_point = long_ago;
    auto last_preview = long_ago;
    analysis::CampaignFit result = analysis::fit_campaign(
        prepared, campaign, options,
        [&](const analysis::FitProgress& p) {
          if (p.stage == analysis::FitStage::Uncertainty) return;
          progress(std::min(0.95, static_cast<double>(p.evaluations) / budget));
          const auto now = std::chrono::steady_clock::now();
          if (now - last_preview >= kPreviewInterval && !cancel.cancelled() &&
              p.best_theta.size() == objective->form().size()) {
            auto preview = std::make_shared<FitPreview>();
            preview->fit_number = fit_number;
            preview->evaluations = p.evaluations;
            preview->best_weighted_cost = p.best_weighted_cost;
            preview->theta = p.best_theta;
            preview->objective = objective;
            try {
              preview->edc_mod_j = model_edc(*objective, p.best_theta);
              Q_EMIT job->preview(std::move(preview));
            } catch (const InputError&) {
              // θ outside a term's domain: no curve this time.
            }
            // From the end of this one, so that sent previews are ≥ 200 ms apart.
            last_preview = std::chrono::steady_clock::now();
          }
          if (now - last_point < std::chrono::milliseconds(50)) return;
          last_point = now;
          QMetaObject::invokeMethod(
              self.data(),
              [self, evaluations = p.evaluations, cost = p.best_weighted_cost] {
                if (self) Q_EMIT self->convergence_point(evaluations, cost);
              },
              Qt::QueuedConnection);
        },
        cancel);
    outcome.fit = std::move(result.fit);
    outcome.objective = std::move(result.objective);  // the settled one, K(z) identified
  });
}

}  // namespace oscilab::ui
