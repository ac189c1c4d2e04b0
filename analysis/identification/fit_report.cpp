#include "analysis/identification/fit_report.h"

#include <cmath>

#include "analysis/common/input_error.h"
#include "analysis/common/json_number.h"
#include "analysis/edc/well.h"
#include "analysis/identification/sigma_budget_report.h"
#include "analysis/model/position_dependent_friction.h"

namespace oscilab::analysis {
namespace {}  // namespace

nlohmann::json fit_report_json(const FitResult& fit, const EdcObjective& objective,
                               const std::vector<std::string>& records) {
  const ModelForm& form = objective.form();
  nlohmann::json out;
  out["format"] = "oscilab-fit/1";
  out["records"] = records;
  out["model_form"] = form.description();
  out["status"] = fit.status == JobStatus::Ok          ? "ok"
                  : fit.status == JobStatus::Cancelled ? "cancelled"
                                                       : "no-convergence";
  if (!fit.message.empty()) out["message"] = fit.message;

  nlohmann::json parameters = nlohmann::json::object();
  for (int i = 0; i < form.size(); ++i) parameters[form.parameters()[i].name] = fit.theta(i);
  out["parameters"] = parameters;
  out["cost_j"] = fit.evaluation.cost_j;
  out["mean_deviation_pct"] = {
      {"positive", finite_or_null(fit.evaluation.mean_deviation_pct_positive)},
      {"negative", finite_or_null(fit.evaluation.mean_deviation_pct_negative)}};
  out["evaluations"] = fit.evaluations;
  out["seconds"] = fit.seconds;
  out["fit_cost"] = {{"name", objective.weighted_cost_name()},
                     {"value", fit.evaluation.weighted_cost}};
  out["method"] = {{"name", fit_method_name(fit.method)}, {"settings", fit.settings}};
  out["hbm"] = {{"harmonics", objective.settings().hbm.harmonics},
                {"model_error_rel", objective.settings().model_error_rel >= 0.0
                                        ? nlohmann::json(objective.settings().model_error_rel)
                                        : nlohmann::json("sigma budget")}};
  out["sigma_budget"] = sigma_budget_json(objective);
  if (fit.check_harmonics > 0) {
    out["hbm"]["truncation_check"] = {
        {"harmonics", fit.check_harmonics},
        {"max_edc_change_rel", finite_or_null(fit.truncation_change_rel)}};
  }

  const Model model = form.build(fit.theta);
  for (const auto& term : model.terms()) {
    if (const auto* friction = dynamic_cast<const PositionDependentFriction*>(term.get())) {
      out["friction_coefficients"] = {{"alpha_n_m2", friction->parameters().alpha_n_m2},
                                      {"beta_n_m", friction->parameters().beta_n_m},
                                      {"gamma_n", friction->parameters().gamma_n}};
    }
  }

  const FitUncertainty& u = fit.uncertainty;
  if (!u.parameters.empty()) {
    nlohmann::json se = nlohmann::json::object(), ci = nlohmann::json::object(),
                   boot_std = nlohmann::json::object(), boot_ci = nlohmann::json::object();
    nlohmann::json weak = nlohmann::json::array();
    for (const ParameterUncertainty& p : u.parameters) {
      se[p.name] = finite_or_null(p.standard_error);
      ci[p.name] = {finite_or_null(p.lower_95), finite_or_null(p.upper_95)};
      boot_std[p.name] = finite_or_null(p.bootstrap_std);
      boot_ci[p.name] = {finite_or_null(p.bootstrap_lower_95),
                         finite_or_null(p.bootstrap_upper_95)};
      if (p.weakly_identified) weak.push_back({{"parameter", p.name}, {"reason", p.note}});
    }
    out["standard_errors"] = se;
    out["intervals_95"] = ci;
    out["weakly_identified"] = weak;
    out["reduced_chi2"] = finite_or_null(u.reduced_chi2);
    out["degrees_of_freedom"] = u.dof;
    nlohmann::json matrix = nlohmann::json::array();
    for (int i = 0; i < u.correlation.rows(); ++i) {
      nlohmann::json row = nlohmann::json::array();
      for (int j = 0; j < u.correlation.cols(); ++j)
        row.push_back(finite_or_null(u.correlation(i, j)));
      matrix.push_back(row);
    }
    out["correlation"] = {{"parameters", form.names()}, {"matrix", matrix}};
    out["uncertainty_evaluations"] = u.evaluations;
    if (u.bootstrap_replicates > 0) {
      out["bootstrap"] = {{"replicates", u.bootstrap_replicates},
                          {"resampling", "levels of each well, with replacement"},
                          {"std", boot_std},
                          {"intervals_95", boot_ci}};
    }
  }

  nlohmann::json levels = nlohmann::json::array();
  int k = 0;
  for (std::size_t g = 0; g < objective.data().groups.size(); ++g) {
    const EdcGroup& group = objective.data().groups[g];
    for (std::size_t i = 0; i < group.levels.size(); ++i, ++k) {
      const MeasuredLevel& m = group.levels[i];
      levels.push_back({{"well", to_string(well_of(group.positive_well))},
                        {"freq_hz", group.freq_hz},
                        {"f0_n", m.f0_n},
                        {"edc_mes_j", m.edc_j},
                        {"edc_std_j", m.edc_std_j},
                        {"cycles", m.cycles},
                        {"edc_mod_j", fit.evaluation.edc_mod_j[g][i]},
                        {"sigma_j", objective.sigma_j()[k]},
                        {"residual_sigma", fit.evaluation.residuals(k)},
                        {"record", m.record}});
    }
  }
  out["levels"] = levels;
  out["excluded_levels"] = objective.data().excluded;
  nlohmann::json history = nlohmann::json::array();
  for (const auto& [evaluations, cost] : fit.history) history.push_back({evaluations, cost});
  out["history"] = history;
  out["model"] = model.to_json();
  return out;
}

FitSummary read_fit_summary(const nlohmann::json& fit, const std::string& source) {
  const auto need = [&](const char* key) -> const nlohmann::json& {
    if (!fit.is_object() || !fit.contains(key)) {
      throw InputError(source + ": " + key + ": missing (not a FIT JSON?)");
    }
    return fit.at(key);
  };
  const auto as_number = [&](const nlohmann::json& value, const std::string& key) {
    if (value.is_null()) return std::nan("");
    if (!value.is_number()) throw InputError(source + ": " + key + ": not a number");
    return value.get<double>();
  };
  FitSummary s;
  s.source = source;
  const nlohmann::json& parameters = need("parameters");
  if (!parameters.is_object() || parameters.empty()) {
    throw InputError(source + ": parameters: expected an object of named values");
  }
  for (const auto& [name, value] : parameters.items()) {
    s.parameters.emplace_back(name, as_number(value, "parameters." + name));
  }
  if (fit.contains("standard_errors") && fit["standard_errors"].is_object()) {
    for (const auto& [name, value] : fit["standard_errors"].items()) {
      s.standard_errors.emplace_back(name, as_number(value, "standard_errors." + name));
    }
  }
  s.cost_j = as_number(need("cost_j"), "cost_j");
  const nlohmann::json& deviation = need("mean_deviation_pct");
  if (!deviation.is_object() || !deviation.contains("positive") ||
      !deviation.contains("negative")) {
    throw InputError(source + ": mean_deviation_pct: needs positive and negative");
  }
  s.mean_deviation_pct_positive = as_number(deviation["positive"], "mean_deviation_pct.positive");
  s.mean_deviation_pct_negative = as_number(deviation["negative"], "mean_deviation_pct.negative");
  s.evaluations = static_cast<long>(as_number(need("evaluations"), "evaluations"));
  s.seconds = as_number(need("seconds"), "seconds");
  if (fit.contains("method") && fit["method"].is_object() && fit["method"].contains("name")) {
    s.method = fit["method"]["name"].get<std::string>();
  }
  if (fit.contains("records") && fit["records"].is_array()) {
    for (const auto& r : fit["records"]) {
      if (!r.is_string()) continue;
      s.records += (s.records.empty() ? "" : ";") + r.get<std::string>();
    }
  }
  return s;
}

}  // namespace oscilab::analysis
