#include "analysis/design/next_point.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "analysis/common/input_error.h"
#include "analysis/common/parallel_for.h"
#include "analysis/common/quantile.h"
#include "analysis/design/response_prediction.h"
#include "analysis/diagnosis/response_fingerprints.h"

namespace oscilab::analysis {

std::vector<double> AdmissibleSettings::f0_grid() const {
  std::vector<double> out;
  // Counted by rounding, so that 0.2:0.1:2.7 gives 26 levels despite the step's rounding.
  const int count = static_cast<int>(std::floor((f0_max_n - f0_min_n) / f0_step_n + 1e-9)) + 1;
  for (int i = 0; i < count; ++i) out.push_back(f0_min_n + i * f0_step_n);
  return out;
}

std::vector<double> AdmissibleSettings::freq_grid() const {
  if (!(freq_span_hz > 0.0)) return {freq_hz};
  std::vector<double> out;
  const int half = static_cast<int>(std::floor(freq_span_hz / freq_step_hz + 1e-9));
  for (int i = -half; i <= half; ++i) out.push_back(freq_hz + i * freq_step_hz);
  return out;
}

void AdmissibleSettings::validate() const {
  const auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  const auto non_negative = [](double x) { return x >= 0.0 && std::isfinite(x); };
  if (!positive(f0_min_n) || !std::isfinite(f0_max_n) || !(f0_max_n >= f0_min_n)) {
    throw InputError("settings.f0_range_n: need 0 < f0_min <= f0_max, got " +
                     std::to_string(f0_min_n) + " to " + std::to_string(f0_max_n) + " N");
  }
  if (!positive(f0_step_n)) throw InputError("settings.f0_step_n: must be a positive force in N");
  if (!positive(freq_hz)) throw InputError("settings.freq_hz: must be a positive number of Hz");
  if (!non_negative(freq_span_hz) || !(freq_hz - freq_span_hz > 0.0)) {
    throw InputError("settings.freq_span_hz: must be >= 0 Hz and leave the range above 0 Hz");
  }
  if (!positive(freq_step_hz)) {
    throw InputError("settings.freq_step_hz: must be a positive number of Hz");
  }
  if (!positive_well && !negative_well) throw InputError("settings.wells: no well allowed");
  if (!positive(dwell_s)) throw InputError("settings.dwell_s: must be a positive number of s");
  if (!non_negative(settling_s)) throw InputError("settings.settling_s: must be >= 0 s");
  if (!non_negative(well_change_s)) throw InputError("settings.well_change_s: must be >= 0 s");
}

namespace {

// The relative standard error a new level would have from its cycles: the median over the
// levels measured so far (0 for twin data without cycles).
struct MeasurementNoise {
  double edc_rel = 0.0;
  double z1_rel = 0.0;
};

MeasurementNoise typical_noise(const EdcDataset& data) {
  std::vector<double> edc, z1;
  for (const EdcGroup& g : data.groups) {
    for (const MeasuredLevel& m : g.levels) {
      if (m.cycles > 0 && m.edc_j > 0.0) edc.push_back(m.sigma_of_mean_j() / m.edc_j);
      if (m.harmonic_cycles > 0 && m.amplitude_m > 0.0) z1.push_back(m.z1_abs_se_m / m.amplitude_m);
    }
  }
  MeasurementNoise out;
  if (!edc.empty()) out.edc_rel = quantiles(edc, {0.5}).front();
  if (!z1.empty()) out.z1_rel = quantiles(z1, {0.5}).front();
  return out;
}

struct Slot {
  bool positive_well = true;
  double freq_hz = 0.0;
};

// The solved hypotheses predicted: the min_models of largest weight and any other of weight ≥
// min_weight, in index order.
std::vector<int> plausible_hypotheses(const std::vector<ModelHypothesis>& hypotheses,
                                      const NextPointOptions& options) {
  std::vector<int> ranked;
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    if (hypotheses[i].solved && hypotheses[i].objective) ranked.push_back(static_cast<int>(i));
  }
  std::stable_sort(ranked.begin(), ranked.end(), [&](int a, int b) {
    return hypotheses[static_cast<std::size_t>(a)].weight >
           hypotheses[static_cast<std::size_t>(b)].weight;
  });
  std::vector<int> plausible;
  for (std::size_t r = 0; r < ranked.size(); ++r) {
    if (static_cast<int>(r) < options.min_models ||
        hypotheses[static_cast<std::size_t>(ranked[r])].weight >= options.min_weight) {
      plausible.push_back(ranked[r]);
    }
  }
  std::sort(plausible.begin(), plausible.end());
  return plausible;
}

// Every plausible hypothesis's predictions at every slot, in parallel over the hypotheses.
// `predictions[a][s]`: plausible[a] at slot s. A hypothesis that cannot be predicted is left
// out of `plausible` and named in `message`.
struct Predictions {
  std::vector<int> plausible;
  std::vector<std::vector<PredictedLevels>> at;
  std::string message;
};

Predictions predict_plausible(const std::vector<ModelHypothesis>& hypotheses,
                              std::vector<int> plausible, const std::vector<Slot>& slots,
                              const std::vector<double>& f0, const NextPointOptions& options,
                              const ProgressFn& progress, const CancelToken& cancel) {
  const std::size_t count = plausible.size();
  std::vector<std::vector<PredictedLevels>> predictions(count);
  std::mutex done_mutex;
  std::size_t done = 0;
  std::vector<std::string> failures(count);
  parallel_for(count, options.threads, [&](std::size_t a) {
    const ModelHypothesis& h = hypotheses[static_cast<std::size_t>(plausible[a])];
    // Nothing throws across threads: a failure leaves this hypothesis without predictions.
    try {
      const Eigen::MatrixXd cov = unit_covariance(*h.objective, h.theta, options.use_fingerprints,
                                                  options.difference_step, cancel);
      for (const Slot& s : slots) {
        if (cancel.cancelled()) return;
        predictions[a].push_back(predict_levels(*h.objective, h.theta, cov, s.positive_well,
                                                s.freq_hz, f0, options.difference_step, cancel));
      }
    } catch (const std::exception& error) {
      failures[a] = h.label() + ": " + error.what();
      predictions[a].clear();
      return;
    }
    const std::lock_guard lock(done_mutex);
    ++done;
    if (progress) progress(static_cast<double>(done) / count);
  });
  Predictions out;
  for (std::size_t a = 0; a < count; ++a) {
    if (failures[a].empty()) {
      out.plausible.push_back(plausible[a]);
      out.at.push_back(std::move(predictions[a]));
    } else {
      out.message += (out.message.empty() ? "not predicted: " : "; ") + failures[a];
    }
  }
  return out;
}

// Whether `data` has a level at this slot within half a grid step of f0.
bool measured_already(const EdcDataset& data, const Slot& slot, double f0_n, double f0_step_n) {
  for (const EdcGroup& g : data.groups) {
    if (g.positive_well != slot.positive_well ||
        std::abs(g.freq_hz - slot.freq_hz) > 1e-6 * slot.freq_hz) {
      continue;
    }
    for (const MeasuredLevel& m : g.levels) {
      if (std::abs(m.f0_n - f0_n) < 0.5 * f0_step_n) return true;
    }
  }
  return false;
}

// Whether the operator skipped this setting (NextPointOptions::skipped).
bool skipped_already(const std::vector<NextPointOptions::Skipped>& skipped, const Slot& slot,
                     double f0_n, double f0_step_n) {
  return std::any_of(skipped.begin(), skipped.end(), [&](const NextPointOptions::Skipped& s) {
    return s.positive_well == slot.positive_well &&
           std::abs(s.freq_hz - slot.freq_hz) <= 1e-6 * slot.freq_hz &&
           std::abs(s.f0_n - f0_n) < 0.5 * f0_step_n;
  });
}

// Box–Hill's criterion of one admissible setting (docs in next_point.h), summed into `score`, with
// the pair and quantity that contribute most. `noise`: the variances s² of what a level measures.
class CriterionSum {
 public:
  explicit CriterionSum(SettingScore& score) : score_(score) {}

