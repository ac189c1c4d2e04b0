#include "analysis/identification/model_form.h"

#include <cmath>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"
#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/position_dependent_friction.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/viscous_damping.h"

namespace oscilab::analysis {
namespace {

TEST(ModelForm, PaperFormReadsTable3BackFromThePaperModel) {
  const ModelForm form = ModelForm::paper(paper_model());
  ASSERT_EQ(form.size(), 6);
  const std::vector<std::string> expected_names = {"fd_zminus_n", "fd_zplus_n", "fd_zero_n",
                                                   "vt_m_s",      "ks",         "c_ns_m"};
  EXPECT_EQ(form.names(), expected_names);  // the order of eq. (9)
  const Eigen::VectorXd theta = form.initial();
  // Table 3 (the parabola of eq. (6) passes exactly through the three values): 1e-12 is
  // rounding of the 3×3 solve.
  EXPECT_NEAR(theta(0), 0.33, 1e-12);
  EXPECT_NEAR(theta(1), 0.66, 1e-12);
  EXPECT_NEAR(theta(2), 0.67, 1e-12);
  EXPECT_NEAR(theta(3), 1.5e-2, 1e-15);
  EXPECT_NEAR(theta(4), 1.07, 1e-15);
  EXPECT_NEAR(theta(5), 2.02, 1e-15);
}

TEST(ModelForm, BuildAndThetaOfRoundTrip) {
  const ModelForm form = ModelForm::paper(paper_model());
  Eigen::VectorXd theta(6);
  theta << 0.5, 0.2, 0.9, 3e-3, 1.4, 0.7;
  const Model model = form.build(theta);
  EXPECT_LT((form.theta_of(model) - theta).norm(), 1e-12);
  // The built friction is eq. (6) through the three points at the wells.
  const auto& friction = dynamic_cast<const PositionDependentFriction&>(*model.terms()[1]);
  EXPECT_NEAR(friction.dynamic_friction_n(model.well(false).z_m), 0.5, 1e-12);
  EXPECT_NEAR(friction.dynamic_friction_n(0.0), 0.9, 1e-12);
  EXPECT_NEAR(model.terms()[2]->parameter("c_ns_m"), 0.7, 0.0);
}

TEST(ModelForm, UnitCubeMapIsLinearOrLogarithmic) {
  const ModelForm form = ModelForm::paper(paper_model());
  const Eigen::VectorXd theta = form.initial();
  EXPECT_LT((form.from_unit(form.to_unit(theta)) - theta).norm(), 1e-12);
  const Eigen::VectorXd half = form.from_unit(Eigen::VectorXd::Constant(6, 0.5));
  const FreeParameter& vt = form.parameters()[3];
  ASSERT_TRUE(vt.log_scale);
  EXPECT_NEAR(half(3), std::sqrt(vt.lower * vt.upper), 1e-15);  // geometric mid-point
  const FreeParameter& c = form.parameters()[5];
  EXPECT_NEAR(half(5), 0.5 * (c.lower + c.upper), 1e-12);  // arithmetic mid-point
  // from_unit clamps into the cube.
  EXPECT_NEAR(form.from_unit(Eigen::VectorXd::Constant(6, 2.0))(5), c.upper, 0.0);
}

TEST(ModelForm, BuildRejectsThetaOutsideTheTermsDomain) {
  const ModelForm form = ModelForm::paper(paper_model());
  Eigen::VectorXd theta = form.initial();
  theta(4) = 0.9;  // k_s < 1 (eq. (6))
  EXPECT_THROW(form.build(theta), InputError);
  EXPECT_THROW(form.build(Eigen::VectorXd::Ones(5)), InputError);
  theta = form.initial();
  theta(0) = std::nan("");
  EXPECT_THROW(form.build(theta), InputError);
}

TEST(ModelForm, PaperFormNeedsTheFrictionTerms) {
  EXPECT_THROW(ModelForm::paper(linear_oscillator_model(1.0, 100.0, 0.1)), InputError);
}

TEST(ModelForm, AddedTermJoinsTheSearch) {
  ModelForm form = ModelForm::paper(paper_model());
  form.add_term(std::make_unique<ViscousDamping>(0.5), {{"c_ns_m", 0.0, 5.0, false}});
  ASSERT_EQ(form.size(), 7);
  EXPECT_EQ(form.description(), "paper + viscous-damping");
  Eigen::VectorXd theta = form.initial();
  EXPECT_EQ(theta(6), 0.5);
  theta(6) = 1.5;
  const Model model = form.build(theta);
  ASSERT_EQ(model.terms().size(), 4u);
  EXPECT_EQ(model.terms()[3]->parameter("c_ns_m"), 1.5);
  // Bounds must hold the term's value.
  EXPECT_THROW(form.add_term(std::make_unique<ViscousDamping>(9.0), {{"c_ns_m", 0.0, 5.0, false}}),
               InputError);
}

TEST(ModelForm, OfTermsBindsNamedParameters) {
  const Model base = linear_oscillator_model(1.0, 100.0, 0.3);
  const ModelForm form = ModelForm::of_terms(base, {{1, {"c_ns_m", 0.0, 2.0, false}}});
  EXPECT_EQ(form.initial()(0), 0.3);
  EXPECT_THROW(ModelForm::of_terms(base, {{5, {"c_ns_m", 0.0, 2.0, false}}}), InputError);
  EXPECT_THROW(ModelForm::of_terms(base, {{1, {"c_ns_m", 1.0, 0.5, false}}}), InputError);
  EXPECT_THROW(ModelForm::of_terms(base, {{1, {"c_ns_m", 0.0, 2.0, true}}}), InputError);
}

// The stiffness identified: K(z)'s four coefficients join θ after the friction, bounded ±30 %
// about their values (or about 5 % of the largest term's force at the wells, for a small one);
// built models carry them, held forms keep them fixed and expand() puts them back.
TEST(ModelForm, FreeStiffnessJoinsTheSearchAndCanBeHeld) {
  ModelForm form = ModelForm::paper(paper_model());
  form.free_stiffness();
  ASSERT_EQ(form.size(), 10);
  EXPECT_EQ(form.names()[6], "stiffness_c0_n");
  EXPECT_EQ(form.names()[9], "stiffness_c3_n_m3");
  EXPECT_FALSE(form.is_stiffness(5));
  EXPECT_TRUE(form.is_stiffness(6));
  EXPECT_TRUE(form.frees_stiffness_power(2));
  EXPECT_FALSE(form.frees_stiffness_power(5));
  // Table 1: k3 = 735 000 N/m³ is c3, bounded to ±30 %.
  EXPECT_NEAR(form.initial()(9), 735000.0, 1e-6);
  EXPECT_NEAR(form.parameters()[9].lower, 0.7 * 735000.0, 1e-6);
  EXPECT_NEAR(form.parameters()[9].upper, 1.3 * 735000.0, 1e-6);
  Eigen::VectorXd theta = form.initial();
  theta(9) = 700000.0;
  const Model built = form.build(theta);
  const auto& k = dynamic_cast<const PolynomialStiffness&>(*built.terms()[0]);
  EXPECT_EQ(k.coefficients()[3], 700000.0);
  EXPECT_LT((form.theta_of(built) - theta).norm(), 1e-9);
  const ModelForm held = form.holding_stiffness(theta);
  ASSERT_EQ(held.size(), 6);
  const auto& held_k = dynamic_cast<const PolynomialStiffness&>(*held.base().terms()[0]);
  EXPECT_EQ(held_k.coefficients()[3], 700000.0);
  Eigen::VectorXd friction = held.initial();
  friction(5) = 1.5;
  const Eigen::VectorXd back = form.expand(friction, theta);
  EXPECT_EQ(back(5), 1.5);
  EXPECT_EQ(back(9), 700000.0);
  EXPECT_THROW(form.free_stiffness(), InputError);  // already free
}

// A law changed instead of a term added: the friction's presliding length becomes free, and the
// models built from the form carry the friction's state.
TEST(ModelForm, ChangeTermFreesAParameterOfALawItHolds) {
  ModelForm form = ModelForm::paper(paper_model());
  form.change_term("position-dependent-friction", {{"presliding_length_m", 1e-6, 1e-3, true}},
                   {1e-5});
  ASSERT_EQ(form.size(), 7);
  EXPECT_EQ(form.base().state_size(), 1);
  Eigen::VectorXd theta = form.initial();
  EXPECT_EQ(theta(6), 1e-5);
  theta(6) = 3e-6;
  const Model model = form.build(theta);
  EXPECT_EQ(model.terms()[1]->parameter("presliding_length_m"), 3e-6);
  EXPECT_EQ(model.state_size(), 1);
  EXPECT_THROW(form.change_term("dahl-friction", {{"fc_n", 0.1, 1.0, false}}, {0.5}), InputError);
  EXPECT_THROW(form.change_term("viscous-damping", {{"c_ns_m", 0.0, 1.0, false}}, {2.0}),
               InputError);  // outside its bounds
}

}  // namespace
}  // namespace oscilab::analysis
