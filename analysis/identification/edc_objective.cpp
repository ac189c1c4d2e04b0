#include "analysis/identification/edc_objective.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "analysis/common/input_error.h"
#include "analysis/hbm/level_response.h"

namespace oscilab::analysis {

EdcObjective::EdcObjective(ModelForm form, EdcDataset data, EdcCostSettings settings)
    : form_(std::move(form)), data_(std::move(data)), settings_(settings) {
  if (data_.level_count() == 0) throw InputError("EDC fit: the dataset has no levels");
  if (!(settings_.model_error_rel >= 0.0)) {
    throw InputError("EDC fit: the model-error floor must be non-negative");
  }
  for (const EdcGroup& group : data_.groups) {
    for (const MeasuredLevel& level : group.levels) {
      const double sigma =
          std::hypot(level.sigma_of_mean_j(), settings_.model_error_rel * level.edc_j);
      if (!(sigma > 0.0)) {
        throw InputError("EDC fit: level at f0 = " + std::to_string(level.f0_n) +
                         " N has no spread and the model-error floor is 0: its weight is infinite");
      }
      sigma_j_.push_back(sigma);
    }
  }
  // Fail early on a model harmonic balance cannot handle (stateful terms it does not support).
  HarmonicBalance check(form_.base(), data_.groups.front().freq_hz, settings_.hbm);
}

std::string EdcObjective::weighted_cost_name() const {
  std::ostringstream out;
  out << "chi2: sum over levels of ((S_mes - S_mod) / sigma)^2, sigma^2 = sigma_mean^2 + ("
      << settings_.model_error_rel << " S_mes)^2";
  return out.str();
}

std::vector<double> EdcObjective::edc_at(const Model& model, bool positive_well, double freq_hz,
                                         const std::vector<double>& f0_n) const {
  const LevelResponse response = level_response(model, freq_hz, positive_well, f0_n, settings_.hbm);
  std::vector<double> out(f0_n.size(), 0.0);
  for (std::size_t k = 0; k < response.edc_j.size() && k < out.size(); ++k) {
    out[k] = response.edc_j[k];
  }
  return out;
}

EdcEvaluation EdcObjective::evaluate(const Eigen::VectorXd& theta,
                                     const std::vector<double>* level_weights) const {
  evaluations_->fetch_add(1);
  EdcEvaluation out;
  out.residuals.resize(level_count());
  std::optional<Model> model;
  try {
    model.emplace(form_.build(theta));
  } catch (const InputError& error) {
    out.ok = false;
    out.message = error.what();
  }
  int k = 0;
  double deviation_sum[2] = {0.0, 0.0};
  int deviation_count[2] = {0, 0};
  for (const EdcGroup& group : data_.groups) {
    std::vector<double> f0;
    for (const MeasuredLevel& level : group.levels) f0.push_back(level.f0_n);
    std::vector<double> predicted(f0.size(), 0.0);
    if (model) {
      try {
        const LevelResponse response =
            level_response(*model, group.freq_hz, group.positive_well, f0, settings_.hbm);
        for (std::size_t i = 0; i < response.edc_j.size() && i < f0.size(); ++i) {
          predicted[i] = response.edc_j[i];
        }
        if (response.status != JobStatus::Ok || response.edc_j.size() < f0.size()) {
          out.ok = false;
          out.message = response.message;
        }
      } catch (const InputError& error) {
        out.ok = false;
        out.message = error.what();
      }
    }
    for (std::size_t i = 0; i < f0.size(); ++i, ++k) {
      const double measured = group.levels[i].edc_j;
      const double difference = measured - predicted[i];
      out.cost_j += std::abs(difference);  // eq. (8)
      out.residuals(k) = difference / sigma_j_[k];
      const double w = level_weights ? (*level_weights)[k] : 1.0;
      out.weighted_cost += w * out.residuals(k) * out.residuals(k);
      const int well = group.positive_well ? 0 : 1;
      deviation_sum[well] += std::abs(difference) / measured;
      ++deviation_count[well];
    }
    out.edc_mod_j.push_back(std::move(predicted));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.mean_deviation_pct_positive =
      deviation_count[0] ? 100.0 * deviation_sum[0] / deviation_count[0] : nan;
  out.mean_deviation_pct_negative =
      deviation_count[1] ? 100.0 * deviation_sum[1] / deviation_count[1] : nan;
  return out;
}

}  // namespace oscilab::analysis
