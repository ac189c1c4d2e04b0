#include "app/cli/cost_options.h"

#include <algorithm>

#include "analysis/common/input_error.h"

namespace oscilab::cli {

void add_cost_options(CLI::App* command, CostOptions& options) {
  command
      ->add_option("--harmonics", options.harmonics,
                   "harmonics H of the model's harmonic balance in every evaluation")
      ->capture_default_str();
  command
      ->add_option("--max-harmonics", options.max_harmonics,
                   "largest reference H of the sigma budget's defect correction (15 ... 63)")
      ->capture_default_str();
  command
      ->add_option("--model-error", options.model_error,
                   "fixed relative model-error floor of each level's sigma (no correction); "
                   "negative: the sigma budget (cycles, estimator bias, the model's truncation "
                   "error per level, H corrected to the reference)")
      ->capture_default_str();
}

analysis::EdcCostSettings cost_settings(const CostOptions& options) {
  if (options.harmonics < 1) throw InputError("--harmonics: must be at least 1");
  if (options.max_harmonics < 1) throw InputError("--max-harmonics: must be at least 1");
  analysis::EdcCostSettings cost;
  cost.hbm.harmonics = options.harmonics;
  cost.max_harmonics = std::max(options.max_harmonics, options.harmonics);
  cost.model_error_rel = options.model_error;
  return cost;
}

}  // namespace oscilab::cli
