#include "analysis/rfs/motion_signals.h"
#include "analysis/model/excitation_force.h"

#include <algorithm>
#include <cmath>

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
  // Two forward transforms, then one inverse for each of z, ż (= y − b in each order) and R.
  const SpectralRecord mass(channels.mass, rate);
  const SpectralRecord base(channels.base, rate);
  MotionSignals s;
  const Eigen::Index n = channels.base.size();
  s.t_s = Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1) / rate);
  SpectralRecord::Spectrum spectrum;
  // The relative motion of a given order: y − b, or the mass channel itself when it measures z.
  const auto relative = [&](int order) {
    mass.clear(spectrum);
    mass.accumulate(spectrum, 1.0, order - mass_order, band(mass_order, order));
    if (!channels.mass_is_relative) {
      base.accumulate(spectrum, -1.0, order - base_order, band(base_order, order));
    }
    return mass.inverse(spectrum);
  };
  s.z_m = relative(0);
  s.z_dot_m_s = relative(1);
  // Eq. (1): R = f − m z̈ = −m (b̈ + z̈), which for an absolute mass channel is −m ÿ.
  mass.clear(spectrum);
  mass.accumulate(spectrum, -mass_kg, 2 - mass_order, band(mass_order, 2));
  if (channels.mass_is_relative) {
    base.accumulate(spectrum, -mass_kg, 2 - base_order, band(base_order, 2));
  }
  s.restoring_force_n = mass.inverse(spectrum);
  s.z_absolute = mass_order == 0;
  return s;
}

Eigen::VectorXd excitation_force(const MeasurementChannels& channels,
                                 const PipelineSettings& settings) {
  const double rate_hz = channels.sample_rate_hz;
  const double mass_kg = channels.mass_kg.value_or(1.0);
  const int measured = derivative_order(channels.base_quantity);
  // motion_signals' band for a second derivative: low-pass inside Nyquist (its taper ends at
  // 1.25× the cut-off); b̈ is never an integral of the base channel, so no high-pass.
  SpectralOptions options;
  options.lowpass_hz = std::min(settings.derivative_lowpass_hz, 0.35 * rate_hz);
  // Samples of invalid intervals may be non-finite; a zero keeps the transform finite. The
  // analysis leaves the restoring force out around them (non-finite R), and so do the loops.
  Eigen::VectorXd base = channels.base;
  for (Eigen::Index i = 0; i < base.size(); ++i) {
    if (!std::isfinite(base[i])) base[i] = 0.0;
  }
  return excitation_force_n(mass_kg, spectral_derivative(base, rate_hz, 2 - measured, options));
}

}  // namespace oscilab::analysis
