#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/identification/edc_fit.h"

namespace oscilab::daq {

/// The FIT JSON that `oscilab-cli fit --out` writes and the fit panel exports
/// (docs/contracts.md §3): analysis::fit_report_json of the fit, plus `notes`, how the base model
/// was set up from the records (analysis::campaign_model). Qt-free.
nlohmann::json fit_json(const analysis::FitResult& fit, const analysis::EdcObjective& objective,
                        const std::vector<std::string>& records,
                        const std::vector<std::string>& notes);

/// Writes fit_json (indented by 2) to `path` under a temporary name, renamed into place. Throws
/// InputError naming the file when it cannot be written.
void write_fit_json(const std::string& path, const analysis::FitResult& fit,
                    const analysis::EdcObjective& objective,
                    const std::vector<std::string>& records, const std::vector<std::string>& notes);

}  // namespace oscilab::daq
