#pragma once

#include <Eigen/Core>

#include "analysis/pipeline/measurement_channels.h"
#include "analysis/pipeline/pipeline_settings.h"

namespace oscilab::analysis {

/// Relative motion and forces of a record in the time domain (§3): z = y − b, ż, z̈, the force
/// f = −m b̈ and the restoring force R = f − m z̈ (eq. (1)), all through the same zero-phase band
/// (spectral_derivative: high-pass only where a channel is integrated, low-pass at
/// derivative_lowpass_hz everywhere), so the terms of R are consistent with each other.
/// Note R = −m ÿ when the mass channel is absolute: R needs no integration of b̈ at all.
struct MotionSignals {
  Eigen::VectorXd t_s, z_m, z_dot_m_s, z_ddot_m_s2, f_n, restoring_force_n;
  bool z_absolute = true;  // false: z's mean is unknown (mass measured as velocity/acceleration)
};

MotionSignals motion_signals(const MeasurementChannels& channels, const PipelineSettings& settings,
                             double mass_kg);

}  // namespace oscilab::analysis
