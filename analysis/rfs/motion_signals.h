#pragma once

#include <Eigen/Core>

#include "analysis/pipeline/measurement_channels.h"
#include "analysis/pipeline/pipeline_settings.h"

namespace oscilab::analysis {

/// Relative motion and restoring force of a record in the time domain (§3): z = y − b, ż and
/// R = f − m z̈ with f = −m b̈ (eq. (1)), all through the same zero-phase band (SpectralRecord:
/// high-pass only where a channel is integrated, low-pass at derivative_lowpass_hz everywhere),
/// so the terms of R are consistent with each other. R = −m (b̈ + z̈) = −m ÿ: with an absolute
/// mass channel R needs no integration of b̈ at all, and it is computed that way, in one
/// inverse transform.
struct MotionSignals {
  Eigen::VectorXd t_s, z_m, z_dot_m_s, restoring_force_n;
  bool z_absolute = true;  // false: z's mean is unknown (mass measured as velocity/acceleration)
};

MotionSignals motion_signals(const MeasurementChannels& channels, const PipelineSettings& settings,
                             double mass_kg);

/// The excitation force f = −m b̈ of eq. (1) at every sample (N, or N/kg without mass_kg),
/// through the zero-phase band of motion_signals (low-pass at derivative_lowpass_hz,
/// high-pass only where b is integrated), so that it lines up in phase with z = y − b.
Eigen::VectorXd excitation_force(const MeasurementChannels& channels,
                                 const PipelineSettings& settings);

}  // namespace oscilab::analysis
