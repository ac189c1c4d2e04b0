#include "analysis/identification/edc_objective.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <future>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "analysis/common/input_error.h"
#include "analysis/hbm/hysteresis_march.h"
#include "analysis/hbm/level_response.h"

namespace oscilab::analysis {

namespace {

// The model's EDC, |Z1| and harmonic ratios at every level of the dataset (group order) with
// these HBM options; `ok` false when a level could not be solved (its entries are then NaN).
struct LevelQuantities {
  std::vector<double> edc_j, z1_abs_m, h2_ratio, h3_ratio;
};

// The measured |Z1| of a group's levels: the branch each level's response is compared on
// (level_response); empty when none was measured (twin data).
std::vector<double> measured_z1(const EdcGroup& group) {
  std::vector<double> out;
  bool any = false;
  for (const MeasuredLevel& level : group.levels) {
    out.push_back(level.amplitude_m);
    any = any || level.amplitude_m > 0.0;
  }
  if (!any) out.clear();
  return out;
}

// Runs group(g) for every group, the groups side by side when each is long work: a model with a
// stuck contact (hysteresis) is solved at the H that resolves its ringing (up to 0.3 s a group at
// δ = 1 µm), while the sliding law's few milliseconds would not pay for a thread.
void for_each_group(std::size_t groups, bool long_work,
                    const std::function<void(std::size_t)>& group) {
  if (!long_work || groups < 2) {
    for (std::size_t g = 0; g < groups; ++g) group(g);
    return;
  }
  std::vector<std::future<void>> others;
  for (std::size_t g = 1; g < groups; ++g) {
    others.push_back(std::async(std::launch::async, group, g));
  }
  group(0);
  for (std::future<void>& other : others) other.get();
}

// A model whose θ leaves it without a well is not long work: its levels fail at once (the
// groups' own solves say why).
bool has_stuck_contact(const Model& model) {
  try {
    return small_loop_stiffness_n_m(model, model.well(true).z_m) > 0.0 ||
           small_loop_stiffness_n_m(model, model.well(false).z_m) > 0.0;
  } catch (const InputError&) {
    return false;
  }
}

LevelQuantities model_quantities(const Model& model, const EdcDataset& data, const HbmOptions& hbm,
                                 bool& ok, const CancelToken& cancel) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // The groups are independent continuations: side by side for a model with a stuck contact,
  // as respond() solves them (the calibration of such a model solves every level at two H).
  std::vector<LevelQuantities> per_group(data.groups.size());
  std::vector<char> group_ok(data.groups.size(), 1);
  for_each_group(data.groups.size(), has_stuck_contact(model), [&](std::size_t g) {
    const EdcGroup& group = data.groups[g];
    std::vector<double> f0;
    for (const MeasuredLevel& level : group.levels) f0.push_back(level.f0_n);
    LevelResponse response;
    try {
      if (!cancel.cancelled()) {
        response =
            level_response(model, group.freq_hz, group.positive_well, f0, hbm, measured_z1(group));
      }
    } catch (const InputError&) {
      response.status = JobStatus::NoConvergence;
    }
    if (cancel.cancelled() || response.status != JobStatus::Ok) group_ok[g] = 0;
    LevelQuantities& out = per_group[g];
    for (std::size_t i = 0; i < f0.size(); ++i) {
      if (i >= response.edc_j.size()) {
        for (auto* v : {&out.edc_j, &out.z1_abs_m, &out.h2_ratio, &out.h3_ratio}) v->push_back(nan);
        continue;
      }
      const Eigen::VectorXd& x = response.coefficients[i];
      const double a1 = harmonic_amplitude(x, 1);
      out.edc_j.push_back(response.edc_j[i]);
      out.z1_abs_m.push_back(a1);
      out.h2_ratio.push_back(harmonic_amplitude(x, 2) / a1);
      out.h3_ratio.push_back(harmonic_amplitude(x, 3) / a1);
    }
  });
  ok = std::find(group_ok.begin(), group_ok.end(), 0) == group_ok.end();
  LevelQuantities out;
  for (const LevelQuantities& group : per_group) {
    out.edc_j.insert(out.edc_j.end(), group.edc_j.begin(), group.edc_j.end());
    out.z1_abs_m.insert(out.z1_abs_m.end(), group.z1_abs_m.begin(), group.z1_abs_m.end());
    out.h2_ratio.insert(out.h2_ratio.end(), group.h2_ratio.begin(), group.h2_ratio.end());
    out.h3_ratio.insert(out.h3_ratio.end(), group.h3_ratio.begin(), group.h3_ratio.end());
  }
  return out;
}

// The rungs of the reference ladder from `start` to `max`: 15, 23, 31, 47 and 63 (friction's kinks
// make harmonics decay slowly, so steps of ~1.5× are the useful grain), or `max` alone when it is
// below the first.
std::vector<int> reference_ladder(int start, int max) {
  std::vector<int> out;
  for (int h : {15, 23, 31, 47, 63}) {
    if (h > start && h <= max) out.push_back(h);
  }
  if (out.empty()) out.push_back(std::max(start, max));
  return out;
}

}  // namespace

