#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "analysis/common/input_error.h"
#include "analysis/common/job.h"
#include "analysis/identification/cmaes_search.h"
#include "analysis/identification/edc_objective.h"
#include "analysis/identification/fit_uncertainty.h"
#include "analysis/identification/genetic_algorithm.h"
#include "analysis/identification/local_polish.h"

namespace oscilab::analysis {

/// How θ̄ of eq. (10) is searched for.
enum class FitMethod {
  Genetic,  // the paper's GA (§5): population 100, 20 generations, 20 % mutation
  Cmaes,    // CMA-ES with restarts, then a BOBYQA polish
  Local,    // BOBYQA from the form's initial θ only (refits from a known neighbourhood)
};
/// "ga", "cmaes", "local"; parse throws InputError for other names.
std::string fit_method_name(FitMethod method);
FitMethod parse_fit_method(const std::string& name);

struct FitOptions {
  FitMethod method = FitMethod::Cmaes;
  GeneticOptions genetic;
  /// CMA-ES: total evaluations of search and polish together (the polish takes
  /// polish_share of it).
  long max_evaluations = 2000;
  double polish_share = 0.2;
  CmaesOptions cmaes;  // max_evaluations and seed are set from the fields here
  /// After the GA too (off by default, so that `--method ga` is the paper's method as it is).
  bool polish_after_genetic = false;
  PolishOptions polish;
  std::uint64_t seed = 1;
  int threads = 0;                 // 0: all hardware threads
  UncertaintyOptions uncertainty;  // seed and threads set from the fields here
  bool compute_uncertainty = true;
  bool check_truncation = true;
};

/// The stages of a fit, in the order they run: the global search (GA or CMA-ES), the local
/// polish (BOBYQA), the uncertainty at the optimum (covariance, bootstrap).
enum class FitStage { Search, Polish, Uncertainty };
/// "search", "polish", "uncertainty": the names progress reports and the Python module use.
const char* to_string(FitStage stage);

/// Progress of a fit: which stage, evaluations so far, the best θ and its χ².
struct FitProgress {
  FitStage stage = FitStage::Search;
  long evaluations = 0;
  double best_weighted_cost = 0.0;
  Eigen::VectorXd best_theta;
};
using FitProgressFn = std::function<void(const FitProgress&)>;

/// The identified model (§5, Table 3) and how it was found.
struct FitResult {
  JobStatus status = JobStatus::Ok;
  std::string message;
  FitMethod method = FitMethod::Cmaes;
  std::vector<std::string> names;
  Eigen::VectorXd theta;                         // θ̄
  EdcEvaluation evaluation;                      // costs, residuals and S^mod at θ̄
  long evaluations = 0;                          // model evaluations of the search and polish
  double seconds = 0.0;                          // wall time of the search and polish
  std::vector<std::pair<long, double>> history;  // best χ² against evaluations (Fig. 14)
  FitUncertainty uncertainty;
  nlohmann::json settings;  // the method's settings as run
  /// Truncation check of the fitted model's harmonic balance: the largest relative change of
  /// S^mod over the levels when H is raised to 2H + 1. When it approaches the model-error floor,
  /// θ̄ partly fits the truncation error (raise the harmonics). 0 harmonics: not computed.
  int check_harmonics = 0;
  double truncation_change_rel = 0.0;
};

/// θ̄ = argmin χ²(θ) over the form's bounds (eq. (10) with the weighted cost of EdcObjective).
/// Populations are evaluated in parallel; the job polls `cancel` between generations and inside
/// every evaluation (an evaluation after cancel returns at once), and returns
/// JobStatus::Cancelled with the best θ so far. Throws InputError for invalid options only.
FitResult fit_edc(const EdcObjective& objective, const FitOptions& options,
                  const FitProgressFn& progress = {}, const CancelToken& cancel = {});

}  // namespace oscilab::analysis
