#pragma once

#include <string>
#include <vector>

#include "analysis/model/model.h"
#include "analysis/pipeline/offline_analysis.h"

namespace oscilab::analysis {

/// Where the fixed part of a friction fit (mass and stiffness) comes from.
enum class StiffnessSource {
  Model,       // the model's K(z) as it is (e.g. Table 1), held fixed
  Rfs,         // the cubic K(z) fitted to the campaign's stiffness slice (§3.1), held fixed
  Identified,  // K(z)'s coefficients free parameters of the fit, identified with the friction
               // from the stepped responses; they start from the stiffness slice's cubic when
               // the records give one, else from the model's K(z)
};

/// The base model of a fit on these records: `model` with the recordings' mass (the EDCs were
/// measured with f = −m b̈ of that mass, so the model must move the same mass) and, if asked,
/// the stiffness slice's cubic in place of the model's polynomial stiffness. What was changed is
/// appended to `notes`. Throws InputError when a record has no mass (energies per unit mass
/// cannot be compared with a model's), when the records disagree on the mass, or when the RFS
/// stiffness is asked for but the campaign has none.
Model campaign_model(const Model& model, const CampaignAnalysis& campaign,
                     StiffnessSource stiffness, std::vector<std::string>& notes);

}  // namespace oscilab::analysis
