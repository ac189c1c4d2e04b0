#include "analysis/rfs/motion_signals.h"

#include <algorithm>

#include "analysis/signal/spectral_calculus.h"

namespace oscilab::analysis {
MotionSignals motion_signals(const MeasurementChannels& channels, const PipelineSettings& settings,
                             double mass_kg) {
  const double rate = channels.sample_rate_hz;
  const int base_order = derivative_order(channels.base_quantity);
  const int mass_order = derivative_order(channels.mass_quantity);
  // The same band for every term: low-pass everywhere (inside Nyquist: its taper ends at 1.25×
  // the cut-off), high-pass where a channel is integrated.
  const auto band = [&](int measured, int target) {
    SpectralOptions options;
    options.lowpass_hz = std::min(settings.derivative_lowpass_hz, 0.35 * rate);
    if (target < measured) options.highpass_hz = settings.integration_highpass_hz;
    return options;
  };
  // Two forward transforms, then one inverse for each of z, ż, z̈ (= y − b in each order) and b̈.
  const SpectralRecord mass(channels.mass, rate);
  const SpectralRecord base(channels.base, rate);
  MotionSignals s;
  const Eigen::Index n = channels.base.size();
  s.t_s = Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1) / rate);
  Eigen::VectorXd relative[3];
  SpectralRecord::Spectrum spectrum;
  for (int order = 0; order < 3; ++order) {
    mass.clear(spectrum);
    mass.accumulate(spectrum, 1.0, order - mass_order, band(mass_order, order));
    if (!channels.mass_is_relative) {
      base.accumulate(spectrum, -1.0, order - base_order, band(base_order, order));
    }
    relative[order] = mass.inverse(spectrum);
  }
  base.clear(spectrum);
  base.accumulate(spectrum, -mass_kg, 2 - base_order, band(base_order, 2));  // eq. (1): f = −m b̈
  s.f_n = base.inverse(spectrum);
  s.z_m = std::move(relative[0]);
  s.z_dot_m_s = std::move(relative[1]);
  s.z_ddot_m_s2 = std::move(relative[2]);
  s.restoring_force_n = s.f_n - mass_kg * s.z_ddot_m_s2;  // eq. (1): R = f − m z̈
  s.z_absolute = mass_order == 0;
  return s;
}

}  // namespace oscilab::analysis
