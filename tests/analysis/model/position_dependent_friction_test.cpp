#include "analysis/model/position_dependent_friction.h"

#include <cmath>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

TEST(PositionDependentFriction, ParabolaThroughThreePointsHitsThem) {
  const auto p =
      PositionDependentFriction::from_three_points(-0.03, 0.3, 0.7, 0.025, 0.6, 1.1, 0.01);
  const PositionDependentFriction friction(p);
  EXPECT_NEAR(friction.dynamic_friction_n(-0.03), 0.3, 1e-12);
  EXPECT_NEAR(friction.dynamic_friction_n(0.0), 0.7, 1e-12);
  EXPECT_NEAR(friction.dynamic_friction_n(0.025), 0.6, 1e-12);
}

TEST(PositionDependentFriction, DynamicFrictionIsClippedAtZero) {
  PositionDependentFriction::Parameters p;
  p.alpha_n_m2 = -1000.0;  // f_d = 1 − 1000 z² < 0 for |z| > 0.0316 m
  p.gamma_n = 1.0;
  const PositionDependentFriction friction(p);
  EXPECT_EQ(friction.dynamic_friction_n(0.05), 0.0);
  EXPECT_EQ(friction.force(0.05, 1.0, nullptr), 0.0);
  EXPECT_EQ(friction.partials(0.05, 1.0, nullptr).d_dz, 0.0);
}

TEST(PositionDependentFriction, VelocityShapeMatchesEquation7) {
  PositionDependentFriction::Parameters p;
  p.gamma_n = 1.0;
  p.ks = 1.5;
  p.vt_m_s = 0.02;
  const PositionDependentFriction friction(p);
  // At ż = v_t: u = 1, q = 1, so g = tanh(4) + (k_s − 1)·1.
  EXPECT_NEAR(friction.velocity_shape(0.02), std::tanh(4.0) + 0.5, 1e-15);
  // Odd in ż.
  EXPECT_NEAR(friction.velocity_shape(-0.013), -friction.velocity_shape(0.013), 1e-15);
  // Slope at 0: 4/v_t from tanh plus (k_s − 1)·(¾)/(¾)³/v_t from the Stribeck part.
  EXPECT_NEAR(friction.velocity_shape_slope(0.0), (4.0 + 0.5 * 0.75 / (0.75 * 0.75 * 0.75)) / 0.02,
              1e-9);
}

TEST(PositionDependentFriction, ThrowsInputErrorWhenKsBelowOne) {
  PositionDependentFriction::Parameters p;
  p.ks = 0.9;
  EXPECT_THROW(PositionDependentFriction{p}, InputError);
  p.ks = 1.0;
  p.vt_m_s = 0.0;
  EXPECT_THROW(PositionDependentFriction{p}, InputError);
}

}  // namespace
}  // namespace oscilab::analysis
