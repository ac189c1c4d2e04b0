// Speed of the EDC identification: a 2000-evaluation fit of the paper's θ (both wells,
// 52 levels, H = 7) by CMA-ES + polish and by the paper's GA (target ≤ 10 s wall on the 2-core
// machine for either), on all hardware threads; and how long a running fit takes to stop after
// cancel() (target ≤ 200 ms). Noise-free twin data of the paper's model. Google Benchmark
// reports medians over repetitions; nothing here asserts a speed.
#include <chrono>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>

#include "analysis/hbm/level_response.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/model/dahl_friction.h"
#include "analysis/model/reference_models.h"
#include "tests/analysis/identification/twin_data.h"

namespace {

using namespace oscilab::analysis;

const EdcObjective& objective() {
  static const EdcObjective o(ModelForm::paper(paper_model()), testing::twin_dataset(paper_model()),
                              testing::twin_settings());
  return o;
}

// One fit cost evaluation (52 levels, both wells, level_response per well) at fixed H on one
// thread: what every optimiser step pays. Range: H; second range 1 adds presliding hysteresis
// (Dahl, F_c 0.06 N, presliding length 20 µm) to the model, whose periodic state is solved
// exactly in each AFT step.
void BM_CostEvaluation(benchmark::State& state) {
  const int harmonics = static_cast<int>(state.range(0));
  const bool dahl = state.range(1) != 0;
  Model truth = paper_model();
  if (dahl) truth.add_term(std::make_unique<DahlFriction>(0.06, 3e3));
  EdcCostSettings cost;
  cost.hbm.harmonics = harmonics;
  cost.adaptive_harmonics = false;
  const EdcObjective o(ModelForm::paper(truth), testing::twin_dataset(paper_model()), cost);
  const Eigen::VectorXd theta = o.form().initial();
  double chi2 = 0.0;
  for (auto _ : state) chi2 = o.evaluate(theta).weighted_cost;
  long newton = 0;
  for (const EdcGroup& g : o.data().groups) {
    std::vector<double> f0;
    for (const MeasuredLevel& l : g.levels) f0.push_back(l.f0_n);
    newton += level_response(o.form().build(theta), g.freq_hz, g.positive_well, f0, cost.hbm)
                  .newton_iterations;
  }
  state.counters["newton_iterations"] = static_cast<double>(newton);
  state.counters["H"] = harmonics;
  state.counters["chi2"] = chi2;
  state.SetLabel(dahl ? "paper + presliding hysteresis" : "paper");
}
BENCHMARK(BM_CostEvaluation)
    ->ArgsProduct({{7, 11, 15, 23, 31}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// The same evaluation with the paper's friction in its presliding regime (presliding length δ in
// µm: range 0; 0 the sliding law): a stuck contact rings at √(f_d/(δ m)), and the levels near the
// stick–slip transition that H = 7 cannot reach are solved with the ringing resolved
// (level_response), the other levels at H = 7.
// The paper's form with its friction in the presliding regime of length `length_um` (0: the
// sliding law) on the paper model's twin data, at H = 7 (raised where the contact rings).
EdcObjective presliding_regime_objective(double length_um) {
  Model truth = paper_model();
  if (length_um > 0.0) truth.set_parameter(1, "presliding_length_m", 1e-6 * length_um);
  EdcCostSettings cost;
  cost.hbm.harmonics = 7;
  cost.adaptive_harmonics = false;
  return EdcObjective(ModelForm::paper(truth), testing::twin_dataset(paper_model()), cost);
}

void BM_CostEvaluationPreslidingRegime(benchmark::State& state) {
  const double length_m = 1e-6 * static_cast<double>(state.range(0));
  const EdcObjective o = presliding_regime_objective(static_cast<double>(state.range(0)));
  const EdcCostSettings& cost = o.settings();
  const Eigen::VectorXd theta = o.form().initial();
  double chi2 = 0.0;
  for (auto _ : state) chi2 = o.evaluate(theta).weighted_cost;
  int largest_h = 0;
  for (const EdcGroup& g : o.data().groups) {
    std::vector<double> f0;
    for (const MeasuredLevel& l : g.levels) f0.push_back(l.f0_n);
    largest_h = std::max(
        largest_h,
        level_response(o.form().build(theta), g.freq_hz, g.positive_well, f0, cost.hbm).harmonics);
  }
  state.counters["largest_H"] = largest_h;
  state.counters["chi2"] = chi2;
  state.SetLabel(length_m > 0.0 ? "paper, friction in its presliding regime" : "paper");
}
BENCHMARK(BM_CostEvaluationPreslidingRegime)
    ->Arg(0)
    ->Arg(1)
    ->Arg(3)
    ->Arg(30)
    ->Unit(benchmark::kMillisecond);

// One finite-difference Jacobian of the residuals as a Levenberg–Marquardt refit takes it (θ and
// one shifted θ per parameter), the friction in its presliding regime at δ µm (range 0; 0 the
// sliding law): range 1 = 0 solves every shifted θ again (the reference), 1 takes the shifted
// evaluations by one Newton step per level from θ's solutions (EdcObjective::evaluate_nearby).
void BM_ResidualJacobianPreslidingRegime(benchmark::State& state) {
  const bool nearby_steps = state.range(1) == 1;
  const EdcObjective o = presliding_regime_objective(static_cast<double>(state.range(0)));
  const Eigen::VectorXd theta = o.form().initial();
  std::vector<Eigen::VectorXd> shifted;
  for (int j = 0; j < theta.size(); ++j) {
    shifted.push_back(theta);
    shifted.back()[j] *= 1.0 + 1e-6;
  }
  double column_sum = 0.0;
  for (auto _ : state) {
    EdcEvaluation at;
    std::vector<EdcEvaluation> around;
    if (!nearby_steps || !o.evaluate_nearby(theta, shifted, at, around)) {
      if (nearby_steps) state.SkipWithError("evaluate_nearby refused");
      at = o.evaluate(theta);
      around.clear();
      for (const Eigen::VectorXd& t : shifted) around.push_back(o.evaluate(t));
    }
    column_sum = 0.0;
    for (const EdcEvaluation& e : around) column_sum += (e.residuals - at.residuals).norm();
    benchmark::DoNotOptimize(column_sum);
  }
  state.counters["parameters"] = static_cast<double>(theta.size());
  state.SetLabel(nearby_steps ? "nearby Newton steps" : "every shifted theta solved");
}
BENCHMARK(BM_ResidualJacobianPreslidingRegime)
    ->ArgsProduct({{0, 1, 3, 30}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

void BM_Fit2000Evaluations(benchmark::State& state) {
  const auto method = static_cast<FitMethod>(state.range(0));
  FitOptions options;
  options.method = method;
  options.compute_uncertainty = false;
  options.check_truncation = false;
  long evaluations = 0;
  double cost = 0.0;
  for (auto _ : state) {
    const FitResult fit = fit_edc(objective(), options);
    evaluations = fit.evaluations;
    cost = fit.evaluation.weighted_cost;
  }
  state.counters["evaluations"] = static_cast<double>(evaluations);
  state.counters["chi2"] = cost;
  state.counters["threads"] = static_cast<double>(std::thread::hardware_concurrency());
  state.SetLabel(fit_method_name(method) + ", both wells, 52 levels, H = 7");
}
BENCHMARK(BM_Fit2000Evaluations)
    ->Arg(static_cast<int>(FitMethod::Cmaes))
    ->Arg(static_cast<int>(FitMethod::Genetic))
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

// A whole fit at the accuracy the σ budget asks for: the objective's calibration (the reference
// ladder up to H = 63 and its check at 2H + 1) and a 2000-evaluation CMA-ES + polish at H = 7 with
// the defect correction, on all hardware threads. Data: the paper's model by harmonic balance at
// H = 40 (off the ladder), no cycles, so σ is the estimator bias alone: the strictest budget.
void BM_FitWithSigmaBudget(benchmark::State& state) {
  HbmOptions converged;
  converged.harmonics = 40;
  const EdcDataset data = testing::twin_dataset(paper_model(), converged);
  FitOptions options;
  options.compute_uncertainty = false;
  double chi2 = 0.0, per_evaluation_ms = 0.0;
  int reference = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const EdcObjective objective(ModelForm::paper(paper_model()), data);
    const FitResult fit = fit_edc(objective, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    chi2 = fit.evaluation.weighted_cost;
    reference = objective.budget().reference_harmonics;
    per_evaluation_ms = 1e3 * fit.seconds / static_cast<double>(fit.evaluations);
    state.counters["whole_fit_s"] = seconds;
  }
  state.counters["chi2"] = chi2;
  state.counters["reference_H"] = reference;
  state.counters["wall_ms_per_evaluation"] = per_evaluation_ms;
  state.SetLabel("calibration + CMA-ES 2000 evaluations, H = 7 corrected, both wells");
}
BENCHMARK(BM_FitWithSigmaBudget)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// Time from cancel() to fit_edc's return, 300 ms into a CMA-ES fit (manual time: the latency).
void BM_FitCancelLatency(benchmark::State& state) {
  FitOptions options;
  options.compute_uncertainty = false;
  for (auto _ : state) {
    oscilab::CancelToken cancel;
    std::chrono::steady_clock::time_point cancelled_at;
    std::thread canceller([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      cancelled_at = std::chrono::steady_clock::now();
      cancel.cancel();
    });
    const FitResult fit = fit_edc(objective(), options, {}, cancel);
    const auto returned_at = std::chrono::steady_clock::now();
    canceller.join();
    benchmark::DoNotOptimize(fit.theta.data());
    state.SetIterationTime(std::chrono::duration<double>(returned_at - cancelled_at).count());
  }
  state.SetLabel("cancel 300 ms into a CMA-ES fit");
}
BENCHMARK(BM_FitCancelLatency)->Unit(benchmark::kMillisecond)->Iterations(5)->UseManualTime();

}  // namespace

BENCHMARK_MAIN();
