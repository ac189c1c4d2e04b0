#include "analysis/model/model_json.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"
#include "analysis/model/coulomb_friction.h"
#include "analysis/model/dahl_friction.h"
#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/position_dependent_friction.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/velocity_power_damping.h"
#include "analysis/model/viscous_damping.h"

namespace oscilab::analysis {
namespace {

using nlohmann::json;

double number_field(const json& object, const std::string& key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) throw InputError(where + ": missing field \"" + key + "\"");
  if (!it->is_number()) {
    throw InputError(where + "." + key + ": expected a number, got " + it->dump());
  }
  return it->get<double>();
}

// Terms report their own domain errors ("viscous-damping: c_ns_m: ..."); prefix the place.
template <typename Make>
std::unique_ptr<ModelTerm> build(const std::string& where, Make make) {
  try {
    return make();
  } catch (const InputError& error) {
    throw InputError(where + ": " + error.what());
  }
}

}  // namespace

std::unique_ptr<ModelTerm> term_from_json(const json& object, const std::string& where) {
  if (!object.is_object()) throw InputError(where + ": expected an object, got " + object.dump());
  const auto type_it = object.find("type");
  if (type_it == object.end() || !type_it->is_string()) {
    throw InputError(where + ": missing string field \"type\"");
  }
  const std::string type = type_it->get<std::string>();
  if (type == "polynomial-stiffness") {
    const auto it = object.find("coefficients");
    if (it == object.end() || !it->is_array()) {
      throw InputError(where + ": missing array field \"coefficients\"");
    }
    std::vector<double> coefficients;
    for (std::size_t i = 0; i < it->size(); ++i) {
      if (!(*it)[i].is_number()) {
        throw InputError(where + ".coefficients[" + std::to_string(i) + "]: expected a number");
      }
      coefficients.push_back((*it)[i].get<double>());
    }
    return build(where, [&] { return std::make_unique<PolynomialStiffness>(coefficients); });
  }
  if (type == "position-dependent-friction") {
    PositionDependentFriction::Parameters p;
    p.alpha_n_m2 = number_field(object, "alpha_n_m2", where);
    p.beta_n_m = number_field(object, "beta_n_m", where);
    p.gamma_n = number_field(object, "gamma_n", where);
    p.ks = number_field(object, "ks", where);
    p.vt_m_s = number_field(object, "vt_m_s", where);
    // Optional: the presliding regime's length δ (absent: the sliding law of eq. (5)).
    if (object.contains("presliding_length_m")) {
      p.presliding_length_m = number_field(object, "presliding_length_m", where);
    }
    return build(where, [&] { return std::make_unique<PositionDependentFriction>(p); });
  }
  if (type == "viscous-damping") {
    const double c = number_field(object, "c_ns_m", where);
    return build(where, [&] { return std::make_unique<ViscousDamping>(c); });
  }
  if (type == "quadratic-damping" || type == "cubic-damping") {
    const int power = type == "quadratic-damping" ? 2 : 3;
    return VelocityPowerDamping::from_json(power, object, where);
  }
  if (type == "coulomb-friction") {
    return CoulombFriction::from_json(object, where);
  }
  if (type == "stribeck-friction") {
    return StribeckFriction::from_json(object, where);
  }
  if (type == "presliding-hysteresis") {
    return DahlFriction::from_json(object, where);
  }
  throw InputError(where + ".type: unknown term type \"" + type + "\"");
}

Model model_from_json(const json& object, const std::string& where) {
  if (!object.is_object()) throw InputError(where + ": expected a JSON object");
  if (const auto it = object.find("format"); it != object.end()) {
    if (!it->is_string() || it->get<std::string>() != "oscilab-model/1") {
      throw InputError(where + ": format: expected \"oscilab-model/1\", got " + it->dump());
    }
  }
  const double mass_kg = number_field(object, "mass_kg", where);
  const auto terms_it = object.find("terms");
  if (terms_it == object.end() || !terms_it->is_array()) {
    throw InputError(where + ": missing array field \"terms\"");
  }
  std::vector<std::unique_ptr<ModelTerm>> terms;
  for (std::size_t i = 0; i < terms_it->size(); ++i) {
    terms.push_back(term_from_json((*terms_it)[i], where + ": terms[" + std::to_string(i) + "]"));
  }
  std::string name;
  if (const auto it = object.find("name"); it != object.end() && it->is_string()) {
    name = it->get<std::string>();
  }
  try {
    return Model(mass_kg, std::move(terms), name);
  } catch (const InputError& error) {
    throw InputError(where + ": " + error.what());
  }
}

Model load_model(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open model file");
  // A model is a few kilobytes: a file over the JSON limit is refused before it is read.
  std::error_code error;
  if (const std::uintmax_t size = std::filesystem::file_size(path, error);
      !error && size > kMaxJsonTextBytes) {
    throw InputError(path + ": " + std::to_string(size) + " bytes of JSON exceed the limit of " +
                     std::to_string(kMaxJsonTextBytes));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read model file");
  return model_from_json(parse_json_within_limits(text.str(), path), path);
}

void save_model(const Model& model, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write model file");
  out << model.to_json().dump(2) << '\n';
  if (!out) throw InputError(path + ": write failed");
}

}  // namespace oscilab::analysis

namespace oscilab::analysis {

Model model_from_spec(const std::string& spec) {
  if (spec == "paper") return paper_model();
  if (spec == "illustrative") return illustrative_model();
  return load_model(spec);
}

nlohmann::json model_summary(const Model& model) {
  nlohmann::json equilibria = nlohmann::json::array();
  for (const Equilibrium& e : model.equilibria()) {
    equilibria.push_back({{"z_m", e.z_m},
                          {"stable", e.stable},
                          {"stiffness_n_m", e.stiffness_n_m},
                          {"linear_frequency_hz", e.stable ? nlohmann::json(e.linear_frequency_hz)
                                                           : nlohmann::json(nullptr)}});
  }
  return {{"name", model.name()},
          {"mass_kg", model.mass_kg()},
          {"equilibria", equilibria},
          {"terms", model.to_json()["terms"]}};
}

}  // namespace oscilab::analysis
