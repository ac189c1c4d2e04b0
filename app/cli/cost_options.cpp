#include "app/cli/cost_options.h"

#include "analysis/identification/fit_setup.h"

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
  return analysis::cost_settings(options.harmonics, options.max_harmonics, options.model_error,
                                 "--harmonics", "--max-harmonics");
}

}  // namespace oscilab::cli
