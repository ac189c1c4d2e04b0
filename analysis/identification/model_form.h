#pragma once

#include <memory>
#include <string>
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

  int size() const { return static_cast<int>(parameters_.size()); }
  const std::vector<FreeParameter>& parameters() const { return parameters_; }
  std::vector<std::string> names() const;
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
  enum class BindingKind { TermParameter, FdAtZminus, FdAtZero, FdAtZplus };
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
