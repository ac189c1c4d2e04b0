#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/model/coulomb_friction.h"
#include "analysis/model/dahl_friction.h"
#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/velocity_power_damping.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::analysis::testing {

/// A hidden effect of the test campaign: the truth is the paper's model plus this term (or the
/// paper's model alone for the control, effect "none").
struct HiddenEffect {
  std::string effect;
  std::unique_ptr<ModelTerm> term;  // nullptr: the control
};

/// The effects of the first hidden-effect campaign, each strong enough to leave a misfit of several
/// σ at some level when the paper's form is fitted (checked by the tests through the baseline).
inline std::vector<HiddenEffect> hidden_effects() {
  std::vector<HiddenEffect> out;
  out.push_back({"presliding-hysteresis", std::make_unique<DahlFriction>(0.06, 3e3)});
  out.push_back({"quadratic-damping", std::make_unique<VelocityPowerDamping>(2, 6.0)});
  out.push_back({"cubic-damping", std::make_unique<VelocityPowerDamping>(3, 60.0)});
  out.push_back({"stribeck-friction", std::make_unique<StribeckFriction>(0.1, 5e-3)});
  out.push_back({"quintic-stiffness", std::make_unique<PolynomialStiffness>(
                                          std::vector<double>{0.0, 0.0, 0.0, 0.0, 0.0, 1.2e7})});
  out.push_back({"none", nullptr});
  return out;
}

/// Outside the vocabulary: viscous damping that engages only beyond z_s, c (z − z_s)² ż (a
/// damper a test builds, no term of Oscilab's).
class OneSidedDamper final : public ModelTerm {
 public:
  OneSidedDamper(double c_ns_m3, double z_s_m) : c_(c_ns_m3), z_s_(z_s_m) {}
  std::string type() const override { return "one-sided-damper"; }
  TermKind kind() const override { return TermKind::Dissipative; }
  double force(double z, double v, const double*) const override {
    const double d = std::max(0.0, z - z_s_);
    return c_ * d * d * v;
  }
  TermPartials partials(double z, double v, const double*) const override {
    const double d = std::max(0.0, z - z_s_);
    return {2.0 * c_ * d * v, c_ * d * d};
  }
  std::vector<std::string> parameter_names() const override { return {}; }
  double parameter(const std::string& name) const override {
    throw InputError("one-sided-damper: no parameter " + name);
  }
  void set_parameter(const std::string& name, double) override {
    throw InputError("one-sided-damper: no parameter " + name);
  }
  nlohmann::json to_json() const override { return {{"type", type()}}; }
  std::unique_ptr<ModelTerm> clone() const override {
    return std::make_unique<OneSidedDamper>(*this);
  }

 private:
  double c_, z_s_;
};

/// The paper's model with its friction in the presliding regime of length δ (eqs. (5)–(6), the
/// Coulomb part a Dahl state of the contact).
inline Model paper_with_presliding(double length_m, const Model& base = paper_model()) {
  Model model = base;
  for (std::size_t i = 0; i < model.terms().size(); ++i) {
    if (model.terms()[i]->type() == "position-dependent-friction") {
      model.set_parameter(i, "presliding_length_m", length_m);
    }
  }
  return model;
}