  // One pair's term in one quantity: mean and variance differences over what a measurement of
  // variance s2 would see.
  void add_pair(int i, int j, const char* quantity, double wij, double mu_i, double mu_j,
                double v_i, double v_j, double s2) {
    if (!(s2 > 0.0)) return;
    const double delta = mu_i - mu_j;
    const double half_bracket = 0.5 * ((v_i - v_j) * (v_i - v_j) / ((s2 + v_i) * (s2 + v_j)) +
                                       delta * delta * (1.0 / (s2 + v_i) + 1.0 / (s2 + v_j)));
    score_.criterion += wij * half_bracket;
    score_.pair_discrimination = std::max(score_.pair_discrimination, half_bracket);
    if (wij * half_bracket > best_term_) {
      best_term_ = wij * half_bracket;
      score_.pair_i = i;
      score_.pair_j = j;
      score_.quantity = quantity;
      score_.separation_sigma = std::abs(delta) / std::sqrt(s2 + v_i + v_j);
      score_.spread_sigma = std::sqrt(std::max(v_i, v_j) / s2);
      score_.uncertain = v_i >= v_j ? i : j;
    }
  }

  // One plausible model alone: its own prediction's variance v against what a level measures,
  // largest where the setting teaches its parameters most.
  void add_single(int i, const char* quantity, double v, double s2) {
    if (!(s2 > 0.0)) return;
    score_.criterion += v / s2;
    if (v / s2 > best_term_) {
      best_term_ = v / s2;
      score_.pair_i = score_.pair_j = i;
      score_.quantity = quantity;
      score_.separation_sigma = std::sqrt(v / s2);
    }
  }

