#include "analysis/identification/edc_fit.h"

#include <algorithm>

#include <chrono>
#include <cmath>
#include <limits>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

// What an evaluation returns after cancellation: finite (the searches sort by it), never best.
constexpr double kCancelledCost = 1e300;

}  // namespace

std::string fit_method_name(FitMethod method) {
  switch (method) {
    case FitMethod::Genetic:
      return "ga";
    case FitMethod::Cmaes:
      return "cmaes";
    case FitMethod::Local:
      return "local";
  }
  return "?";
}

FitMethod parse_fit_method(const std::string& name) {
  if (name == "ga") return FitMethod::Genetic;
  if (name == "cmaes") return FitMethod::Cmaes;
  if (name == "local") return FitMethod::Local;
  throw InputError("--method: unknown method \"" + name + "\" (ga, cmaes or local)");
}

const char* to_string(FitStage stage) {
  switch (stage) {
    case FitStage::Search:
      return "search";
    case FitStage::Polish:
      return "polish";
    case FitStage::Uncertainty:
      return "uncertainty";
  }
  return "unknown";
}

namespace {

// The method's global search (the GA, CMA-ES) or the local start, what it leaves of the budget
// for the BOBYQA polish, and its settings as run.
struct GlobalSearch {
  SearchResult best;
  long polish_budget = 0;
  nlohmann::json settings;
};

GlobalSearch global_search(const ModelForm& form, const UnitCost& cost, const FitOptions& options,
                           const SearchProgressFn& report, const CancelToken& cancel) {
  GlobalSearch out;
  out.best.best_cost = std::numeric_limits<double>::infinity();
  switch (options.method) {
    case FitMethod::Genetic: {
      GeneticOptions ga = options.genetic;
      ga.seed = options.seed;
      ga.threads = options.threads;
      out.best = genetic_algorithm(form.size(), cost, ga, report, cancel);
      out.polish_budget = options.polish_after_genetic ? options.polish.max_evaluations : 0;
      out.settings = {{"population", ga.population},
                      {"generations", ga.generations},
                      {"mutation_rate", ga.mutation_rate},
                      {"crossover_fraction", ga.crossover_fraction},
                      {"elite", ga.elite},
                      {"mutation_sigma_unit", ga.mutation_sigma},
                      {"seed", ga.seed},
                      {"polish", options.polish_after_genetic}};
      break;
    }
    case FitMethod::Cmaes: {
      CmaesOptions cmaes = options.cmaes;
      const auto polish_share = static_cast<long>(options.polish_share * options.max_evaluations);
      cmaes.max_evaluations = options.max_evaluations - polish_share;
      cmaes.seed = options.seed;
      cmaes.threads = options.threads;
      out.best = cmaes_search(form.size(), cost, cmaes, report, cancel);
      // What the global search left of the budget goes to the polish.
      out.polish_budget = options.max_evaluations - out.best.evaluations;
      out.settings = {{"max_evaluations", options.max_evaluations},
                      {"polish_share", options.polish_share},
                      {"sigma0_unit", cmaes.sigma0},
                      {"initial_population", cmaes.initial_population},
                      {"streams", cmaes.streams},
                      {"seed", cmaes.seed},
                      {"polish", "BOBYQA (NLopt)"}};
      break;
    }
    case FitMethod::Local:
      out.best.best_unit = form.to_unit(form.clamp(form.initial()));
      out.polish_budget = options.max_evaluations;
      out.settings = {{"max_evaluations", options.max_evaluations},
                      {"start", "the form's initial values"},
                      {"polish", "BOBYQA (NLopt)"}};
      break;
  }
  return out;
}

// One evaluation of the fitted model at 2H + 1 harmonics (the same levels and branches): the
// model side at θ̄ against 2H' + 1 harmonics without correction (H' the reference of the defect
// correction, else H): what the fitted S_mod still misses, the correction's drift from its
// calibration θ included. Sets check_harmonics and truncation_change_rel.
void check_truncation(const EdcObjective& objective, FitResult& result) {
  EdcCostSettings finer = objective.settings();
  SigmaBudget budget = objective.budget();  // the same σ
  const int base = std::max(budget.harmonics, budget.reference_harmonics);
  budget.harmonics = 2 * base + 1;
  for (auto* v : {&budget.correction_j, &budget.correction_z1_m, &budget.correction_h2,
                  &budget.correction_h3}) {
    std::fill(v->begin(), v->end(), 0.0);
  }
  finer.hbm.harmonics = budget.harmonics;
  finer.hbm.samples = 0;
  finer.max_harmonics = std::max(finer.max_harmonics, budget.harmonics);
  finer.budget = budget;
  const EdcObjective check(objective.form(), objective.data(), finer);
  const EdcEvaluation fine = check.evaluate(result.theta);
  result.check_harmonics = finer.hbm.harmonics;
  result.truncation_change_rel = 0.0;
  for (std::size_t g = 0; g < fine.edc_mod_j.size(); ++g) {
    for (std::size_t i = 0; i < fine.edc_mod_j[g].size(); ++i) {
      const double coarse = result.evaluation.edc_mod_j[g][i];
      result.truncation_change_rel = std::max(
          result.truncation_change_rel, std::abs(fine.edc_mod_j[g][i] - coarse) / std::abs(coarse));
    }
  }
}

}  // namespace

