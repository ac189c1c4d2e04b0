#include "analysis/identification/fit_uncertainty.h"

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/viscous_damping.h"

namespace oscilab::analysis {
namespace {

// A linear oscillator m z̈ + c ż + k z = f has the EDC in closed form: Z1 = F/(k − mω² + icω), so
//
//   S(c, k) = π c ω |Z1|² = π c ω F² / D,   D = (k − mω²)² + c²ω²,
//   ∂S/∂c = π ω F² (D − 2c²ω²) / D²,   ∂S/∂k = −2π c ω F² (k − mω²) / D².
//
// Harmonic balance solves a linear model exactly (no higher harmonics), so the objective's S^mod is
// this S to the Newton tolerance, and the least-squares covariance of the whitened residuals
// r_k = (S_k^mes − S_k^mod)/σ_k is known in closed form: J_kj = −∂S_k/∂θ_j / σ_k and
// Cov = max{1, χ²/(n − p)} (JᵀJ)⁻¹.
constexpr double kMassKg = 1.3, kStiffness = 800.0, kDamping = 1.0;  // kg, N/m, N s/m

struct Level {
  double freq_hz, f0_n;
};

// One frequency alone cannot separate c from k (every level's relative sensitivities are the
// same: S ∝ F²), so the levels span three frequencies around the 3.95 Hz resonance.
std::vector<Level> levels() {
  std::vector<Level> out;
  for (double f : {3.0, 5.0, 8.0}) {
    for (double f0 : {0.5, 1.0, 2.0}) out.push_back({f, f0});
  }
  return out;
}

double edc(const Level& l, double c, double k) {
  const double w = 2 * std::numbers::pi * l.freq_hz;
  const double d = std::pow(k - kMassKg * w * w, 2) + c * c * w * w;
  return std::numbers::pi * c * w * l.f0_n * l.f0_n / d;
}

Eigen::Vector2d edc_gradient(const Level& l, double c, double k) {
  const double w = 2 * std::numbers::pi * l.freq_hz;
  const double detune = k - kMassKg * w * w;
  const double d = detune * detune + c * c * w * w;
  const double a = std::numbers::pi * w * l.f0_n * l.f0_n;
  return {a * (d - 2 * c * c * w * w) / (d * d), -2 * a * c * detune / (d * d)};
}

// Measured EDCs: the closed form at the true (c, k), times (1 + misfit·(−1)^k).
EdcDataset dataset(double misfit = 0.0) {
  EdcDataset data;
  int k = 0;
  for (const Level& l : levels()) {
    if (data.groups.empty() || data.groups.back().freq_hz != l.freq_hz) {
      data.groups.push_back({true, l.freq_hz, {}});
    }
    MeasuredLevel m;
    m.f0_n = l.f0_n;
    m.edc_j = edc(l, kDamping, kStiffness) * (1.0 + misfit * ((k++ % 2 == 0) ? 1.0 : -1.0));
    m.record = "closed form";
    data.groups.back().levels.push_back(m);
  }
  return data;
}

// Free θ = [c, k] (term 1's c_ns_m, term 0's linear coefficient c1).
ModelForm form(bool log_c = false, double k_lower = 500.0) {
  return ModelForm::of_terms(linear_oscillator_model(kMassKg, kStiffness, kDamping),
                             {{1, {"c_ns_m", 0.1, 3.0, log_c}}, {0, {"c1", k_lower, 1100.0}}});
}

EdcCostSettings fixed_floor(double rho) {
  EdcCostSettings s;
  s.model_error_rel = rho;  // σ_k = ρ S_k^mes (no cycles in this data)
  s.adaptive_harmonics = false;
  return s;
}

UncertaintyOptions quick() {
  UncertaintyOptions o;
  o.threads = 2;
  return o;
}

// (JᵀJ)⁻¹ · max{1, χ²/dof} from the closed form, with σ_k = ρ S_k^mes as the objective sets it.
Eigen::Matrix2d closed_form_covariance(const EdcDataset& data, double rho) {
  const std::vector<Level> ls = levels();
  Eigen::MatrixXd j(static_cast<Eigen::Index>(ls.size()), 2);
  double chi2 = 0.0;
  int k = 0;
  for (const EdcGroup& g : data.groups) {
    for (const MeasuredLevel& m : g.levels) {
      const double sigma = rho * m.edc_j;
      j.row(k) = -edc_gradient(ls[k], kDamping, kStiffness).transpose() / sigma;
      chi2 += std::pow((m.edc_j - edc(ls[k], kDamping, kStiffness)) / sigma, 2);
      ++k;
    }
  }
  const double dof = static_cast<double>(ls.size()) - 2.0;
  const Eigen::Matrix2d jtj = j.transpose() * j;
  return std::max(1.0, chi2 / dof) * jtj.inverse();
}

// The tolerance of the comparisons with the closed form: fit_uncertainty differentiates the
// residuals by central differences with a unit-cube step of 1e-3 (c: 2.9e-3 N s/m, k: 0.6 N/m).
// Their truncation error is (h²/6)·S'''/S'; for k, with S ∝ 1/(k − mω²)² away from resonance,
// that is 2(h/(k − mω²))² ≤ 6.3e-6 relative (|k − mω²| ≥ 338 N/m at these frequencies; measured
// 5e-6 on the standard error of k); c's is far smaller (S is nearly linear in c here), and the
// Newton tolerance of the harmonic balance adds ~1e-9. 2e-5 relative is three times the bound.
constexpr double kDifferenceTol = 2e-5;

TEST(FitUncertainty, CovarianceIsTheClosedFormGaussNewtonCovariance) {
  const EdcDataset data = dataset();
  const EdcObjective objective(form(), data, fixed_floor(0.01));
  const Eigen::Vector2d theta(kDamping, kStiffness);
  const FitUncertainty u = fit_uncertainty(objective, theta, quick());
  ASSERT_TRUE(u.ok) << u.message;
  EXPECT_EQ(u.levels, 9);
  EXPECT_EQ(u.dof, 7);
  // The data are the model's own EDC: χ² ≈ 0, so s² = 1 (never shrunk below the stated σ).
  EXPECT_LT(u.reduced_chi2, 1e-12);
  // Student's t, 0.975 quantile, 7 degrees of freedom (tables: 2.3646).
  EXPECT_NEAR(u.t_quantile, 2.364624251592785, 1e-9);
  EXPECT_EQ(u.evaluations, 1 + 2 * 2);  // the optimum and two differences per parameter

  const Eigen::Matrix2d expected = closed_form_covariance(data, 0.01);
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(u.covariance(i, j), expected(i, j),
                  kDifferenceTol * std::sqrt(expected(i, i) * expected(j, j)))
          << "(" << i << ", " << j << ")";
    }
  }
  const double rho_ck = expected(0, 1) / std::sqrt(expected(0, 0) * expected(1, 1));
  EXPECT_NEAR(u.correlation(0, 1), rho_ck, kDifferenceTol);
  EXPECT_EQ(u.correlation(0, 0), 1.0);
  ASSERT_EQ(u.parameters.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    const ParameterUncertainty& q = u.parameters[static_cast<std::size_t>(i)];
    const double se = std::sqrt(expected(i, i));
    EXPECT_NEAR(q.standard_error, se, kDifferenceTol * se) << q.name;
    EXPECT_EQ(q.value, theta(i));
    EXPECT_DOUBLE_EQ(q.lower_95, q.value - u.t_quantile * q.standard_error);
    EXPECT_DOUBLE_EQ(q.upper_95, q.value + u.t_quantile * q.standard_error);
    EXPECT_FALSE(q.at_bound);
    EXPECT_TRUE(std::isnan(q.bootstrap_std));  // no replicates asked for
  }
  EXPECT_EQ(u.parameters[0].name, "c_ns_m");
  EXPECT_EQ(u.parameters[1].name, "c1");
}

