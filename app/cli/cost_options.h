#pragma once

#include <CLI/CLI.hpp>

#include "analysis/identification/edc_objective.h"

namespace oscilab::cli {

/// The options of how a fit weighs the levels, shared by `fit` and `diagnose`: the model side's
/// harmonics, the reference of its defect correction, and the σ budget or a fixed floor.
struct CostOptions {
  int harmonics = 7;
  int max_harmonics = 63;
  double model_error = -1.0;  // negative: the σ budget
};

void add_cost_options(CLI::App* command, CostOptions& options);

/// The settings they describe; throws InputError naming the option for a bad value.
analysis::EdcCostSettings cost_settings(const CostOptions& options);

}  // namespace oscilab::cli
