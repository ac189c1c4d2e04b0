#include "daq/rig/sensor_models.h"

#include <cmath>
#include <numbers>

namespace oscilab::daq {

double quantise(double value, double lsb) {
  return lsb > 0.0 ? std::round(value / lsb) * lsb : value;
}

TableCreep::TableCreep(const TableCreepSpec& spec, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> log_period(std::log(spec.min_period_s),
                                                    std::log(spec.max_period_s));
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
  for (int i = 0; i < 3; ++i) {
    amplitude_m_[i] = spec.amplitude_m;
    omega_[i] = 2.0 * std::numbers::pi / std::exp(log_period(rng));
    phase_[i] = phase(rng);
  }
}

double TableCreep::at(double t_s) const {
  double c = 0.0;
  for (int i = 0; i < 3; ++i) {
    c += amplitude_m_[i] * (std::sin(omega_[i] * t_s + phase_[i]) - std::sin(phase_[i]));
  }
  return c;
}

SensorChain::SensorChain(const SensorSpec& spec, std::mt19937_64& rng)
    : spec_(spec), rng_(rng), creep_(spec.creep, rng) {}

SensorChain::Reading SensorChain::read(double t_s, double b_m, double b_ddot_m_s2, double z_m) {
  const auto& a = spec_.accelerometer;
  const auto& v = spec_.vibrometer;
  const double acc = b_ddot_m_s2 + a.bias_m_s2 + a.noise_rms_m_s2 * unit_normal_(rng_);
  const double y = z_m + b_m + creep_.at(t_s) + v.noise_rms_m * unit_normal_(rng_);
  return {quantise(acc, a.lsb_m_s2), quantise(y, v.lsb_m)};
}

}  // namespace oscilab::daq
