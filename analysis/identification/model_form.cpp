#include "analysis/identification/model_form.h"

#include <algorithm>
#include <cmath>

#include "analysis/common/input_error.h"
#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/position_dependent_friction.h"

namespace oscilab::analysis {
namespace {

std::size_t term_of_type(const Model& model, const std::string& type) {
  std::size_t found = model.terms().size();
  for (std::size_t i = 0; i < model.terms().size(); ++i) {
    if (model.terms()[i]->type() != type) continue;
    if (found != model.terms().size()) {
      throw InputError("model form paper: the model has more than one " + type + " term");
    }
    found = i;
  }
  if (found == model.terms().size()) {
    throw InputError("model form paper: the model has no " + type + " term");
  }
  return found;
}

void check_bounds(const FreeParameter& parameter, double value) {
  if (!(parameter.lower < parameter.upper) || !std::isfinite(parameter.lower) ||
      !std::isfinite(parameter.upper)) {
    throw InputError("model form: " + parameter.name +
                     ": bounds must be finite with lower < upper");
  }
  if (parameter.log_scale && !(parameter.lower > 0.0)) {
    throw InputError("model form: " + parameter.name + ": a log-scale bound must be positive");
  }
  if (!(value >= parameter.lower && value <= parameter.upper)) {
    throw InputError("model form: " + parameter.name + ": value " + std::to_string(value) +
                     " lies outside its bounds [" + std::to_string(parameter.lower) + ", " +
                     std::to_string(parameter.upper) + "]");
  }
}

}  // namespace

ModelForm::ModelForm(Model base, std::string description)
    : base_(std::move(base)), description_(std::move(description)) {}

void ModelForm::add(const FreeParameter& parameter, const Binding& binding, double initial_value) {
  check_bounds(parameter, initial_value);
  parameters_.push_back(parameter);
  bindings_.push_back(binding);
  initial_.conservativeResize(initial_.size() + 1);
  initial_(initial_.size() - 1) = initial_value;
}

ModelForm ModelForm::paper(const Model& base) {
  ModelForm form(base, "paper");
  const std::size_t friction_index = term_of_type(base, "position-dependent-friction");
  const std::size_t viscous_index = term_of_type(base, "viscous-damping");
  form.z_minus_m_ = base.well(false).z_m;
  form.z_plus_m_ = base.well(true).z_m;
  if (!(form.z_minus_m_ < 0.0 && form.z_plus_m_ > 0.0)) {
    throw InputError("model form paper: the wells must lie on both sides of z = 0 (eq. (9))");
  }
  const auto& friction =
      static_cast<const PositionDependentFriction&>(*base.terms()[friction_index]);
  const double fd_minus = friction.dynamic_friction_n(form.z_minus_m_);
  const double fd_zero = friction.dynamic_friction_n(0.0);
  const double fd_plus = friction.dynamic_friction_n(form.z_plus_m_);
  const double ks = friction.parameters().ks;
  const double vt = friction.parameters().vt_m_s;
  const double c = base.terms()[viscous_index]->parameter("c_ns_m");

  // Search bounds: wide enough for a laboratory oscillator of this kind (friction up to a few N,
  // static excess up to 3× the dynamic friction, v_t over three decades), widened to hold the
  // base model's own values.
  const auto fd_bounds = [](const char* name, double value) {
    return FreeParameter{name, 0.0, std::max(2.0, 2.0 * value), false};
  };
  // Eq. (9): θ = [f_d(z₋*), f_d(z₊*), f_d(0), v_t, k_s, c].
  form.add(fd_bounds("fd_zminus_n", fd_minus), {BindingKind::FdAtZminus, friction_index, ""},
           fd_minus);
  form.add(fd_bounds("fd_zplus_n", fd_plus), {BindingKind::FdAtZplus, friction_index, ""}, fd_plus);
  form.add(fd_bounds("fd_zero_n", fd_zero), {BindingKind::FdAtZero, friction_index, ""}, fd_zero);
  form.add({"vt_m_s", std::min(1e-3, vt), std::max(1e-1, vt), true},
           {BindingKind::TermParameter, friction_index, "vt_m_s"}, vt);
  form.add({"ks", 1.0, std::max(3.0, 2.0 * ks), false},
           {BindingKind::TermParameter, friction_index, "ks"}, ks);
  form.add({"c_ns_m", 0.0, std::max(10.0, 2.0 * c), false},
           {BindingKind::TermParameter, viscous_index, "c_ns_m"}, c);
  return form;
}

ModelForm ModelForm::of_terms(const Model& base, std::vector<TermParameter> parameters) {
  ModelForm form(base, "terms");
  for (const TermParameter& p : parameters) {
    if (p.term_index >= base.terms().size()) {
      throw InputError("model form: term index " + std::to_string(p.term_index) +
                       " is beyond the model's " + std::to_string(base.terms().size()) + " terms");
    }
    const double value = base.terms()[p.term_index]->parameter(p.parameter.name);
    form.add(p.parameter, {BindingKind::TermParameter, p.term_index, p.parameter.name}, value);
  }
  return form;
}

void ModelForm::add_term(std::unique_ptr<ModelTerm> term, std::vector<FreeParameter> free) {
  if (!term) throw InputError("model form: add_term needs a term");
  const std::size_t index = base_.terms().size();
  const std::string type = term->type();
  std::vector<double> values;
  for (const FreeParameter& p : free) values.push_back(term->parameter(p.name));
  base_.add_term(std::move(term));
  for (std::size_t i = 0; i < free.size(); ++i) {
    add(free[i], {BindingKind::TermParameter, index, free[i].name}, values[i]);
  }
  description_ += " + " + type;
}

void ModelForm::change_term(const std::string& type, std::vector<FreeParameter> free,
                            const std::vector<double>& initial) {
  if (initial.size() != free.size()) {
    throw InputError("model form: change_term needs one initial value per free parameter");
  }
  std::size_t index = base_.terms().size();
  for (std::size_t i = 0; i < base_.terms().size() && index == base_.terms().size(); ++i) {
    if (base_.terms()[i]->type() == type) index = i;
  }
  if (index == base_.terms().size()) {
    throw InputError("model form: the model has no " + type + " term to change");
  }
  for (std::size_t i = 0; i < free.size(); ++i) {
    check_bounds(free[i], initial[i]);
    base_.set_parameter(index, free[i].name, initial[i]);
    add(free[i], {BindingKind::TermParameter, index, free[i].name}, initial[i]);
  }
  description_ += " + " + type + " (" + free.front().name + ")";
}

void ModelForm::free_stiffness(double relative) {
  if (!(relative > 0.0 && relative < 1.0)) {
    throw InputError("model form: the stiffness's relative range must lie in (0, 1)");
  }
  for (const Binding& b : bindings_) {
    if (b.kind == BindingKind::Stiffness) throw InputError("model form: the stiffness is free");
  }
  std::size_t index = base_.terms().size();
  for (std::size_t i = 0; i < base_.terms().size() && index == base_.terms().size(); ++i) {
    if (base_.terms()[i]->type() == "polynomial-stiffness") index = i;
  }
  if (index == base_.terms().size()) {
    throw InputError("model form: the model has no polynomial-stiffness term to identify");
  }
  const auto& stiffness = static_cast<const PolynomialStiffness&>(*base_.terms()[index]);
  const std::vector<double>& c = stiffness.coefficients();
  // The scale of each power: its force at the largest |z| of the wells (or 1 cm without wells).
  double z_ref = 0.0;
  for (const Equilibrium& e : base_.equilibria()) z_ref = std::max(z_ref, std::abs(e.z_m));
  if (!(z_ref > 0.0)) z_ref = 1e-2;
  double force_scale = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    force_scale = std::max(force_scale, std::abs(c[i]) * std::pow(z_ref, static_cast<double>(i)));
  }
  if (!(force_scale > 0.0)) force_scale = 1.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double power_scale = 0.05 * force_scale / std::pow(z_ref, static_cast<double>(i));
    const double half_width = relative * std::max(std::abs(c[i]), power_scale);
    const std::string unit = i == 0 ? "_n" : i == 1 ? "_n_m" : "_n_m" + std::to_string(i);
    add({"stiffness_c" + std::to_string(i) + unit, c[i] - half_width, c[i] + half_width, false},
        {BindingKind::Stiffness, index, "c" + std::to_string(i)}, c[i]);
  }
  description_ += " + identified stiffness";
}