/// The paper's model plus `effect` at `scale` × its reference strength (the campaign's strengths
/// above; stiffness powers at 10 % of k2 and 5 % of k3 of Table 1 for c2 and c3). The scale
/// multiplies the term's force (F_c, f_s, c_p) and keeps its shape (presliding length, v_s).
/// Several effects hidden together: their names joined by '+' ("presliding-hysteresis+
/// quadratic-damping"), each at `scale`.
inline Model truth_with_effect(const std::string& effect, double scale,
                               const Model& base = paper_model()) {
  Model model = base;
  if (const std::size_t plus = effect.find('+'); plus != std::string::npos) {
    Model first = truth_with_effect(effect.substr(0, plus), scale, base);
    const Model rest = truth_with_effect(effect.substr(plus + 1), scale, base);
    for (std::size_t i = model.terms().size(); i < rest.terms().size(); ++i) {
      first.add_term(rest.terms()[i]->clone());
    }
    return first;
  }
  if (effect == "presliding-regime") {
    // The friction's own presliding regime: `scale` is δ in µm (a length, not a strength).
    return paper_with_presliding(1e-6 * scale, base);
  }
  if (effect == "one-sided-damper") {
    // Outside the vocabulary: c (z − z₊*)² ż beyond the positive well, c = 2e6 N s/m³ × scale.
    model.add_term(std::make_unique<OneSidedDamper>(2e6 * scale, model.well(true).z_m));
    return model;
  }
  if (effect == "presliding-hysteresis") {
    model.add_term(std::make_unique<DahlFriction>(0.06 * scale, 3e3 * scale));
  } else if (effect == "quadratic-damping") {
    model.add_term(std::make_unique<VelocityPowerDamping>(2, 6.0 * scale));
  } else if (effect == "cubic-damping") {
    model.add_term(std::make_unique<VelocityPowerDamping>(3, 60.0 * scale));
  } else if (effect == "stribeck-friction") {
    model.add_term(std::make_unique<StribeckFriction>(0.1 * scale, 5e-3));
  } else if (effect == "coulomb-friction") {
    model.add_term(std::make_unique<CoulombFriction>(0.05 * scale, 1e-3));
  } else if (effect == "quadratic-stiffness") {
    model.add_term(std::make_unique<PolynomialStiffness>(std::vector<double>{0, 0, 156.0 * scale}));
  } else if (effect == "cubic-stiffness") {
    model.add_term(
        std::make_unique<PolynomialStiffness>(std::vector<double>{0, 0, 0, 3.7e4 * scale}));
  } else if (effect == "quintic-stiffness") {
    model.add_term(
        std::make_unique<PolynomialStiffness>(std::vector<double>{0, 0, 0, 0, 0, 1.2e7 * scale}));
  } else if (effect != "none") {
    throw InputError("unknown hidden effect \"" + effect + "\"");
  }
  return model;
}

inline Model truth_with(const HiddenEffect& hidden) {
  Model model = paper_model();
  if (hidden.term) model.add_term(hidden.term->clone());
  return model;
}

/// How a campaign is recorded: the forcing frequency, the sensor noise as a multiple of the
/// rig's default (accelerometer and vibrometer noise alike), and whether a random record joins.
struct CampaignSpec {
  double freq_hz = 9.0;
  double noise_scale = 1.0;
  bool random_record = true;
};

/// The stepped recordings as the rig makes them (both wells), with the truth beside them.
inline std::vector<daq::RigRecording> record_stepped(const Model& truth, std::uint64_t seed,
                                                     const std::vector<double>& levels,
                                                     const CampaignSpec& campaign = {}) {
  SteppedSineSchedule schedule;
  schedule.levels_n = levels;
  schedule.frequency_hz = campaign.freq_hz;
  std::vector<daq::RigRecording> out;
  for (bool positive : {true, false}) {
    daq::RigSpec spec;
    spec.positive_well = positive;
    spec.seed = seed * 10 + (positive ? 1 : 2);
    spec.sensors.accelerometer.noise_rms_m_s2 *= campaign.noise_scale;
    spec.sensors.vibrometer.noise_rms_m *= campaign.noise_scale;
    out.push_back(daq::record_stepped_sine(truth, schedule, spec));
  }
  return out;
}

/// The campaign as the lab records it with the virtual rig (sensor bias, noise, quantisation,
/// creep): stepped sines over `levels` at the campaign's frequency in both wells (10 s holds) and
/// a random record (2–30 Hz, 2 N rms, 60 s) that crosses the wells, analysed by the project's
/// pipeline.
inline CampaignAnalysis record_campaign(const Model& truth, std::uint64_t seed,
                                        const std::vector<double>& levels,
                                        const CampaignSpec& campaign = {}) {
  std::vector<MeasurementChannels> records;
  for (const daq::RigRecording& rig : record_stepped(truth, seed, levels, campaign)) {
    records.push_back(daq::measurement_channels(rig.recording));
    records.back().name = records.size() == 1 ? "stepped_positive" : "stepped_negative";
  }
  if (campaign.random_record) {
    daq::RigSpec spec;
    spec.seed = seed * 10 + 3;
    spec.sensors.accelerometer.noise_rms_m_s2 *= campaign.noise_scale;
    spec.sensors.vibrometer.noise_rms_m *= campaign.noise_scale;
    RandomMotionSpec random;
    random.duration_s = 60.0;
    random.force_rms_n = 2.0;
    random.seed = seed * 10 + 3;
    const daq::RigRecording rig = daq::record_random(truth, random, spec);
    records.push_back(daq::measurement_channels(rig.recording));
    records.back().name = "random";
  }
  return analyze_campaign(records, PipelineSettings{});
}

}  // namespace oscilab::analysis::testing
