#include "analysis/model/model.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/reference_models.h"

namespace oscilab::analysis {
namespace {

// Real roots of a z³ + b z² + c z + d with three real roots, by the trigonometric form of
// Cardano's formula (Viète): independent of the companion-matrix eigenvalues the model uses.
std::vector<double> cubic_roots_closed_form(double a, double b, double c, double d) {
  const double p = (3 * a * c - b * b) / (3 * a * a);
  const double q = (2 * b * b * b - 9 * a * b * c + 27 * a * a * d) / (27 * a * a * a);
  std::vector<double> roots;
  for (int k = 0; k < 3; ++k) {
    const double t =
        2 * std::sqrt(-p / 3) *
        std::cos(std::acos(3 * q / (2 * p) * std::sqrt(-3 / p)) / 3 - 2 * std::numbers::pi * k / 3);
    roots.push_back(t - b / (3 * a));
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

TEST(Model, PaperEquilibriaMatchClosedFormCubicRoots) {
  const Model model = paper_model();
  const auto equilibria = model.equilibria();
  ASSERT_EQ(equilibria.size(), 3u);
  // Table 1, eq. (2): 7.35e5 z³ + 1.56e3 z² − 550 z + 2.4 = 0.
  const auto expected = cubic_roots_closed_form(7.35e5, 1.56e3, -550.0, 2.4);
  for (int i = 0; i < 3; ++i) {
    // Both are accurate to a few ulps of |z| ~ 3e-2 m after Newton polishing.
    EXPECT_NEAR(equilibria[i].z_m, expected[i], 1e-12) << "root " << i;
  }
  EXPECT_TRUE(equilibria[0].stable);
  EXPECT_FALSE(equilibria[1].stable);
  EXPECT_TRUE(equilibria[2].stable);
}

TEST(Model, PaperLinearFrequenciesMatchSection3) {
  const Model model = paper_model();
  // §3.1: ω₋ = 11.6·2π and ω₊ = 8.6·2π rad/s; the paper rounds to 0.1 Hz, hence ±0.05 Hz.
  EXPECT_NEAR(model.well(false).linear_frequency_hz, 11.6, 0.05);
  EXPECT_NEAR(model.well(true).linear_frequency_hz, 8.6, 0.05);
  EXPECT_EQ(model.equilibria()[1].linear_frequency_hz, 0.0);
}

TEST(Model, PaperFrictionPassesThroughTable3Values) {
  const Model model = paper_model();
  const double z_minus = model.well(false).z_m;
  const double z_plus = model.well(true).z_m;
  // At speed far above v_t the velocity shape is tanh → 1 and the Stribeck part → 0 (as 16/u³);
  // at ż = 100 v_t that part is (k_s − 1)·16e-6 ≈ 1e-6 relative, plus the viscous c ż we subtract.
  const double v = 100 * 1.5e-2;
  const auto friction_at = [&](double z) {
    return model.dissipative_force(z, v, nullptr) - 2.02 * v;
  };
  EXPECT_NEAR(friction_at(z_minus), 0.33, 1e-5);
  EXPECT_NEAR(friction_at(0.0), 0.67, 1e-5);
  EXPECT_NEAR(friction_at(z_plus), 0.66, 1e-5);
}

TEST(Model, PartialsMatchCentralDifferences) {
  const Model model = paper_model();
  for (double z : {-0.03, -0.01, 0.0, 0.012, 0.028}) {
    for (double v : {-0.2, -0.01, -0.001, 0.0, 0.004, 0.05, 0.3}) {
      const TermPartials p = model.partials(z, v, nullptr);
      const double hz = 1e-7, hv = 1e-8;
      const double d_dz =
          (model.restoring_force(z + hz, v, nullptr) - model.restoring_force(z - hz, v, nullptr)) /
          (2 * hz);
      const double d_dv =
          (model.restoring_force(z, v + hv, nullptr) - model.restoring_force(z, v - hv, nullptr)) /
          (2 * hv);
      // Central differences: truncation ∝ h² times the third derivative, plus rounding ~ε F/h;
      // 1e-5 relative (with a floor) covers both at these steps.
      EXPECT_NEAR(p.d_dz, d_dz, 1e-5 * std::max(1.0, std::abs(d_dz))) << z << " " << v;
      EXPECT_NEAR(p.d_dz_dot, d_dv, 1e-5 * std::max(1.0, std::abs(d_dv))) << z << " " << v;
    }
  }
}

TEST(Model, PotentialIsTheIntegralOfTheElasticForce) {
  const Model model = paper_model();
  // Simpson's rule on [a, b] is exact for the cubic K(z), so U(b) − U(a) must match to rounding.
  const double a = -0.035, b = 0.031;
  const double simpson =
      (b - a) / 6 *
      (model.elastic_force(a) + 4 * model.elastic_force(0.5 * (a + b)) + model.elastic_force(b));
  EXPECT_NEAR(model.potential_j(b) - model.potential_j(a), simpson, 1e-12);
}

TEST(Model, IllustrativeModelHasOneWellAtTheLinearFrequency) {
  const Model model = illustrative_model();
  const auto equilibria = model.equilibria();
  ASSERT_EQ(equilibria.size(), 1u);
  EXPECT_NEAR(equilibria[0].z_m, 0.0, 1e-15);
  // Table 2: √(k/m)/2π = √(800/1.3)/2π.
  EXPECT_NEAR(equilibria[0].linear_frequency_hz, std::sqrt(800.0 / 1.3) / (2 * std::numbers::pi),
              1e-12);
}

TEST(Model, ThrowsInputErrorWhenMassIsNotPositive) {
  std::vector<std::unique_ptr<ModelTerm>> terms;
  terms.push_back(std::make_unique<PolynomialStiffness>(std::vector<double>{0.0, 1.0}));
  EXPECT_THROW(Model(0.0, std::move(terms)), InputError);
}

TEST(Model, CopiesAreIndependent) {
  Model a = paper_model();
  Model b = a;
  b.term(2).set_parameter("c_ns_m", 5.0);
  EXPECT_DOUBLE_EQ(a.terms()[2]->parameter("c_ns_m"), 2.02);
  EXPECT_DOUBLE_EQ(b.terms()[2]->parameter("c_ns_m"), 5.0);
}

}  // namespace
}  // namespace oscilab::analysis
