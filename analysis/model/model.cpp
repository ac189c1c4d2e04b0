#include "analysis/model/model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "analysis/common/input_error.h"
#include "analysis/model/polynomial_stiffness.h"

namespace oscilab::analysis {

Model::Model(double mass_kg, std::vector<std::unique_ptr<ModelTerm>> terms, std::string name)
    : name_(std::move(name)), mass_kg_(mass_kg), terms_(std::move(terms)) {
  if (!std::isfinite(mass_kg_) || mass_kg_ <= 0.0) {
    throw InputError("model: mass_kg: " + std::to_string(mass_kg_) + " must be positive");
  }
  if (terms_.empty()) throw InputError("model: terms: a model needs at least one term");
  for (const auto& term : terms_) {
    if (!term) throw InputError("model: terms: null term");
  }
  index_states();
}

Model::Model(const Model& other) : name_(other.name_), mass_kg_(other.mass_kg_) {
  for (const auto& term : other.terms_) terms_.push_back(term->clone());
  index_states();
}

Model& Model::operator=(const Model& other) {
  if (this != &other) *this = Model(other);
  return *this;
}

void Model::add_term(std::unique_ptr<ModelTerm> term) {
  if (!term) throw InputError("model: terms: null term");
  terms_.push_back(std::move(term));
  index_states();
}

void Model::set_parameter(std::size_t term_index, const std::string& name, double value) {
  terms_.at(term_index)->set_parameter(name, value);
  index_states();
}

void Model::index_states() {
  state_offsets_.clear();
  state_size_ = 0;
  for (const auto& term : terms_) {
    state_offsets_.push_back(state_size_);
    state_size_ += term->state_size();
  }
}

std::vector<double> Model::initial_state(double z_m) const {
  std::vector<double> state(static_cast<std::size_t>(state_size_), 0.0);
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    if (terms_[i]->state_size() > 0)
      terms_[i]->initial_state(z_m, state.data() + state_offsets_[i]);
  }
  return state;
}

double Model::restoring_force(double z_m, double z_dot_m_s, const double* state) const {
  double force = 0.0;
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    force += terms_[i]->force(z_m, z_dot_m_s, state ? state + state_offsets_[i] : nullptr);
  }
  return force;
}

double Model::elastic_force(double z_m) const {
  double force = 0.0;
  for (const auto& term : terms_) {
    if (term->kind() == TermKind::Elastic) force += term->force(z_m, 0.0, nullptr);
  }
  return force;
}

double Model::dissipative_force(double z_m, double z_dot_m_s, const double* state) const {
  double force = 0.0;
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    if (terms_[i]->kind() == TermKind::Dissipative) {
      force += terms_[i]->force(z_m, z_dot_m_s, state ? state + state_offsets_[i] : nullptr);
    }
  }
  return force;
}

TermPartials Model::partials(double z_m, double z_dot_m_s, const double* state) const {
  TermPartials sum;
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    const TermPartials p =
        terms_[i]->partials(z_m, z_dot_m_s, state ? state + state_offsets_[i] : nullptr);
    sum.d_dz += p.d_dz;
    sum.d_dz_dot += p.d_dz_dot;
  }
  return sum;
}

void Model::state_rate(double z_m, double z_dot_m_s, const double* state, double* rate) const {
  for (std::size_t i = 0; i < terms_.size(); ++i) {
    if (terms_[i]->state_size() > 0) {
      terms_[i]->state_rate(z_m, z_dot_m_s, state + state_offsets_[i], rate + state_offsets_[i]);
    }
  }
}

double Model::potential_j(double z_m) const {
  double energy = 0.0;
  for (const auto& term : terms_) energy += term->potential_j(z_m);
  return energy;
}

std::vector<Equilibrium> Model::equilibria() const {
  // Sum the elastic polynomials, then take the real roots as the eigenvalues of the companion
  // matrix of the monic polynomial (Golub & Van Loan, "Matrix Computations", §7.4.6).
  std::vector<double> coefficients;
  for (const auto& term : terms_) {
    if (term->kind() != TermKind::Elastic) continue;
    const auto* polynomial = dynamic_cast<const PolynomialStiffness*>(term.get());
    if (!polynomial) {
      throw InputError("model: equilibria: elastic term \"" + term->type() +
                       "\" is not a polynomial");
    }
    const auto& c = polynomial->coefficients();
    if (c.size() > coefficients.size()) coefficients.resize(c.size(), 0.0);
    for (std::size_t i = 0; i < c.size(); ++i) coefficients[i] += c[i];
  }
  while (!coefficients.empty() && coefficients.back() == 0.0) coefficients.pop_back();
  if (coefficients.size() < 2) {
    throw InputError("model: equilibria: the elastic force is constant, there is no equilibrium");
  }
  const PolynomialStiffness total(coefficients);
  const int degree = static_cast<int>(coefficients.size()) - 1;
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  for (int i = 0; i < degree; ++i)
    companion(0, i) = -coefficients[degree - 1 - i] / coefficients[degree];
  for (int i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
  const Eigen::VectorXcd roots = companion.eigenvalues();

  // Scale for "real": a root whose imaginary part is negligible against the root spread.
  double scale = 0.0;
  for (const auto& r : roots) scale = std::max(scale, std::abs(r));
  std::vector<double> real_roots;
  for (const auto& r : roots) {
    if (std::abs(r.imag()) <= 1e-9 * std::max(scale, 1e-300)) {
      // Polish with Newton on the original polynomial: the eigenvalue is accurate to about
      // machine precision times the condition of the root; two steps bring it to full precision.
      double z = r.real();
      for (int k = 0; k < 3; ++k) {
        const double slope = total.stiffness_n_m(z);
        if (slope == 0.0) break;
        z -= total.force(z, 0.0, nullptr) / slope;
      }
      real_roots.push_back(z);
    }
  }
  std::sort(real_roots.begin(), real_roots.end());

  std::vector<Equilibrium> result;
  for (double z : real_roots) {
    Equilibrium e;
    e.z_m = z;
    e.stiffness_n_m = total.stiffness_n_m(z);
    e.stable = e.stiffness_n_m > 0.0;
    // Eq. (4): ω = √(U''(z*)/m).
    e.linear_frequency_hz =
        e.stable ? std::sqrt(e.stiffness_n_m / mass_kg_) / (2.0 * std::numbers::pi) : 0.0;
    result.push_back(e);
  }
  return result;
}

Equilibrium Model::well(bool positive) const {
  std::vector<Equilibrium> stable;
  for (const auto& e : equilibria()) {
    if (e.stable) stable.push_back(e);
  }
  if (stable.empty()) throw InputError("model: the model has no stable equilibrium");
  if (stable.size() == 1) return stable.front();
  return positive ? stable.back() : stable.front();
}

nlohmann::json Model::to_json() const {
  nlohmann::json terms = nlohmann::json::array();
  for (const auto& term : terms_) terms.push_back(term->to_json());
  return {{"format", "oscilab-model/1"}, {"name", name_}, {"mass_kg", mass_kg_}, {"terms", terms}};
}

}  // namespace oscilab::analysis
