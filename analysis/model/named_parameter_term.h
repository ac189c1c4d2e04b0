#pragma once

#include <memory>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/model/model_term.h"

namespace oscilab::analysis {

/// Base of the terms whose parameters are a fixed list of named scalars, each non-negative or
/// strictly positive: it implements the parameter access, validation and JSON of ModelTerm once
/// ({"type": type(), <name>: <value>, ...}). Subclasses read their values with value(i).
class NamedParameterTerm : public ModelTerm {
 public:
  struct Spec {
    std::string name;       // unit-suffixed JSON key, e.g. "c2_ns2_m2"
    bool positive = false;  // > 0 required (else ≥ 0)
  };

  std::vector<std::string> parameter_names() const override;
  double parameter(const std::string& name) const override;
  /// Throws InputError naming the term and parameter for an unknown name or a value outside
  /// the domain.
  void set_parameter(const std::string& name, double value) override;
  nlohmann::json to_json() const override;

 protected:
  /// Throws InputError when a value is outside its domain (messages name type() and the key, so
  /// construct with the subclass's type known: `type_name`).
  NamedParameterTerm(std::string type_name, std::vector<Spec> specs, std::vector<double> values);
  double value(std::size_t index) const { return values_[index]; }

  /// Reads the values of `specs` from a term's JSON object and builds the term with make(values);
  /// every InputError (missing field, value outside the domain) names `where`.
  template <typename Make>
  static std::unique_ptr<ModelTerm> from_json_values(const nlohmann::json& object,
                                                     const std::vector<Spec>& specs,
                                                     const std::string& where, Make make) {
    const std::vector<double> values = values_from_json(object, specs, where);
    try {
      return make(values);
    } catch (const InputError& error) {
      throw InputError(where + ": " + error.what());
    }
  }
  static std::vector<double> values_from_json(const nlohmann::json& object,
                                              const std::vector<Spec>& specs,
                                              const std::string& where);

 private:
  void check(std::size_t index, double value) const;

  std::string type_name_;
  std::vector<Spec> specs_;
  std::vector<double> values_;
};

}  // namespace oscilab::analysis
