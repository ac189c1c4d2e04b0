// The terms a diagnosis adds (docs/contracts.md §4 effect names): forces against their
// definitions and closed-form cycle energies, analytic partials against central differences, JSON
// round trips and domain errors.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/coulomb_friction.h"
#include "analysis/model/dahl_friction.h"
#include "analysis/model/model_json.h"
#include "analysis/model/velocity_power_damping.h"

namespace oscilab::analysis {
namespace {

// ∂F/∂ż by central differences with h = 1e-7 m/s: truncation O(h²) ≈ 1e-14 relative, rounding
// ≈ 1e-16/1e-7 = 1e-9 relative, hence the 1e-6 relative bound.
void expect_partials_match_differences(const ModelTerm& term) {
  for (double v : {-0.3, -0.02, -1e-3, 2e-4, 5e-3, 0.1, 0.7}) {
    const double h = 1e-7;
    const double numeric =
        (term.force(0.01, v + h, nullptr) - term.force(0.01, v - h, nullptr)) / (2.0 * h);
    const double analytic = term.partials(0.01, v, nullptr).d_dz_dot;
    EXPECT_NEAR(analytic, numeric, 1e-6 * std::max(1.0, std::abs(numeric)))
        << term.type() << " at ż = " << v;
    EXPECT_EQ(term.partials(0.01, v, nullptr).d_dz, 0.0) << term.type();
  }
}

// Energy per harmonic cycle z = Z sin ωt by the midpoint rule over 20000 steps (error ~1e-8).
double cycle_energy(const ModelTerm& term, double amplitude_m, double omega) {
  const int n = 20000;
  double work = 0.0;
  for (int k = 0; k < n; ++k) {
    const double t = (k + 0.5) / n * 2.0 * std::numbers::pi / omega;
    const double v = amplitude_m * omega * std::cos(omega * t);
    work += term.force(0.0, v, nullptr) * v * (2.0 * std::numbers::pi / omega / n);
  }
  return work;
}

TEST(EffectTerms, VelocityPowerDampingForcesAndCycleEnergies) {
  const VelocityPowerDamping quadratic(2, 3.0), cubic(3, 5.0);
  EXPECT_EQ(quadratic.type(), "quadratic-damping");
  EXPECT_EQ(cubic.type(), "cubic-damping");
  EXPECT_DOUBLE_EQ(quadratic.force(0.0, -0.2, nullptr), -3.0 * 0.04);
  EXPECT_DOUBLE_EQ(cubic.force(0.0, -0.2, nullptr), -5.0 * 0.008);
  const double z = 2e-3, w = 2 * std::numbers::pi * 9;
  // Closed forms: 8/3 c2 ω² Z³ and 3π/4 c3 ω³ Z⁴.
  EXPECT_NEAR(cycle_energy(quadratic, z, w) / (8.0 / 3.0 * 3.0 * w * w * z * z * z), 1.0, 1e-6);
  EXPECT_NEAR(cycle_energy(cubic, z, w) / (0.75 * std::numbers::pi * 5.0 * std::pow(w * z, 3) * z),
              1.0, 1e-6);
  expect_partials_match_differences(quadratic);
  expect_partials_match_differences(cubic);
}

TEST(EffectTerms, CoulombAndStribeckShapes) {
  const CoulombFriction coulomb(0.4, 1e-4);
  // Rectangle loop: 4 F_c Z when ωZ ≫ v_ε (here ωZ ≈ 0.11 m/s, 1100 v_ε): the tanh's rounding
  // near ż = 0 takes ~v_ε/(ωZ) ≈ 1e-3 of it.
  const double z = 2e-3, w = 2 * std::numbers::pi * 9;
  EXPECT_NEAR(cycle_energy(coulomb, z, w) / (4.0 * 0.4 * z), 1.0, 2e-3);
  const StribeckFriction stribeck(0.3, 0.01);
  // u / (¼u² + ¾)² peaks at u = 1 with value 1: the force there is f_s.
  EXPECT_NEAR(stribeck.force(0.0, 0.01, nullptr), 0.3, 1e-15);
  EXPECT_LT(stribeck.force(0.0, 0.1, nullptr), 0.01);  // vanishes at high speed
  expect_partials_match_differences(coulomb);
  expect_partials_match_differences(stribeck);
}

TEST(EffectTerms, DahlStateRateAndExactUpdate) {
  const DahlFriction dahl(0.2, 1e4);
  double s = 0.0;
  dahl.initial_state(0.0, &s);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(dahl.force(0.0, 0.0, nullptr), 0.0);  // untracked: at rest
  double rate = 0.0;
  const double state = 0.5;
  dahl.state_rate(0.0, 0.01, &state, &rate);
  EXPECT_DOUBLE_EQ(rate, 1e4 / 0.2 * 0.01 * 0.5);  // (σ0/F_c) ż (1 − s sgn ż)
  // A long stretch saturates the state at sgn Δz: F → F_c.
  dahl.advance_state(0.0, 0.1, 1e-2, 0.1, 0.1, &s);
  EXPECT_NEAR(dahl.force(0.0, 0.1, &s), 0.2, 1e-12);
}

TEST(EffectTerms, JsonRoundTripKeepsEveryParameter) {
  std::vector<std::unique_ptr<ModelTerm>> terms;
  terms.push_back(std::make_unique<VelocityPowerDamping>(2, 1.5));
  terms.push_back(std::make_unique<VelocityPowerDamping>(3, 2.5));
  terms.push_back(std::make_unique<CoulombFriction>(0.1, 2e-3));
  terms.push_back(std::make_unique<StribeckFriction>(0.2, 5e-3));
  terms.push_back(std::make_unique<DahlFriction>(0.05, 3e3));
  const Model model(0.26, std::move(terms), "effects");
  const Model back = model_from_json(model.to_json(), "effects.json");
  ASSERT_EQ(back.terms().size(), 5u);
  EXPECT_EQ(back.state_size(), 1);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(back.terms()[i]->to_json(), model.terms()[i]->to_json());
  }
}

TEST(EffectTerms, DomainAndJsonErrorsNameTheParameter) {
  EXPECT_THROW(VelocityPowerDamping(4, 1.0), InputError);
  EXPECT_THROW(VelocityPowerDamping(2, -1.0), InputError);
  EXPECT_THROW(CoulombFriction(0.1, 0.0), InputError);
  EXPECT_THROW(DahlFriction(0.0, 1e3), InputError);
  try {
    term_from_json({{"type", "presliding-hysteresis"}, {"fc_n", 0.1}}, "m.json: terms[3]");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(), "m.json: terms[3]: missing field \"sigma0_n_m\"");
  }
  try {
    term_from_json({{"type", "cubic-damping"}, {"c3_ns3_m3", -2.0}}, "m.json: terms[1]");
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("m.json: terms[1]: cubic-damping: c3_ns3_m3"),
              std::string::npos)
        << error.what();
  }
  CoulombFriction coulomb(0.1, 1e-3);
  EXPECT_THROW(coulomb.set_parameter("fc", 0.2), InputError);
  EXPECT_THROW(coulomb.set_parameter("v_eps_m_s", -1.0), InputError);
}

}  // namespace
}  // namespace oscilab::analysis
