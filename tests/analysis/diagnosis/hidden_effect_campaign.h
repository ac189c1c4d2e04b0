#pragma once

#include <memory>
#include <string>
#include <vector>

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

/// The effects of the issue-9 campaign, each strong enough to leave a misfit of several σ at
/// some level when the paper's form is fitted (checked by the tests through the baseline).
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

inline Model truth_with(const HiddenEffect& hidden) {
  Model model = paper_model();
  if (hidden.term) model.add_term(hidden.term->clone());
  return model;
}

/// The campaign as the lab records it with the virtual rig (sensor bias, noise, quantisation,
/// creep): stepped sines 0.2 → 2.7 N at 9 Hz in both wells (`levels`, 10 s holds) and a random
/// record (2–30 Hz, 2 N rms, 60 s) that crosses the wells, analysed by the project's pipeline.
inline CampaignAnalysis record_campaign(const Model& truth, std::uint64_t seed,
                                        const std::vector<double>& levels) {
  SteppedSineSchedule schedule;
  schedule.levels_n = levels;
  std::vector<MeasurementChannels> records;
  for (bool positive : {true, false}) {
    daq::RigSpec spec;
    spec.positive_well = positive;
    spec.seed = seed * 10 + (positive ? 1 : 2);
    const daq::RigRecording rig = daq::record_stepped_sine(truth, schedule, spec);
    records.push_back(daq::measurement_channels(rig.recording));
    records.back().name = positive ? "stepped_positive" : "stepped_negative";
  }
  daq::RigSpec spec;
  spec.seed = seed * 10 + 3;
  RandomMotionSpec random;
  random.duration_s = 60.0;
  random.force_rms_n = 2.0;
  random.seed = seed * 10 + 3;
  const daq::RigRecording rig = daq::record_random(truth, random, spec);
  records.push_back(daq::measurement_channels(rig.recording));
  records.back().name = "random";
  return analyze_campaign(records, PipelineSettings{});
}

}  // namespace oscilab::analysis::testing