SigmaBudget EdcObjective::calibrate_budget(const ModelForm& form, const EdcDataset& data,
                                           const EdcCostSettings& settings,
                                           const Eigen::VectorXd& theta) {
  SigmaBudget budget;
  budget.harmonics = settings.hbm.harmonics;
  budget.model_error_target = settings.model_error_target;
  std::vector<double> measured;
  for (const EdcGroup& group : data.groups) {
    for (const MeasuredLevel& level : group.levels) {
      budget.cycles_j.push_back(level.sigma_of_mean_j());
      measured.push_back(level.edc_j);
    }
  }
  const std::size_t n = measured.size();
  budget.bias_j.assign(n, 0.0);
  budget.model_j.assign(n, 0.0);
  budget.correction_j.assign(n, 0.0);
  budget.correction_z1_m.assign(n, 0.0);
  budget.correction_h2.assign(n, 0.0);
  budget.correction_h3.assign(n, 0.0);
  budget.branch_ambiguous.assign(n, false);
  if (settings.model_error_rel >= 0.0) {
    for (std::size_t k = 0; k < n; ++k) {
      budget.model_j[k] = settings.model_error_rel * std::abs(measured[k]);
    }
  } else {
    for (std::size_t k = 0; k < n; ++k) {
      budget.bias_j[k] = kEdcEstimatorBiasRel * std::abs(measured[k]);
    }
    std::optional<Model> model;
    try {
      model.emplace(form.build(theta));
    } catch (const InputError&) {
      budget.resolved = false;
    }
    // Quantities per H, computed once: the check of one rung (2H_ref + 1) is the reference of a
    // later one (31, 47, 63).
    std::map<int, std::pair<LevelQuantities, bool>> computed;
    const auto at = [&](int harmonics) -> const std::pair<LevelQuantities, bool>& {
      auto found = computed.find(harmonics);
      if (found != computed.end()) return found->second;
      HbmOptions hbm = settings.hbm;
      hbm.harmonics = harmonics;
      hbm.samples = 0;
      std::pair<LevelQuantities, bool> value;
      value.second = true;
      value.first = model_quantities(*model, data, hbm, value.second, settings.cancel);
      return computed.emplace(harmonics, std::move(value)).first->second;
    };
    bool fit_ok = model.has_value();
    const LevelQuantities* at_fit = nullptr;
    if (model) {
      const auto& fit = at(settings.hbm.harmonics);
      at_fit = &fit.first;
      fit_ok = fit.second;
    }
    const std::vector<int> ladder =
        settings.adaptive_harmonics
            ? reference_ladder(settings.hbm.harmonics, settings.max_harmonics)
            : std::vector<int>{settings.hbm.harmonics};
    for (std::size_t rung = 0; model && fit_ok && rung < ladder.size(); ++rung) {
      if (settings.cancel.cancelled()) {
        budget.resolved = false;
        break;
      }
      const auto& [s_reference, reference_ok] = at(ladder[rung]);
      const auto& [s_check, check_ok] = at(2 * ladder[rung] + 1);
      budget.reference_harmonics = ladder[rung];
      budget.resolved = reference_ok && check_ok;
      for (std::size_t k = 0; k < n; ++k) {
        const double error = std::abs(s_reference.edc_j[k] - s_check.edc_j[k]);
        budget.model_j[k] = std::isfinite(error) ? error : 0.0;
        const double measurement = std::hypot(budget.cycles_j[k], budget.bias_j[k]);
        if (!(error <= settings.model_error_target * measurement)) budget.resolved = false;
        // The defect correction: what H harmonics miss against the reference, at this θ.
        const auto defect = [&](const std::vector<double>& fine,
                                const std::vector<double>& coarse) {
          const double d = fine[k] - coarse[k];
          return std::isfinite(d) ? d : 0.0;
        };
        budget.correction_j[k] = defect(s_reference.edc_j, at_fit->edc_j);
        budget.correction_z1_m[k] = defect(s_reference.z1_abs_m, at_fit->z1_abs_m);
        budget.correction_h2[k] = defect(s_reference.h2_ratio, at_fit->h2_ratio);
        budget.correction_h3[k] = defect(s_reference.h3_ratio, at_fit->h3_ratio);
        const double gap = std::abs(budget.correction_j[k]);
        const double larger = std::max(std::abs(s_reference.edc_j[k]), std::abs(at_fit->edc_j[k]));
        budget.branch_ambiguous[k] = gap > kBranchGapRel * larger;
        if (budget.branch_ambiguous[k]) {
          budget.correction_j[k] = budget.correction_z1_m[k] = 0.0;
          budget.correction_h2[k] = budget.correction_h3[k] = 0.0;
          budget.model_j[k] = std::max(budget.model_j[k], gap);
        }
      }
      if (budget.resolved) break;
    }
    if (!fit_ok) budget.resolved = false;
  }
  budget.total_j.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    budget.total_j[k] =
        std::sqrt(budget.cycles_j[k] * budget.cycles_j[k] + budget.bias_j[k] * budget.bias_j[k] +
                  budget.model_j[k] * budget.model_j[k]);
  }
  return budget;
}

