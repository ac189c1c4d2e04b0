#include "analysis/identification/sigma_budget_report.h"
#include "analysis/edc/well.h"

#include <cstdio>

namespace oscilab::analysis {
namespace {

// Calls f(group, level, k) for every level in group order (k the budget's index).
template <class F>
void for_each_level(const EdcObjective& objective, F&& f) {
  std::size_t k = 0;
  for (const EdcGroup& group : objective.data().groups) {
    for (const MeasuredLevel& level : group.levels) f(group, level, k++);
  }
}

}  // namespace

nlohmann::json sigma_budget_json(const EdcObjective& objective) {
  const SigmaBudget& b = objective.budget();
  nlohmann::json levels = nlohmann::json::array();
  for_each_level(objective, [&](const EdcGroup& group, const MeasuredLevel& level, std::size_t k) {
    levels.push_back({{"well", to_string(well_of(group.positive_well))},
                      {"freq_hz", group.freq_hz},
                      {"f0_n", level.f0_n},
                      {"edc_mes_j", level.edc_j},
                      {"sigma_cycles_j", b.cycles_j[k]},
                      {"sigma_bias_j", b.bias_j[k]},
                      {"sigma_model_j", b.model_j[k]},
                      {"sigma_j", b.total_j[k]},
                      {"correction_j", b.correction_j[k]}});
  });
  const bool fixed = objective.settings().model_error_rel >= 0.0;
  return {
      {"harmonics", b.harmonics},
      {"reference_harmonics", b.reference_harmonics},
      {"model_error",
       fixed ? "fixed floor" : "estimated: |S(H_ref) - S(2 H_ref + 1)|, S(H) corrected to H_ref"},
      {"model_error_floor_rel",
       fixed ? nlohmann::json(objective.settings().model_error_rel) : nlohmann::json(nullptr)},
      {"model_error_target", b.model_error_target},
      {"resolved", b.resolved},
      {"estimator_bias_rel", fixed ? 0.0 : kEdcEstimatorBiasRel},
      {"levels", levels}};
}

std::vector<std::string> sigma_budget_lines(const EdcObjective& objective) {
  const SigmaBudget& b = objective.budget();
  std::vector<std::string> out;
  char line[256];
  if (objective.settings().model_error_rel >= 0.0) {
    std::snprintf(line, sizeof line,
                  "sigma budget: H = %d, fixed model-error floor %.3g of S_mes per level",
                  b.harmonics, objective.settings().model_error_rel);
  } else {
    std::snprintf(line, sizeof line,
                  "sigma budget: H = %d corrected to H = %d (model error = |S(%d) - S(%d)|, "
                  "target %.2g of the measurement sigma: %s), estimator bias %.2g %% of S_mes",
                  b.harmonics, b.reference_harmonics, b.reference_harmonics,
                  2 * b.reference_harmonics + 1, b.model_error_target,
                  b.resolved ? "met at every level" : "NOT met at every level",
                  100.0 * kEdcEstimatorBiasRel);
  }
  out.emplace_back(line);
  std::snprintf(line, sizeof line, "  %-8s %8s %12s %12s %12s %12s %12s %12s", "well", "f0 [N]",
                "S_mes [J]", "cycles [J]", "bias [J]", "model [J]", "sigma [J]", "corr. [J]");
  out.emplace_back(line);
  for_each_level(objective, [&](const EdcGroup& group, const MeasuredLevel& level, std::size_t k) {
    std::snprintf(line, sizeof line, "  %-8s %8.4g %12.5g %12.3g %12.3g %12.3g %12.3g %12.3g",
                  to_string(well_of(group.positive_well)).c_str(), level.f0_n, level.edc_j,
                  b.cycles_j[k], b.bias_j[k], b.model_j[k], b.total_j[k], b.correction_j[k]);
    out.emplace_back(line);
  });
  return out;
}

}  // namespace oscilab::analysis