// σ_k = ρ S_k^mes: tripling ρ divides J by 3 exactly and, while χ²/dof ≤ 1, multiplies every
// standard error by 3 (to the rounding of an SVD).
TEST(FitUncertainty, StandardErrorsScaleWithTheDataSigma) {
  const EdcDataset data = dataset();
  const Eigen::Vector2d theta(kDamping, kStiffness);
  const FitUncertainty a =
      fit_uncertainty(EdcObjective(form(), data, fixed_floor(0.01)), theta, quick());
  const FitUncertainty b =
      fit_uncertainty(EdcObjective(form(), data, fixed_floor(0.03)), theta, quick());
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(b.parameters[i].standard_error / a.parameters[i].standard_error, 3.0, 1e-9);
  }
  EXPECT_NEAR(b.correlation(0, 1), a.correlation(0, 1), 1e-9);
}

// A misfit beyond σ (±5 % against σ = 1 %: χ²/dof ≈ 32) scales the covariance by χ²/dof, as the
// closed form with that factor says; then σ cancels: doubling ρ quarters χ² and JᵀJ alike and
// leaves the covariance unchanged.
TEST(FitUncertainty, MisfitBeyondSigmaInflatesTheCovarianceByTheReducedChiSquare) {
  const EdcDataset data = dataset(0.05);
  const Eigen::Vector2d theta(kDamping, kStiffness);
  const FitUncertainty u =
      fit_uncertainty(EdcObjective(form(), data, fixed_floor(0.01)), theta, quick());
  EXPECT_GT(u.reduced_chi2, 10.0);
  const Eigen::Matrix2d expected = closed_form_covariance(data, 0.01);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(u.parameters[static_cast<std::size_t>(i)].standard_error, std::sqrt(expected(i, i)),
                kDifferenceTol * std::sqrt(expected(i, i)));
  }
  const FitUncertainty doubled =
      fit_uncertainty(EdcObjective(form(), data, fixed_floor(0.02)), theta, quick());
  EXPECT_NEAR(doubled.reduced_chi2, u.reduced_chi2 / 4.0, 1e-12 * u.reduced_chi2);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(doubled.parameters[i].standard_error / u.parameters[i].standard_error, 1.0, 1e-9);
  }
}

