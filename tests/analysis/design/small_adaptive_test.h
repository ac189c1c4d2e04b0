#pragma once
// The adaptive test small enough for the unit and GUI suites, shared by their tests.

#include <memory>

#include "analysis/design/adaptive_test.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/velocity_power_damping.h"

namespace oscilab::testing {

/// The rig's truth: the paper's model with a quadratic damping (c2 = 6 N s²/m²) hidden in it.
inline analysis::Model quadratic_damping_truth() {
  analysis::Model m = analysis::paper_model();
  m.add_term(std::make_unique<analysis::VelocityPowerDamping>(2, 6.0));
  return m;
}

/// Two pilot levels per well, one candidate, short fits, at most two adaptive levels, no final
/// diagnosis; dwell 6 s, settling 2.5 s, a change of well 10 s.
inline analysis::AdaptiveTestOptions small_adaptive_test_options() {
  analysis::AdaptiveTestOptions o;
  o.settings.dwell_s = 6.0;
  o.settings.settling_s = 2.5;
  o.settings.well_change_s = 10.0;
  o.settings.f0_step_n = 0.5;
  o.pilot_levels_n = {0.5, 1.5};
  o.max_levels = 2;
  o.hypotheses.effects = {"quadratic-damping"};
  o.hypotheses.global_evaluations = 0;
  o.hypotheses.initial_evaluations = 40;
  o.hypotheses.refit_evaluations = 20;
  o.hypotheses.threads = 2;
  o.next.threads = 2;
  o.final_diagnosis = false;
  return o;
}

}  // namespace oscilab::testing