 private:
  SettingScore& score_;
  double best_term_ = -1.0;
};

// The score of level k of slot s: not admissible where a plausible model's response jumps wells
// or is not predicted; otherwise the criterion at the measurement variances of the predictions'
// weighted mean.
void score_setting(SettingScore& score, const Predictions& p, std::size_t s, std::size_t k,
                   const std::vector<ModelHypothesis>& hypotheses, const MeasurementNoise& noise,
                   const NextPointOptions& options) {
  const auto weight = [&](int i) {
    return std::max(hypotheses[static_cast<std::size_t>(i)].weight, options.min_weight);
  };
  const std::size_t count = p.plausible.size();
  double weight_sum = 0.0, edc_mean = 0.0, z1_mean = 0.0;
  for (std::size_t a = 0; a < count; ++a) {
    const PredictedLevels& levels = p.at[a][s];
    const ModelHypothesis& h = hypotheses[static_cast<std::size_t>(p.plausible[a])];
    if (!levels.valid[k]) {
      score.admissible = false;
      score.why_not =
          h.label() + (levels.first_well_jump >= 0 && static_cast<int>(k) >= levels.first_well_jump
                           ? ": the response jumps wells"
                           : ": no prediction");
      return;
    }
    const double w = weight(p.plausible[a]);
    weight_sum += w;
    edc_mean += w * levels.edc_j[k];
    z1_mean += w * levels.z1_m[k];
  }
  edc_mean /= weight_sum;
  z1_mean /= weight_sum;
  const auto sq = [](double x) { return x * x; };
  const double var_edc = sq(edc_mean * std::hypot(kEdcEstimatorBiasRel, noise.edc_rel));
  const double var_z1 = sq(z1_mean * std::hypot(kAmplitudeBiasRel, noise.z1_rel));
  CriterionSum sum(score);
  if (count == 1) {
    const PredictedLevels& levels = p.at[0][s];
    sum.add_single(p.plausible[0], "EDC", sq(levels.edc_sigma_j[k]), var_edc);
    if (options.use_amplitude) {
      sum.add_single(p.plausible[0], "|Z1|", sq(levels.z1_sigma_m[k]), var_z1);
    }
  }
  for (std::size_t a = 0; a < count; ++a) {
    for (std::size_t b = a + 1; b < count; ++b) {
      const PredictedLevels& pa = p.at[a][s];
      const PredictedLevels& pb = p.at[b][s];
      const int i = p.plausible[a], j = p.plausible[b];
      const double wij = weight(i) * weight(j);
      sum.add_pair(i, j, "EDC", wij, pa.edc_j[k], pb.edc_j[k], sq(pa.edc_sigma_j[k]),
                   sq(pb.edc_sigma_j[k]), var_edc);
      if (options.use_amplitude) {
        sum.add_pair(i, j, "|Z1|", wij, pa.z1_m[k], pb.z1_m[k], sq(pa.z1_sigma_m[k]),
                     sq(pb.z1_sigma_m[k]), var_z1);
      }
    }
  }
  score.criterion_per_s = score.criterion / score.shaker_s;
}

// The proposal in words: the pair and quantity that contribute most at the best setting.
std::string proposal_reason(const SettingScore& b, const std::vector<ModelHypothesis>& hypotheses) {
  const auto label = [&](int i) { return hypotheses[static_cast<std::size_t>(i)].label(); };
  char text[600];
  const char* well = b.positive_well ? "positive" : "negative";
  if (b.pair_i == b.pair_j) {
    std::snprintf(text, sizeof text,
                  "only %s is plausible; its %s is least certain (%.1f sigma of a measurement) at "
                  "%.2f N, %.2f Hz, %s well",
                  label(b.pair_i).c_str(), b.quantity.c_str(), b.separation_sigma, b.f0_n,
                  b.freq_hz, well);
  } else if (b.separation_sigma >= 1.0 || b.spread_sigma < 1.0) {
    std::snprintf(text, sizeof text,
                  "%s vs %s differ by %.1f sigma in %s at %.2f N, %.2f Hz, %s well",
                  label(b.pair_i).c_str(), label(b.pair_j).c_str(), b.separation_sigma,
                  b.quantity.c_str(), b.f0_n, b.freq_hz, well);
  } else {
    // The means agree; the spread of one model's prediction is what a level would settle.
    const int other = b.uncertain == b.pair_i ? b.pair_j : b.pair_i;
    std::snprintf(text, sizeof text,
                  "%s vs %s agree within %.1f sigma in %s at %.2f N, %.2f Hz, %s well, but %s's "
                  "prediction there is uncertain to %.1f sigma: a level would show its effect or "
                  "rule it out",
                  label(b.uncertain).c_str(), label(other).c_str(), b.separation_sigma,
                  b.quantity.c_str(), b.f0_n, b.freq_hz, well, label(b.uncertain).c_str(),
                  b.spread_sigma);
  }
  return text;
}

}  // namespace

