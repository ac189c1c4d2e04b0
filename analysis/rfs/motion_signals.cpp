#include "analysis/rfs/motion_signals.h"

#include <algorithm>

#include "analysis/signal/spectral_calculus.h"

namespace oscilab::analysis {
namespace {

// The displacement-order `target` (0, 1, 2) of a channel measured at order `measured`.
Eigen::VectorXd to_order(const Eigen::VectorXd& x, int measured, int target, double rate_hz,
                         const PipelineSettings& settings) {
  SpectralOptions options;
  // The low-pass band must fit below Nyquist (its taper ends at 1.25 × the cut-off).
  options.lowpass_hz = std::min(settings.derivative_lowpass_hz, 0.35 * rate_hz);
  if (target < measured) options.highpass_hz = settings.integration_highpass_hz;
  return spectral_derivative(x, rate_hz, target - measured, options);
}

}  // namespace

MotionSignals motion_signals(const MeasurementChannels& channels, const PipelineSettings& settings,
                             double mass_kg) {
  const double rate = channels.sample_rate_hz;
  const int base_order = derivative_order(channels.base_quantity);
  const int mass_order = derivative_order(channels.mass_quantity);
  MotionSignals s;
  const Eigen::Index n = channels.base.size();
  s.t_s = Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1) / rate);
  Eigen::VectorXd relative[3];
  Eigen::VectorXd base_acc;
  for (int order = 0; order < 3; ++order) {
    Eigen::VectorXd y = to_order(channels.mass, mass_order, order, rate, settings);
    if (channels.mass_is_relative) {
      relative[order] = std::move(y);
    } else {
      relative[order] = y - to_order(channels.base, base_order, order, rate, settings);
    }
  }
  base_acc = to_order(channels.base, base_order, 2, rate, settings);
  s.z_m = std::move(relative[0]);
  s.z_dot_m_s = std::move(relative[1]);
  s.z_ddot_m_s2 = std::move(relative[2]);
  s.f_n = -mass_kg * base_acc;                            // eq. (1): f = −m b̈
  s.restoring_force_n = s.f_n - mass_kg * s.z_ddot_m_s2;  // eq. (1): R = f − m z̈
  s.z_absolute = mass_order == 0;
  return s;
}

}  // namespace oscilab::analysis
