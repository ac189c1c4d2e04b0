#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/model/model_term.h"

namespace oscilab::analysis {

/// A static equilibrium z* of the model at rest (K(z*) = 0) and its linearised motion.
struct Equilibrium {
  double z_m = 0.0;
  double stiffness_n_m = 0.0;        // U''(z*) = dK/dz at z*
  bool stable = false;               // U'' > 0: a well
  double linear_frequency_hz = 0.0;  // eq. (4): √(U''/m) / 2π; 0 when unstable
};

/// Single-degree-of-freedom model of eq. (1): m z̈ + Σ_i F_i(z, ż, s_i) = f(t), a mass and a list
/// of named terms. Copyable (terms are cloned). Internal states of all terms are concatenated in
/// term order; state_offset(i) tells where term i's start.
///
/// Thread-safety: const methods are safe to call concurrently.
class Model {
 public:
  /// Throws InputError when the mass is not positive or there are no terms.
  Model(double mass_kg, std::vector<std::unique_ptr<ModelTerm>> terms, std::string name = "");
  Model(const Model& other);
  Model& operator=(const Model& other);
  Model(Model&&) noexcept = default;
  Model& operator=(Model&&) noexcept = default;
  ~Model() = default;

  const std::string& name() const { return name_; }
  double mass_kg() const { return mass_kg_; }
  const std::vector<std::unique_ptr<ModelTerm>>& terms() const { return terms_; }
  /// A term to change in place. A change of a parameter that gives a term a state or takes it
  /// away (a friction's presliding length) must go through set_parameter(), which re-indexes the
  /// states.
  ModelTerm& term(std::size_t index) { return *terms_.at(index); }
  /// Sets a term's named parameter (ModelTerm::set_parameter) and re-indexes the states.
  void set_parameter(std::size_t term_index, const std::string& name, double value);
  void add_term(std::unique_ptr<ModelTerm> term);

  int state_size() const { return state_size_; }
  int state_offset(std::size_t term_index) const { return state_offsets_.at(term_index); }
  /// Internal states at rest at position z.
  std::vector<double> initial_state(double z_m) const;

  /// R(z, ż, s) = Σ F_i: the restoring surface of eq. (1), in N.
  double restoring_force(double z_m, double z_dot_m_s, const double* state) const;
  /// The elastic part K and the dissipative part D of R = K + D.
  double elastic_force(double z_m) const;
  double dissipative_force(double z_m, double z_dot_m_s, const double* state) const;
  TermPartials partials(double z_m, double z_dot_m_s, const double* state) const;
  void state_rate(double z_m, double z_dot_m_s, const double* state, double* rate) const;
  /// U(z) of eq. (3): sum of the elastic terms' potentials, in J.
  double potential_j(double z_m) const;

  /// The equilibria K(z*) = 0 in increasing z, from the real roots of the elastic polynomial.
  /// Throws InputError when an elastic term is not a polynomial.
  std::vector<Equilibrium> equilibria() const;
  /// The stable equilibrium of the positive (z₊*) or negative (z₋*) well; with a single well,
  /// that one. Throws InputError when the model has no such well.
  Equilibrium well(bool positive) const;

  /// {"format": "oscilab-model/1", "name", "mass_kg", "terms": [...]}.
  nlohmann::json to_json() const;

 private:
  void index_states();

  std::string name_;
  double mass_kg_;
  std::vector<std::unique_ptr<ModelTerm>> terms_;
  std::vector<int> state_offsets_;
  int state_size_ = 0;
};

}  // namespace oscilab::analysis
