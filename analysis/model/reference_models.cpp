#include "analysis/model/reference_models.h"

#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/position_dependent_friction.h"
#include "analysis/model/viscous_damping.h"

namespace oscilab::analysis {
namespace {

constexpr double kPaperMassKg = 0.26;  // §2

PolynomialStiffness paper_stiffness() {
  // Table 1.
  return PolynomialStiffness::from_paper(7.35e5, 1.56e3, 550.0, 2.4);
}

}  // namespace

Model paper_model(const PaperFriction& friction) {
  // f_d(z) of eq. (6) through Table 3's values at the equilibria of the Table 1 stiffness.
  std::vector<std::unique_ptr<ModelTerm>> stiffness_only;
  stiffness_only.push_back(paper_stiffness().clone());
  const Model elastic(kPaperMassKg, std::move(stiffness_only));
  const double z_minus = elastic.well(false).z_m;
  const double z_plus = elastic.well(true).z_m;

  std::vector<std::unique_ptr<ModelTerm>> terms;
  terms.push_back(paper_stiffness().clone());
  terms.push_back(
      std::make_unique<PositionDependentFriction>(PositionDependentFriction::from_three_points(
          z_minus, friction.fd_zminus_n, friction.fd_zero_n, z_plus, friction.fd_zplus_n,
          friction.ks, friction.vt_m_s)));
  terms.push_back(std::make_unique<ViscousDamping>(friction.c_ns_m));
  return Model(kPaperMassKg, std::move(terms), "paper");
}

Model paper_model() { return paper_model(PaperFriction{}); }

Model linear_oscillator_model(double mass_kg, double k_n_m, double c_ns_m) {
  std::vector<std::unique_ptr<ModelTerm>> terms;
  terms.push_back(std::make_unique<PolynomialStiffness>(std::vector<double>{0.0, k_n_m}));
  terms.push_back(std::make_unique<ViscousDamping>(c_ns_m));
  return Model(mass_kg, std::move(terms), "linear");
}

Model illustrative_model() {
  // Table 2; eq. (14) is eq. (7) with a linear spring and a position-independent f_d.
  PositionDependentFriction::Parameters friction;
  friction.gamma_n = 1.0;
  friction.ks = 1.2;
  friction.vt_m_s = 1e-2;
  std::vector<std::unique_ptr<ModelTerm>> terms;
  terms.push_back(std::make_unique<PolynomialStiffness>(std::vector<double>{0.0, 800.0}));
  terms.push_back(std::make_unique<PositionDependentFriction>(friction));
  terms.push_back(std::make_unique<ViscousDamping>(1.0));
  return Model(1.3, std::move(terms), "illustrative");
}

}  // namespace oscilab::analysis