void SigmaBudget::adopt_corrections(const SigmaBudget& other) {
  const std::size_t n = correction_j.size();
  if (other.correction_j.size() != n) {
    throw InputError("sigma budget: corrections of " + std::to_string(other.correction_j.size()) +
                     " levels given for " + std::to_string(n));
  }
  branch_ambiguous.resize(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    if (k < other.branch_ambiguous.size() && other.branch_ambiguous[k]) continue;
    correction_j[k] = other.correction_j[k];
    correction_z1_m[k] = other.correction_z1_m[k];
    correction_h2[k] = other.correction_h2[k];
    correction_h3[k] = other.correction_h3[k];
  }
}

EdcObjective::EdcObjective(ModelForm form, EdcDataset data, EdcCostSettings settings)
    : form_(std::move(form)), data_(std::move(data)), settings_(std::move(settings)) {
  if (data_.level_count() == 0) throw InputError("EDC fit: the dataset has no levels");
  if (!(settings_.model_error_target > 0.0)) {
    throw InputError("EDC fit: the model-error target must be positive");
  }
  if (settings_.max_harmonics < settings_.hbm.harmonics) {
    throw InputError("EDC fit: the largest harmonics (" + std::to_string(settings_.max_harmonics) +
                     ") is below the starting harmonics (" +
                     std::to_string(settings_.hbm.harmonics) + ")");
  }
  // Fail early on a model harmonic balance cannot handle (stateful terms it does not support).
  HarmonicBalance check(form_.base(), data_.groups.front().freq_hz, settings_.hbm);
  if (settings_.budget) {
    if (settings_.budget->total_j.size() != static_cast<std::size_t>(data_.level_count())) {
      throw InputError("EDC fit: the given sigma budget has " +
                       std::to_string(settings_.budget->total_j.size()) + " levels, the data " +
                       std::to_string(data_.level_count()));
    }
    budget_ = *settings_.budget;
  } else {
    budget_ = calibrate_budget(form_, data_, settings_, form_.initial());
  }
  settings_.hbm.harmonics = budget_.harmonics;
  settings_.hbm.samples = 0;
  settings_.budget = budget_;
  int k = 0;
  for (const EdcGroup& group : data_.groups) {
    for (const MeasuredLevel& level : group.levels) {
      const double sigma = budget_.total_j[static_cast<std::size_t>(k++)];
      if (!(sigma > 0.0)) {
        throw InputError("EDC fit: level at f0 = " + std::to_string(level.f0_n) +
                         " N has no spread, no estimator bias and no model error: its weight is "
                         "infinite");
      }
      sigma_j_.push_back(sigma);
    }
  }
}

