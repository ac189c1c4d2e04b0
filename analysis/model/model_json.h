#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "analysis/model/model.h"

namespace oscilab::analysis {

/// Reads one term from its JSON object. `where` names the place for error messages, e.g.
/// `model.json: terms[2]`. Throws InputError naming the field and value on bad input.
std::unique_ptr<ModelTerm> term_from_json(const nlohmann::json& json, const std::string& where);

/// Reads a whole model (Model::to_json() format). Throws InputError naming `where` and the field.
Model model_from_json(const nlohmann::json& json, const std::string& where);

/// Reads a model file; messages name the file.
Model load_model(const std::string& path);
/// Writes a model file (pretty JSON). Throws InputError when the file cannot be written.
void save_model(const Model& model, const std::string& path);

}  // namespace oscilab::analysis

namespace oscilab::analysis {

/// A model named on a command line: "paper" (eq. (7), Tables 1 and 3), "illustrative" (eq. (14),
/// Table 2), or the path of a model JSON file.
Model model_from_spec(const std::string& spec);

/// {"name", "mass_kg", "equilibria": [{"z_m", "stable", "linear_frequency_hz"}], "terms"}: the
/// model summary of docs/contracts.md §3, with linear_frequency_hz null at an unstable equilibrium.
nlohmann::json model_summary(const Model& model);

}  // namespace oscilab::analysis
