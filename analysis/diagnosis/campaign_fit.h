#pragma once

#include <memory>

#include "analysis/common/job.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

/// A fit's result and the objective its σ budget and S^mod belong to.
struct CampaignFit {
  FitResult fit;
  std::shared_ptr<const EdcObjective> objective;
};

/// The friction fit of a prepared problem (prepare_fit), as `fit`, the app's Fit and Python run
/// it. With the stiffness held (model or rfs) it is fit_edc on the prepared objective. With the
/// stiffness identified (the form frees K(z)'s coefficients) the search runs over the friction
/// with K(z) held at its start (the records' slice, which the EDC alone barely corrects), then
/// settle_model frees everything on the EDC and the response fingerprints, which pin K(z); the
/// result holds the whole θ, its evaluation and σ budget are the settled model's, and its
/// uncertainty is the EDC's at the settled θ (the fingerprints that pin K(z) are not in it: the
/// stiffness's intervals are wider than what the fit knew). `progress` gets θ in the prepared
/// form's order and size. Throws InputError as fit_edc does.
CampaignFit fit_campaign(const PreparedFit& prepared, const CampaignAnalysis& campaign,
                         const FitOptions& options, const FitProgressFn& progress = {},
                         const CancelToken& cancel = {});

}  // namespace oscilab::analysis