std::string EdcObjective::weighted_cost_name() const {
  std::ostringstream out;
  if (settings_.model_error_rel >= 0.0) {
    out << "chi2: sum over levels of ((S_mes - S_mod) / sigma)^2, sigma^2 = sigma_mean^2 + ("
        << settings_.model_error_rel << " S_mes)^2";
  } else {
    out << "chi2: sum over levels of ((S_mes - S_mod) / sigma)^2, sigma^2 = sigma_mean^2 + ("
        << kEdcEstimatorBiasRel << " S_mes)^2 + (S_mod(H=" << budget_.harmonics
        << ") - S_mod(H=" << budget_.reference_harmonics << "))^2";
  }
  return out.str();
}

std::vector<double> EdcObjective::edc_at(const Model& model, bool positive_well, double freq_hz,
                                         const std::vector<double>& f0_n) const {
  const LevelResponse response = level_response(model, freq_hz, positive_well, f0_n, settings_.hbm);
  std::vector<double> out(f0_n.size(), 0.0);
  for (std::size_t k = 0; k < response.edc_j.size() && k < out.size(); ++k) {
    out[k] = response.edc_j[k];
  }
  // The group's corrections at its measured levels, interpolated linearly in f0.
  std::vector<double> level_f0, correction;
  std::size_t k = 0;
  for (const EdcGroup& group : data_.groups) {
    const bool same = group.positive_well == positive_well &&
                      std::abs(group.freq_hz - freq_hz) <= 1e-9 * std::abs(freq_hz);
    for (const MeasuredLevel& level : group.levels) {
      if (same) {
        level_f0.push_back(level.f0_n);
        correction.push_back(budget_.correction_j[k]);
      }
      ++k;
    }
  }
  if (level_f0.empty()) return out;
  for (std::size_t i = 0; i < response.edc_j.size() && i < out.size(); ++i) {
    const double f0 = f0_n[i];
    const auto upper = std::lower_bound(level_f0.begin(), level_f0.end(), f0);
    double delta = 0.0;
    if (upper == level_f0.begin()) {
      delta = correction.front();
    } else if (upper == level_f0.end()) {
      delta = correction.back();
    } else {
      const std::size_t j = static_cast<std::size_t>(upper - level_f0.begin());
      const double w = (f0 - level_f0[j - 1]) / (level_f0[j] - level_f0[j - 1]);
      delta = (1.0 - w) * correction[j - 1] + w * correction[j];
    }
    out[i] += delta;
  }
  return out;
}

std::vector<EdcObjective::GroupResponse> EdcObjective::respond(const Eigen::VectorXd& theta,
                                                               std::optional<Model>& model) const {
  std::vector<GroupResponse> responses(data_.groups.size());
  try {
    model.emplace(form_.build(theta));
  } catch (const InputError& error) {
    for (GroupResponse& g : responses) g.message = error.what();
    return responses;
  }
  for_each_group(data_.groups.size(), has_stuck_contact(*model), [&](std::size_t i) {
    const EdcGroup& group = data_.groups[i];
    std::vector<double> f0;
    for (const MeasuredLevel& level : group.levels) f0.push_back(level.f0_n);
    try {
      responses[i].response = level_response(*model, group.freq_hz, group.positive_well, f0,
                                             settings_.hbm, measured_z1(group));
    } catch (const InputError& error) {
      responses[i].message = error.what();
    }
  });
  return responses;
}