// The covariance is of θ, whatever the search coordinates: c searched on a log scale
// (dθ/du = θ ln(upper/lower)) gives the same standard errors to the difference error (the log
// step, ±0.34 % of c, is about as large as the linear one).
TEST(FitUncertainty, LogScaleSearchCoordinateGivesTheSameCovariance) {
  const EdcDataset data = dataset();
  const Eigen::Vector2d theta(kDamping, kStiffness);
  const FitUncertainty u =
      fit_uncertainty(EdcObjective(form(true), data, fixed_floor(0.01)), theta, quick());
  const Eigen::Matrix2d expected = closed_form_covariance(data, 0.01);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(u.parameters[static_cast<std::size_t>(i)].standard_error, std::sqrt(expected(i, i)),
                kDifferenceTol * std::sqrt(expected(i, i)));
  }
}

// Two viscous dampers c₁ ż + c₂ ż: the EDCs see only c₁ + c₂, so JᵀJ is singular along
// (1, −1, 0). Both dampers get an infinite standard error and say why; k, orthogonal to that
// direction, keeps the standard error it has with a single damper c = c₁ + c₂ (the
// pseudo-inverse's k-marginal is invariant under the reparametrisation (c₁, c₂) → c₁ + c₂).
TEST(FitUncertainty, UnidentifiableDirectionGetsAnInfiniteStandardError) {
  std::vector<std::unique_ptr<ModelTerm>> terms;
  terms.push_back(std::make_unique<PolynomialStiffness>(std::vector<double>{0.0, kStiffness}));
  terms.push_back(std::make_unique<ViscousDamping>(0.6 * kDamping));
  terms.push_back(std::make_unique<ViscousDamping>(0.4 * kDamping));
  const Model model(kMassKg, std::move(terms));
  const ModelForm three = ModelForm::of_terms(
      model, {{1, {"c_ns_m", 0.1, 3.0}}, {2, {"c_ns_m", 0.1, 3.0}}, {0, {"c1", 500.0, 1100.0}}});
  const EdcDataset data = dataset();
  const FitUncertainty u = fit_uncertainty(EdcObjective(three, data, fixed_floor(0.01)),
                                           Eigen::Vector3d(0.6, 0.4, kStiffness), quick());
  ASSERT_EQ(u.parameters.size(), 3u);
  for (std::size_t i : {std::size_t{0}, std::size_t{1}}) {
    EXPECT_TRUE(std::isinf(u.parameters[i].standard_error));
    EXPECT_TRUE(u.parameters[i].weakly_identified);
    EXPECT_NE(u.parameters[i].note.find("not identifiable"), std::string::npos)
        << u.parameters[i].note;
  }
  const double se_k = std::sqrt(closed_form_covariance(data, 0.01)(1, 1));
  EXPECT_NEAR(u.parameters[2].standard_error, se_k, kDifferenceTol * se_k);
  EXPECT_EQ(u.parameters[2].note.find("not identifiable"), std::string::npos);
}

