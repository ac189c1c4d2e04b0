#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "analysis/model/model.h"

namespace oscilab::analysis {

/// One free parameter of a fit: its name (unit-suffixed, e.g. `c_ns_m`), its search bounds and
/// whether it is searched in log space (a transition velocity spans decades).
struct FreeParameter {
  std::string name;
  double lower = 0.0;
  double upper = 1.0;
  bool log_scale = false;
};

/// A model with free parameters: the map θ → Model that an identification searches over.
///
/// The paper's form (§4, eq. (9)) is θ = [f_d(z₋*), f_d(0), f_d(z₊*), k_s, c, v_t] on eq. (7) with
/// the stiffness and mass of a base model: the three friction values set α, β, γ of eq. (6) by the
/// parabola through (z₋*, f_d(z₋*)), (0, f_d(0)), (z₊*, f_d(z₊*)) at the base model's own
/// equilibria. A diagnosis adds terms with their own free parameters (add_term), and a fit then
/// searches all of them together.
///
/// The optimisers work in the unit cube: u = (θ − lower) / (upper − lower), or the same of log θ
/// for log-scale parameters (to_unit / from_unit).
///
/// Thread-safety: const methods are safe to call concurrently.
class ModelForm {
 public:
  /// The paper's θ of eq. (9) over `base`, which must hold one position-dependent-friction term
  /// and one viscous-damping term (their current values are the initial θ) and two wells. Throws
  /// InputError otherwise.
  static ModelForm paper(const Model& base);

  /// A form whose free parameters are the named parameters of the model's terms, each bound as
  /// `term_index`/`parameter name`. Throws InputError for an unknown term or name.
  struct TermParameter {
    std::size_t term_index = 0;
    FreeParameter parameter;  // name: the term's parameter name
  };
  static ModelForm of_terms(const Model& base, std::vector<TermParameter> parameters);

  /// Adds a term to the model and makes some of its parameters free (names as the term's
  /// parameter_names()); bounds must contain the term's current values, which join the initial θ.
  void add_term(std::unique_ptr<ModelTerm> term, std::vector<FreeParameter> free);
  /// Changes a law the model already holds instead of adding one: the first term of `type` gets
  /// `free` parameters (names as its parameter_names()) set to `initial` (inside the bounds),
  /// e.g. a friction's presliding length. Throws InputError when the model has no such term.
  void change_term(const std::string& type, std::vector<FreeParameter> free,
                   const std::vector<double>& initial);

  /// Makes the coefficients of the model's polynomial stiffness K(z) free parameters, named
  /// `stiffness_c<i>_n_m<i>` (N/mⁱ, K = Σ cᵢ zⁱ), each bounded to ±`relative` of the larger of
  /// its value and 5 % of the largest term's force at the wells' largest |z|, starting from the
  /// model's values: the stiffness identified from the data rather than given. Throws
  /// InputError when the model has no polynomial-stiffness term or its K is already free.
  void free_stiffness(double relative = 0.3);
  /// Whether parameter i is one of free_stiffness()'s, and whether the form has any.
  bool is_stiffness(int i) const;
  bool identifies_stiffness() const;
  /// Whether the form frees the power zᵖ of its (first) polynomial stiffness.
  bool frees_stiffness_power(int power) const;
  /// The form with its stiffness parameters held at `theta`'s values (the others free, in their
  /// order); expand() maps a θ of that form back to this one's with the held values.
  ModelForm holding_stiffness(const Eigen::VectorXd& theta) const;
  Eigen::VectorXd expand(const Eigen::VectorXd& held_theta, const Eigen::VectorXd& theta) const;

  int size() const { return static_cast<int>(parameters_.size()); }
  const std::vector<FreeParameter>& parameters() const { return parameters_; }
  std::vector<std::string> names() const;
  /// θ with each value's parameter name, in θ's order.
  std::vector<std::pair<std::string, double>> named(const Eigen::VectorXd& theta) const;
  const Model& base() const { return base_; }
  /// "paper" or "terms"; a diagnosis appends the effects it adds.
  const std::string& description() const { return description_; }

  /// The model at θ; throws InputError when θ leaves a term's domain (e.g. k_s < 1).
  Model build(const Eigen::VectorXd& theta) const;
  /// θ of the base model (and of added terms): the form's starting point.
  Eigen::VectorXd initial() const { return initial_; }
  /// θ read off a model of this form (the inverse of build for the paper's friction values).
  Eigen::VectorXd theta_of(const Model& model) const;

  Eigen::VectorXd to_unit(const Eigen::VectorXd& theta) const;
  Eigen::VectorXd from_unit(const Eigen::VectorXd& unit) const;
  /// θ clamped into the bounds.
  Eigen::VectorXd clamp(const Eigen::VectorXd& theta) const;
  /// The same form starting from θ (clamped into the bounds): a refit from a known point.
  ModelForm with_initial(const Eigen::VectorXd& theta) const;

 private:
  enum class BindingKind { TermParameter, FdAtZminus, FdAtZero, FdAtZplus, Stiffness };
  struct Binding {
    BindingKind kind = BindingKind::TermParameter;
    std::size_t term_index = 0;
    std::string term_parameter;
  };
  ModelForm(Model base, std::string description);
  void add(const FreeParameter& parameter, const Binding& binding, double initial_value);

  Model base_;
  std::string description_;
  std::vector<FreeParameter> parameters_;
  std::vector<Binding> bindings_;
  Eigen::VectorXd initial_;
  double z_minus_m_ = 0.0;  // base model's wells (paper form)
  double z_plus_m_ = 0.0;
};

}  // namespace oscilab::analysis