EdcEvaluation EdcObjective::assemble(const std::vector<GroupResponse>& responses,
                                     const std::vector<double>* level_weights) const {
  EdcEvaluation out;
  out.residuals.resize(level_count());
  int k = 0;
  double deviation_sum[2] = {0.0, 0.0};
  int deviation_count[2] = {0, 0};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t g = 0; g < data_.groups.size(); ++g) {
    const EdcGroup& group = data_.groups[g];
    const std::size_t count = group.levels.size();
    std::vector<double> predicted(count, 0.0);
    std::vector<std::array<double, 3>> harmonics(count, {nan, nan, nan});
    if (const std::optional<LevelResponse>& response = responses[g].response) {
      for (std::size_t i = 0; i < response->edc_j.size() && i < count; ++i) {
        // Defect correction of the budget: S(H) + (S(H_ref) − S(H)) at the calibration θ.
        const std::size_t level = static_cast<std::size_t>(k) + i;
        predicted[i] = response->edc_j[i] + budget_.correction_j[level];
        const Eigen::VectorXd& x = response->coefficients[i];
        const double a1 = harmonic_amplitude(x, 1);
        harmonics[i] = {a1 + budget_.correction_z1_m[level],
                        harmonic_amplitude(x, 2) / a1 + budget_.correction_h2[level],
                        harmonic_amplitude(x, 3) / a1 + budget_.correction_h3[level]};
      }
      if (response->status != JobStatus::Ok || response->edc_j.size() < count) {
        out.ok = false;
        out.message = response->message;
      }
    } else {
      out.ok = false;
      out.message = responses[g].message;
    }
    for (std::size_t i = 0; i < count; ++i, ++k) {
      const double measured = group.levels[i].edc_j;
      const double difference = measured - predicted[i];
      out.cost_j += std::abs(difference);  // eq. (8)
      out.residuals(k) = difference / sigma_j_[k];
      const double w = level_weights ? (*level_weights)[k] : 1.0;
      out.weighted_cost += w * out.residuals(k) * out.residuals(k);
      const int well = group.positive_well ? 0 : 1;
      deviation_sum[well] += std::abs(difference) / measured;
      ++deviation_count[well];
      out.z1_abs_m.push_back(harmonics[i][0]);
      out.h2_ratio.push_back(harmonics[i][1]);
      out.h3_ratio.push_back(harmonics[i][2]);
      const auto at = static_cast<std::size_t>(k);
      out.branch_ambiguous.push_back(at < budget_.branch_ambiguous.size() &&
                                     budget_.branch_ambiguous[at]);
    }
    out.edc_mod_j.push_back(std::move(predicted));
  }
  out.mean_deviation_pct_positive =
      deviation_count[0] ? 100.0 * deviation_sum[0] / deviation_count[0] : nan;
  out.mean_deviation_pct_negative =
      deviation_count[1] ? 100.0 * deviation_sum[1] / deviation_count[1] : nan;
  return out;
}

EdcEvaluation EdcObjective::evaluate(const Eigen::VectorXd& theta,
                                     const std::vector<double>* level_weights) const {
  evaluations_->fetch_add(1);
  std::optional<Model> model;
  return assemble(respond(theta, model), level_weights);
}

bool EdcObjective::evaluate_nearby(const Eigen::VectorXd& theta,
                                   const std::vector<Eigen::VectorXd>& nearby, EdcEvaluation& at,
                                   std::vector<EdcEvaluation>& at_nearby) const {
  // One evaluation at θ, and one more for the Jacobians and residuals of the nearby θ.
  evaluations_->fetch_add(2);
  std::optional<Model> model;
  const std::vector<GroupResponse> responses = respond(theta, model);
  at = assemble(responses, nullptr);
  at_nearby.clear();
  if (!at.ok) return false;
  std::vector<Model> models;
  try {
    for (const Eigen::VectorXd& t : nearby) models.push_back(form_.build(t));
  } catch (const InputError&) {
    return false;
  }
  std::vector<std::vector<GroupResponse>> nearby_responses(
      nearby.size(), std::vector<GroupResponse>(data_.groups.size()));
  std::vector<char> solved(data_.groups.size(), 1);
  for_each_group(data_.groups.size(), has_stuck_contact(*model), [&](std::size_t g) {
    // Each level's solution, reached by natural continuation or by arclength past a fold, is a
    // regular root of the balance (a landing exactly on a fold would make J singular: refused
    // below), so a small change of θ moves it along dx/dθ = −J⁻¹ ∂r/∂θ.
    const LevelResponse& base = *responses[g].response;
    std::vector<LevelResponse> near;
    try {
      near = nearby_level_responses(*model, models, data_.groups[g].freq_hz, base, settings_.hbm);
    } catch (const InputError&) {  // a nearby θ harmonic balance refuses: solve each instead
      solved[g] = 0;
      return;
    }
    for (std::size_t j = 0; j < near.size(); ++j) {
      if (near[j].status != JobStatus::Ok) solved[g] = 0;
      nearby_responses[j][g].response = std::move(near[j]);
    }
  });
  if (std::find(solved.begin(), solved.end(), 0) != solved.end()) return false;
  for (const std::vector<GroupResponse>& r : nearby_responses) {
    at_nearby.push_back(assemble(r, nullptr));
  }
  return true;
}

}  // namespace oscilab::analysis
