// EDC identification on noise-free twin data of the paper's model, the issue-6 targets: CMA-ES
// recovers θ in 3 of 4 seeds within 2000 evaluations; the paper's GA runs with its settings.
// Labelled slow: release build only (tests/CMakeLists.txt).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "analysis/identification/edc_fit.h"
#include "analysis/model/reference_models.h"
#include "tests/analysis/identification/twin_data.h"

namespace oscilab::analysis {
namespace {

// Twin data of the paper's model; the truth is Table 3 (ModelForm::paper reads it back).
const EdcObjective& twin_objective() {
  static const EdcObjective objective(ModelForm::paper(paper_model()),
                                      testing::twin_dataset(paper_model()));
  return objective;
}

// Largest relative error over the parameters the issue requires (f_d(z±*), k_s, c, v_t); f_d(0)
// is weakly identified from EDCs and is reported, not required.
double worst_required_error(const FitResult& fit, const Eigen::VectorXd& truth) {
  double worst = 0.0;
  for (int i = 0; i < truth.size(); ++i) {
    if (fit.names[i] == "fd_zero_n") continue;
    worst = std::max(worst, std::abs(fit.theta(i) / truth(i) - 1.0));
  }
  return worst;
}

// Issue 6 target: the stronger method recovers f_d(z±*), k_s, c and v_t within 1 % in at least
// 3 of 4 seeds within 2000 model evaluations (noise-free data: the truth is the exact minimiser,
// so 1 % measures the optimiser alone).
TEST(EdcFitSlow, CmaesRecoversPaperFrictionInThreeOfFourSeeds) {
  const EdcObjective& objective = twin_objective();
  const Eigen::VectorXd truth = objective.form().initial();
  int recovered = 0;
  for (int seed = 1; seed <= 4; ++seed) {
    FitOptions options;
    options.seed = static_cast<std::uint64_t>(seed);
    options.compute_uncertainty = false;
    const FitResult fit = fit_edc(objective, options);
    EXPECT_EQ(fit.status, JobStatus::Ok) << fit.message;
    EXPECT_LE(fit.evaluations, 2000);
    const double worst = worst_required_error(fit, truth);
    std::printf(
        "cmaes seed %d: %ld evaluations, %.2f s, chi2 %.3g, eq. (8) %.3g J, worst %.3f %%\n", seed,
        fit.evaluations, fit.seconds, fit.evaluation.weighted_cost, fit.evaluation.cost_j,
        100.0 * worst);
    if (worst < 0.01) ++recovered;
  }
  EXPECT_GE(recovered, 3);
}

// The paper's GA setting runs and reports its result as it is (issue 6: "even when it is worse").
TEST(EdcFitSlow, PaperGeneticAlgorithmRunsWithPaperSettings) {
  const EdcObjective& objective = twin_objective();
  FitOptions options;
  options.method = FitMethod::Genetic;
  options.compute_uncertainty = false;
  const FitResult fit = fit_edc(objective, options);
  EXPECT_EQ(fit.status, JobStatus::Ok) << fit.message;
  // 100 + 20 × (100 − 5 elite) evaluations.
  EXPECT_EQ(fit.evaluations, 2000);
  // The GA's best must beat a random start by far: the first generation's best is its history's
  // first entry, the final best is ≤ it, and the history is monotone.
  ASSERT_FALSE(fit.history.empty());
  for (std::size_t i = 1; i < fit.history.size(); ++i) {
    EXPECT_LE(fit.history[i].second, fit.history[i - 1].second);
  }
  EXPECT_LT(fit.evaluation.weighted_cost, fit.history.front().second);
  std::printf("paper GA: chi2 %.3g, eq. (8) %.3g J, worst parameter error %.1f %%, %.2f s\n",
              fit.evaluation.weighted_cost, fit.evaluation.cost_j,
              100.0 * worst_required_error(fit, objective.form().initial()), fit.seconds);
}

}  // namespace
}  // namespace oscilab::analysis
