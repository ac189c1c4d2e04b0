#pragma once

#include <cstdint>
#include <random>

namespace oscilab::daq {

/// Piezo accelerometer on the table, sampled by a 24-bit DAQ: bias, white noise and quantisation.
struct AccelerometerSpec {
  double bias_m_s2 = 4e-3;       // a few mm/s² of offset (thermal, mounting, DAQ offset)
  double noise_rms_m_s2 = 2e-3;  // white, over the sampled band
  double lsb_m_s2 = 3e-5;        // ±250 m/s² over 24 bits
};

/// Laser vibrometer (displacement output) on the moving mass: white noise and quantisation.
struct VibrometerSpec {
  double noise_rms_m = 1.5e-6;
  double lsb_m = 1e-7;
};

/// Slow creep of the table, seen by the vibrometer (y includes it) but not by the accelerometer
/// (its acceleration is ~1e-9 m/s², far below the accelerometer's noise).
struct TableCreepSpec {
  double amplitude_m = 3e-6;  // peak of each of the three slow components
  double min_period_s = 30.0;
  double max_period_s = 300.0;
};

/// The measurement chain of the virtual rig; zero noise and lsb give ideal sensors.
struct SensorSpec {
  AccelerometerSpec accelerometer;
  VibrometerSpec vibrometer;
  TableCreepSpec creep;
};

/// Rounds to the nearest multiple of lsb (no-op for lsb ≤ 0): an ideal mid-tread quantiser.
double quantise(double value, double lsb);

/// Creep c(t) = Σ a_i [sin(ω_i t + φ_i) − sin φ_i], zero at t = 0; periods and phases drawn from
/// the generator.
class TableCreep {
 public:
  TableCreep(const TableCreepSpec& spec, std::mt19937_64& rng);
  double at(double t_s) const;

 private:
  double amplitude_m_[3] = {};
  double omega_[3] = {};
  double phase_[3] = {};
};

/// The rig's two sensors read at one instant: the accelerometer's b̈ + bias + noise and the
/// vibrometer's y = z + b + creep + noise, each quantised to its lsb. Draws from the generator in
/// a fixed order (creep phases at construction, then the two noises per sample), so a seed
/// reproduces a recording.
class SensorChain {
 public:
  struct Reading {
    double base_acc_m_s2 = 0.0;
    double y_m = 0.0;
  };
  SensorChain(const SensorSpec& spec, std::mt19937_64& rng);
  Reading read(double t_s, double b_m, double b_ddot_m_s2, double z_m);

 private:
  SensorSpec spec_;
  std::mt19937_64& rng_;
  TableCreep creep_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
};

}  // namespace oscilab::daq