FitResult fit_edc(const EdcObjective& objective, const FitOptions& options,
                  const FitProgressFn& progress, const CancelToken& cancel) {
  if (!(options.polish_share >= 0.0 && options.polish_share < 1.0)) {
    throw InputError("fit: the polish share must lie in [0, 1)");
  }
  const ModelForm& form = objective.form();
  const auto start = std::chrono::steady_clock::now();
  const long evaluations_before = objective.evaluations();
  FitResult result;
  result.method = options.method;
  result.names = form.names();

  const UnitCost cost = [&](const Eigen::VectorXd& u) {
    if (cancel.cancelled()) return kCancelledCost;
    return objective.evaluate(form.from_unit(u)).weighted_cost;
  };
  long spent = 0;
  const auto reporter = [&](FitStage stage) -> SearchProgressFn {
    if (!progress) return {};
    return [&, stage](const SearchProgress& p) {
      progress({stage, spent + p.evaluations, p.best_cost, form.from_unit(p.best_unit)});
    };
  };
  const auto append_history = [&](const SearchResult& s) {
    for (const auto& [evaluations, best] : s.history) {
      const double so_far =
          result.history.empty() ? best : std::min(best, result.history.back().second);
      result.history.emplace_back(spent + evaluations, so_far);
    }
    spent += s.evaluations;
  };

  GlobalSearch search = global_search(form, cost, options, reporter(FitStage::Search), cancel);
  SearchResult& best = search.best;
  result.settings = std::move(search.settings);
  append_history(best);
  if (search.polish_budget > 0 && !cancel.cancelled()) {
    PolishOptions polish = options.polish;
    polish.max_evaluations = search.polish_budget;
    const SearchResult polished =
        local_polish(best.best_unit, cost, polish, reporter(FitStage::Polish), cancel);
    append_history(polished);
    if (polished.best_cost < best.best_cost) {
      best.best_unit = polished.best_unit;
      best.best_cost = polished.best_cost;
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.evaluations = objective.evaluations() - evaluations_before;
  result.theta = form.from_unit(best.best_unit);
  result.evaluation = objective.evaluate(result.theta);

  if (cancel.cancelled()) {
    result.status = JobStatus::Cancelled;
    result.message = "cancelled after " + std::to_string(result.evaluations) + " evaluations";
    return result;
  }
  if (!result.evaluation.ok) {
    result.status = JobStatus::NoConvergence;
    result.message =
        "the best model could not be solved at every level: " + result.evaluation.message;
  }
  if (options.check_truncation) check_truncation(objective, result);
  if (options.compute_uncertainty) {
    if (progress)
      progress({FitStage::Uncertainty, result.evaluations, best.best_cost, result.theta});
    UncertaintyOptions u = options.uncertainty;
    u.seed = options.seed;
    u.threads = options.threads;
    result.uncertainty = fit_uncertainty(objective, result.theta, u, cancel);
    if (cancel.cancelled()) {
      result.status = JobStatus::Cancelled;
      result.message = "cancelled during the uncertainty analysis";
    }
  }
  return result;
}

}  // namespace oscilab::analysis