NextPoint propose_next_point(const std::vector<ModelHypothesis>& hypotheses,
                             const AdmissibleSettings& settings, const NextPointOptions& options,
                             const ProgressFn& progress, const CancelToken& cancel) {
  settings.validate();
  NextPoint out;
  out.plausible = plausible_hypotheses(hypotheses, options);
  if (out.plausible.empty()) {
    out.status = JobStatus::InvalidInput;
    out.message = "no solved hypothesis to predict";
    return out;
  }
  const std::vector<double> f0 = settings.f0_grid();
  std::vector<Slot> slots;
  for (bool positive : {true, false}) {
    if (positive ? !settings.positive_well : !settings.negative_well) continue;
    for (double freq : settings.freq_grid()) slots.push_back({positive, freq});
  }
  const Predictions predictions =
      predict_plausible(hypotheses, out.plausible, slots, f0, options, progress, cancel);
  out.message = predictions.message;
  if (predictions.plausible.empty() && !cancel.cancelled()) {
    out.status = JobStatus::NumericalIssue;
    return out;
  }
  out.plausible = predictions.plausible;
  if (cancel.cancelled()) {
    out.status = JobStatus::Cancelled;
    out.message = "cancelled";
    return out;
  }
  const EdcDataset& data =
      hypotheses[static_cast<std::size_t>(out.plausible.front())].objective->data();
  const MeasurementNoise noise = typical_noise(data);
  for (std::size_t s = 0; s < slots.size(); ++s) {
    for (std::size_t k = 0; k < f0.size(); ++k) {
      SettingScore score;
      score.f0_n = f0[k];
      score.freq_hz = slots[s].freq_hz;
      score.positive_well = slots[s].positive_well;
      score.shaker_s =
          settings.dwell_s + settings.settling_s +
          (slots[s].positive_well != settings.current_positive_well ? settings.well_change_s : 0.0);
      score.admissible = true;
      if (!options.repeat_measured && measured_already(data, slots[s], f0[k], settings.f0_step_n)) {
        score.admissible = false;
        score.why_not = "measured already";
      } else if (skipped_already(options.skipped, slots[s], f0[k], settings.f0_step_n)) {
        score.admissible = false;
        score.why_not = "skipped by the operator";
      } else {
        score_setting(score, predictions, s, k, hypotheses, noise, options);
      }
      if (score.admissible) {
        out.max_discrimination = std::max(out.max_discrimination, score.pair_discrimination);
        if (!out.found || score.criterion_per_s > out.best.criterion_per_s) {
          out.found = true;
          out.best = score;
        }
      }
      out.settings.push_back(score);
    }
  }
  if (!out.found) {
    out.message = "no admissible setting: every one jumps wells or is not predicted";
    out.reason = out.message;
    return out;
  }
  out.reason = proposal_reason(out.best, hypotheses);
  return out;
}

}  // namespace oscilab::analysis
