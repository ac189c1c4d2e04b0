#include "analysis/model/named_parameter_term.h"

#include <cmath>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {

NamedParameterTerm::NamedParameterTerm(std::string type_name, std::vector<Spec> specs,
                                       std::vector<double> values)
    : type_name_(std::move(type_name)), specs_(std::move(specs)), values_(std::move(values)) {
  for (std::size_t i = 0; i < specs_.size(); ++i) check(i, values_.at(i));
}

void NamedParameterTerm::check(std::size_t index, double value) const {
  const Spec& spec = specs_[index];
  const bool ok = std::isfinite(value) && (spec.positive ? value > 0.0 : value >= 0.0);
  if (!ok) {
    throw InputError(
        type_name_ + ": " + spec.name + ": " + std::to_string(value) +
        (spec.positive ? " must be a finite number > 0" : " must be a finite number >= 0"));
  }
}

std::vector<std::string> NamedParameterTerm::parameter_names() const {
  std::vector<std::string> names;
  for (const Spec& spec : specs_) names.push_back(spec.name);
  return names;
}

double NamedParameterTerm::parameter(const std::string& name) const {
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (specs_[i].name == name) return values_[i];
  }
  throw InputError(type_name_ + ": unknown parameter \"" + name + "\"");
}

void NamedParameterTerm::set_parameter(const std::string& name, double value) {
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    if (specs_[i].name != name) continue;
    check(i, value);
    values_[i] = value;
    return;
  }
  throw InputError(type_name_ + ": unknown parameter \"" + name + "\"");
}

nlohmann::json NamedParameterTerm::to_json() const {
  nlohmann::json out = {{"type", type()}};
  for (std::size_t i = 0; i < specs_.size(); ++i) out[specs_[i].name] = values_[i];
  return out;
}

std::vector<double> NamedParameterTerm::values_from_json(const nlohmann::json& object,
                                                         const std::vector<Spec>& specs,
                                                         const std::string& where) {
  std::vector<double> values;
  for (const Spec& spec : specs) {
    const auto it = object.find(spec.name);
    if (it == object.end()) throw InputError(where + ": missing field \"" + spec.name + "\"");
    if (!it->is_number()) {
      throw InputError(where + "." + spec.name + ": expected a number, got " + it->dump());
    }
    values.push_back(it->get<double>());
  }
  return values;
}

}  // namespace oscilab::analysis
