#include "analysis/model/polynomial_stiffness.h"

#include <cmath>
#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

// Parameter names: "c0", "c1", ... (c_i in N/m^i).
std::size_t index_of(const std::string& name, std::size_t count) {
  if (name.size() >= 2 && name[0] == 'c') {
    try {
      std::size_t used = 0;
      const unsigned long index = std::stoul(name.substr(1), &used);
      if (used + 1 == name.size() && index < count) return index;
    } catch (const std::exception&) {
    }
  }
  throw InputError("polynomial-stiffness: unknown parameter \"" + name + "\"");
}

}  // namespace

PolynomialStiffness::PolynomialStiffness(std::vector<double> coefficients)
    : coefficients_(std::move(coefficients)) {
  if (coefficients_.empty()) {
    throw InputError("polynomial-stiffness: coefficients: empty list");
  }
  for (std::size_t i = 0; i < coefficients_.size(); ++i) {
    if (!std::isfinite(coefficients_[i])) {
      throw InputError("polynomial-stiffness: coefficients[" + std::to_string(i) +
                       "]: not a finite number");
    }
  }
}

PolynomialStiffness PolynomialStiffness::from_paper(double k3_n_m3, double k2_n_m2, double k1_n_m,
                                                    double k0_n) {
  // Eq. (2): K(z) = k3 z³ + k2 z² − k1 z + k0.
  return PolynomialStiffness({k0_n, -k1_n_m, k2_n_m2, k3_n_m3});
}

double PolynomialStiffness::force(double z_m, double /*z_dot_m_s*/, const double* /*state*/) const {
  double value = 0.0;  // Horner
  for (auto it = coefficients_.rbegin(); it != coefficients_.rend(); ++it)
    value = value * z_m + *it;
  return value;
}

double PolynomialStiffness::stiffness_n_m(double z_m) const {
  double value = 0.0;
  for (std::size_t i = coefficients_.size() - 1; i >= 1; --i) {
    value = value * z_m + static_cast<double>(i) * coefficients_[i];
  }
  return value;
}

TermPartials PolynomialStiffness::partials(double z_m, double /*z_dot_m_s*/,
                                           const double* /*state*/) const {
  return {stiffness_n_m(z_m), 0.0};
}

double PolynomialStiffness::potential_j(double z_m) const {
  double value = 0.0;
  for (std::size_t i = coefficients_.size(); i-- > 0;) {
    value = value * z_m + coefficients_[i] / static_cast<double>(i + 1);
  }
  return value * z_m;
}

std::vector<std::string> PolynomialStiffness::parameter_names() const {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < coefficients_.size(); ++i) names.push_back("c" + std::to_string(i));
  return names;
}

double PolynomialStiffness::parameter(const std::string& name) const {
  return coefficients_[index_of(name, coefficients_.size())];
}

void PolynomialStiffness::set_parameter(const std::string& name, double value) {
  const std::size_t index = index_of(name, coefficients_.size());
  if (!std::isfinite(value)) {
    throw InputError("polynomial-stiffness: " + name + ": not a finite number");
  }
  coefficients_[index] = value;
}

nlohmann::json PolynomialStiffness::to_json() const {
  return {{"type", type()}, {"coefficients", coefficients_}};
}

std::unique_ptr<ModelTerm> PolynomialStiffness::clone() const {
  return std::make_unique<PolynomialStiffness>(*this);
}

}  // namespace oscilab::analysis
