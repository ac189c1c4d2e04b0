#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/identification/edc_objective.h"

namespace oscilab::analysis {

/// The σ budget of an objective as JSON: {"harmonics", "reference_harmonics",
/// "model_error_target", "resolved", "estimator_bias_rel", "levels": [{"well", "f0_n",
/// "edc_mes_j", "sigma_cycles_j", "sigma_bias_j", "sigma_model_j", "sigma_j"}]}.
nlohmann::json sigma_budget_json(const EdcObjective& objective);

/// The same as text lines for a terminal: a heading and one line per level.
std::vector<std::string> sigma_budget_lines(const EdcObjective& objective);

}  // namespace oscilab::analysis
