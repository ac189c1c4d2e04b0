#include "analysis/identification/campaign_model.h"

#include <cmath>
#include <sstream>

#include "analysis/common/input_error.h"
#include "analysis/model/polynomial_stiffness.h"

namespace oscilab::analysis {
namespace {

// Whether the slice's cubic has a well on either side of z = 0.
bool bistable_about_zero(const StiffnessSlice& slice) {
  const Eigen::VectorXd& c = slice.fit.coefficients;
  std::vector<std::unique_ptr<ModelTerm>> terms;
  terms.push_back(
      std::make_unique<PolynomialStiffness>(std::vector<double>(c.data(), c.data() + c.size())));
  try {
    const Model elastic(1.0, std::move(terms));
    return elastic.well(false).z_m < 0.0 && elastic.well(true).z_m > 0.0;
  } catch (const InputError&) {
    return false;  // no such well
  }
}

}  // namespace

Model campaign_model(const Model& model, const CampaignAnalysis& campaign,
                     StiffnessSource stiffness, std::vector<std::string>& notes) {
  double mass_kg = 0.0;
  std::string mass_record;
  for (const RecordAnalysis& record : campaign.records) {
    if (record.per_unit_mass) {
      throw InputError(record.name +
                       ": mass_kg is missing from the sidecar: a fit compares energies in J with "
                       "the model's, so the moving mass must be known");
    }
    const double m = record.setup.mass_kg;
    if (mass_kg == 0.0) {
      mass_kg = m;
      mass_record = record.name;
    } else if (std::abs(m - mass_kg) > 1e-9 * mass_kg) {
      throw InputError(record.name + ": mass_kg " + std::to_string(m) + " differs from " +
                       mass_record + "'s " + std::to_string(mass_kg) +
                       ": fit records of one oscillator together");
    }
  }
  std::vector<std::unique_ptr<ModelTerm>> terms;
  // An identified stiffness starts from the slice's cubic when there is one that is bistable
  // about z = 0 (eq. (9) puts f_d(z) through both wells and z = 0). The slice of records of one
  // well only sees that well: its cubic's other roots are an extrapolation, often not a well.
  const bool slice_bistable = campaign.stiffness && bistable_about_zero(*campaign.stiffness);
  if (stiffness == StiffnessSource::Rfs && campaign.stiffness && !slice_bistable) {
    throw InputError(
        "--stiffness rfs: the records' stiffness slice has no wells on both sides of z = 0 "
        "(records of one well?): give --stiffness model or identified");
  }
  const bool from_slice = stiffness == StiffnessSource::Rfs ||
                          (stiffness == StiffnessSource::Identified && slice_bistable);
  if (stiffness == StiffnessSource::Identified && !campaign.stiffness) {
    notes.push_back(
        "stiffness identified from the stepped responses, starting from the model's "
        "K(z) (the records give no stiffness slice: " +
        campaign.rfs_message + ")");
  } else if (stiffness == StiffnessSource::Identified && !slice_bistable) {
    notes.push_back(
        "stiffness identified from the stepped responses, starting from the model's K(z) (the "
        "records' stiffness slice has no wells on both sides of z = 0: records of one well?)");
  }
  for (const auto& term : model.terms()) {
    if (from_slice && term->type() == "polynomial-stiffness") {
      if (!campaign.stiffness) {
        throw InputError("--stiffness rfs: the records give no stiffness slice: " +
                         campaign.rfs_message);
      }
      const Eigen::VectorXd& c = campaign.stiffness->fit.coefficients;
      terms.push_back(std::make_unique<PolynomialStiffness>(
          std::vector<double>(c.data(), c.data() + c.size())));
      std::ostringstream note;
      note << (stiffness == StiffnessSource::Identified
                   ? "stiffness identified from the stepped responses, starting from the records' "
                     "restoring-force slice (eq. (2)): k3 = "
                   : "stiffness from the records' restoring-force slice (eq. (2)): k3 = ")
           << c[3] << " N/m^3, k2 = " << c[2] << " N/m^2, k1 = " << -c[1] << " N/m, k0 = " << c[0]
           << " N";
      notes.push_back(note.str());
      continue;
    }
    terms.push_back(term->clone());
  }
  if (mass_kg > 0.0 && std::abs(mass_kg - model.mass_kg()) > 1e-9 * model.mass_kg()) {
    std::ostringstream note;
    note << "mass " << mass_kg << " kg from the recordings (the model had " << model.mass_kg()
         << " kg)";
    notes.push_back(note.str());
  }
  return Model(mass_kg > 0.0 ? mass_kg : model.mass_kg(), std::move(terms), model.name());
}

}  // namespace oscilab::analysis