// A parameter on a search bound is differenced one-sidedly and flagged; its standard error is the
// closed form's to the forward difference's first-order error. With k = 800 N/m on the lower bound
// of [800, 1100] the step is h = 0.3 N/m, and each level's error (h/2)|S''/S'| = 1.5 h/|k − mω²| is
// at most 1.3e-3 relative (|k − mω²| ≥ 338 N/m; measured 5e-4 on the standard error): 2e-3.
TEST(FitUncertainty, ParameterOnABoundIsFlaggedAndDifferencedOneSided) {
  const EdcDataset data = dataset();
  const EdcObjective objective(form(false, kStiffness), data, fixed_floor(0.01));
  const FitUncertainty u =
      fit_uncertainty(objective, Eigen::Vector2d(kDamping, kStiffness), quick());
  const ParameterUncertainty& k = u.parameters[1];
  EXPECT_TRUE(k.at_bound);
  EXPECT_TRUE(k.weakly_identified);
  EXPECT_NE(k.note.find("at a search bound"), std::string::npos) << k.note;
  EXPECT_FALSE(u.parameters[0].at_bound);
  const Eigen::Matrix2d expected = closed_form_covariance(data, 0.01);
  EXPECT_NEAR(k.standard_error, std::sqrt(expected(1, 1)), 2e-3 * std::sqrt(expected(1, 1)));
}

// A relative standard error above 25 % flags a parameter, with the number in the note.
TEST(FitUncertainty, LargeRelativeErrorFlagsTheParameter) {
  const EdcDataset data = dataset();
  const Eigen::Vector2d theta(kDamping, kStiffness);
  for (double rho : {0.01, 1.0}) {
    const FitUncertainty u =
        fit_uncertainty(EdcObjective(form(), data, fixed_floor(rho)), theta, quick());
    const Eigen::Matrix2d expected = closed_form_covariance(data, rho);
    for (int i = 0; i < 2; ++i) {
      const ParameterUncertainty& q = u.parameters[static_cast<std::size_t>(i)];
      const bool weak = std::sqrt(expected(i, i)) / std::abs(theta(i)) > 0.25;
      EXPECT_EQ(q.note.find("relative standard error") != std::string::npos, weak)
          << "rho " << rho << ", " << q.name << ": " << q.note;
    }
  }
}

// Perfect data: every bootstrap replicate's refit starts at its own optimum (χ² = 0 whatever the
// weights), so the replicates scatter by no more than the local polish's tolerance, far below the
// covariance's standard error, and bracket θ̂.
TEST(FitUncertainty, BootstrapOfPerfectDataCollapsesOnTheOptimum) {
  const EdcDataset data = dataset();
  const Eigen::Vector2d theta(kDamping, kStiffness);
  UncertaintyOptions o = quick();
  o.bootstrap_replicates = 6;
  o.bootstrap_polish_evaluations = 40;
  o.seed = 3;
  const FitUncertainty u = fit_uncertainty(EdcObjective(form(), data, fixed_floor(0.01)), theta, o);
  EXPECT_EQ(u.bootstrap_replicates, 6);
  for (const ParameterUncertainty& q : u.parameters) {
    EXPECT_LT(q.bootstrap_std, 1e-3 * q.standard_error) << q.name;
    EXPECT_LE(q.bootstrap_lower_95, q.value + 1e-3 * q.standard_error) << q.name;
    EXPECT_GE(q.bootstrap_upper_95, q.value - 1e-3 * q.standard_error) << q.name;
  }
}

TEST(FitUncertainty, FewerLevelsThanParametersIsNotOk) {
  EdcDataset data;
  MeasuredLevel m;
  m.f0_n = 1.0;
  m.edc_j = edc({5.0, 1.0}, kDamping, kStiffness);
  data.groups.push_back({true, 5.0, {m}});
  const FitUncertainty u = fit_uncertainty(EdcObjective(form(), data, fixed_floor(0.01)),
                                           Eigen::Vector2d(kDamping, kStiffness), quick());
  EXPECT_FALSE(u.ok);
  EXPECT_EQ(u.dof, -1);
  EXPECT_NE(u.message.find("fewer levels than parameters"), std::string::npos) << u.message;
  EXPECT_TRUE(std::isnan(u.t_quantile));
}

}  // namespace
}  // namespace oscilab::analysis