bool ModelForm::is_stiffness(int i) const {
  return i >= 0 && i < size() &&
         bindings_[static_cast<std::size_t>(i)].kind == BindingKind::Stiffness;
}

bool ModelForm::identifies_stiffness() const {
  for (int i = 0; i < size(); ++i) {
    if (is_stiffness(i)) return true;
  }
  return false;
}

bool ModelForm::frees_stiffness_power(int power) const {
  const std::string name = "c" + std::to_string(power);
  for (const Binding& b : bindings_) {
    if (b.kind == BindingKind::Stiffness && b.term_parameter == name) return true;
  }
  return false;
}

ModelForm ModelForm::holding_stiffness(const Eigen::VectorXd& theta) const {
  if (theta.size() != size()) {
    throw InputError("model form: θ has " + std::to_string(theta.size()) + " values, expected " +
                     std::to_string(size()));
  }
  ModelForm out = *this;
  out.parameters_.clear();
  out.bindings_.clear();
  out.initial_.resize(0);
  for (int i = 0; i < size(); ++i) {
    const Binding& b = bindings_[static_cast<std::size_t>(i)];
    if (b.kind == BindingKind::Stiffness) {
      out.base_.set_parameter(b.term_index, b.term_parameter, theta(i));
    } else {
      out.add(parameters_[static_cast<std::size_t>(i)], b,
              std::clamp(theta(i), parameters_[i].lower, parameters_[i].upper));
    }
  }
  return out;
}

Eigen::VectorXd ModelForm::expand(const Eigen::VectorXd& held_theta,
                                  const Eigen::VectorXd& theta) const {
  Eigen::VectorXd out = theta;
  Eigen::Index next = 0;
  for (int i = 0; i < size(); ++i) {
    if (bindings_[static_cast<std::size_t>(i)].kind == BindingKind::Stiffness) continue;
    if (next >= held_theta.size()) throw InputError("model form: θ of the held form is too short");
    out(i) = held_theta(next++);
  }
  return out;
}

std::vector<std::string> ModelForm::names() const {
  std::vector<std::string> out;
  for (const FreeParameter& p : parameters_) out.push_back(p.name);
  return out;
}

std::vector<std::pair<std::string, double>> ModelForm::named(const Eigen::VectorXd& theta) const {
  std::vector<std::pair<std::string, double>> out;
  for (int i = 0; i < size(); ++i) out.emplace_back(parameters_[i].name, theta(i));
  return out;
}

Model ModelForm::build(const Eigen::VectorXd& theta) const {
  if (theta.size() != size()) {
    throw InputError("model form: θ has " + std::to_string(theta.size()) + " values, expected " +
                     std::to_string(size()));
  }
  Model model = base_;
  double fd[3] = {0.0, 0.0, 0.0};
  std::size_t friction_index = model.terms().size();
  for (int i = 0; i < size(); ++i) {
    if (!std::isfinite(theta(i))) {
      throw InputError("model form: " + parameters_[i].name + ": not a finite number");
    }
    const Binding& b = bindings_[i];
    switch (b.kind) {
      case BindingKind::TermParameter:
      case BindingKind::Stiffness:
        model.set_parameter(b.term_index, b.term_parameter, theta(i));
        break;
      case BindingKind::FdAtZminus:
        fd[0] = theta(i);
        friction_index = b.term_index;
        break;
      case BindingKind::FdAtZero:
        fd[1] = theta(i);
        friction_index = b.term_index;
        break;
      case BindingKind::FdAtZplus:
        fd[2] = theta(i);
        friction_index = b.term_index;
        break;
    }
  }
  if (friction_index < model.terms().size()) {
    // Eq. (6) through the three values of eq. (9), at the base model's wells: fixed abscissae,
    // also when the stiffness is identified and the wells move by the fraction it changes.
    auto& friction = static_cast<PositionDependentFriction&>(model.term(friction_index));
    const auto p = friction.parameters();
    const auto three = PositionDependentFriction::from_three_points(
        z_minus_m_, fd[0], fd[1], z_plus_m_, fd[2], p.ks, p.vt_m_s);
    friction.set_parameter("alpha_n_m2", three.alpha_n_m2);
    friction.set_parameter("beta_n_m", three.beta_n_m);
    friction.set_parameter("gamma_n", three.gamma_n);
  }
  return model;
}

Eigen::VectorXd ModelForm::theta_of(const Model& model) const {
  Eigen::VectorXd theta(size());
  for (int i = 0; i < size(); ++i) {
    const Binding& b = bindings_[i];
    if (b.term_index >= model.terms().size()) {
      throw InputError("model form: the model has fewer terms than the form");
    }
    const ModelTerm& term = *model.terms()[b.term_index];
    if (b.kind == BindingKind::TermParameter || b.kind == BindingKind::Stiffness) {
      theta(i) = term.parameter(b.term_parameter);
      continue;
    }
    const auto& friction = dynamic_cast<const PositionDependentFriction&>(term);
    const double z = b.kind == BindingKind::FdAtZminus  ? z_minus_m_
                     : b.kind == BindingKind::FdAtZplus ? z_plus_m_
                                                        : 0.0;
    theta(i) = friction.dynamic_friction_n(z);
  }
  return theta;
}

Eigen::VectorXd ModelForm::to_unit(const Eigen::VectorXd& theta) const {
  Eigen::VectorXd u(size());
  for (int i = 0; i < size(); ++i) {
    const FreeParameter& p = parameters_[i];
    u(i) = p.log_scale ? std::log(theta(i) / p.lower) / std::log(p.upper / p.lower)
                       : (theta(i) - p.lower) / (p.upper - p.lower);
  }
  return u;
}

Eigen::VectorXd ModelForm::from_unit(const Eigen::VectorXd& unit) const {
  Eigen::VectorXd theta(size());
  for (int i = 0; i < size(); ++i) {
    const FreeParameter& p = parameters_[i];
    const double u = std::clamp(unit(i), 0.0, 1.0);
    theta(i) =
        p.log_scale ? p.lower * std::pow(p.upper / p.lower, u) : p.lower + u * (p.upper - p.lower);
  }
  return theta;
}

Eigen::VectorXd ModelForm::clamp(const Eigen::VectorXd& theta) const {
  Eigen::VectorXd out = theta;
  for (int i = 0; i < size(); ++i) {
    out(i) = std::clamp(theta(i), parameters_[i].lower, parameters_[i].upper);
  }
  return out;
}

ModelForm ModelForm::with_initial(const Eigen::VectorXd& theta) const {
  if (theta.size() != size()) {
    throw InputError("model form: θ has " + std::to_string(theta.size()) + " values, expected " +
                     std::to_string(size()));
  }
  ModelForm out = *this;
  out.initial_ = clamp(theta);
  return out;
}

}  // namespace oscilab::analysis
