#pragma once

#include <random>
#include <string>
#include <vector>

#include "analysis/model/model.h"
#include "daq/rig/sensor_models.h"

namespace oscilab::daq {

/// An electrodynamic shaker as a plant for the drive: a table of mass M_t on a suspension of
/// natural frequency f_s and damping ratio ζ, pushed by a force proportional to the drive
/// (amplifier and coil, F = k_f u with u in the drive's full-scale units).
struct ShakerSpec {
  double table_mass_kg = 8.0;
  double suspension_hz = 3.0;
  double suspension_damping_ratio = 0.1;
  double force_n_per_fs = 300.0;

  /// "" or what is wrong, naming the field.
  std::string validate() const;
};

/// The shaker with the oscillator on its table, integrated sample by sample as a real rig
/// responds to a DAC (the drive held over each sample): the table feels the oscillator's
/// reaction, so the table acceleration per unit of drive changes with the oscillator's response
/// (what makes the drive a closed-loop problem).
///
///   M_t b̈ = k_f u − k_s b − c_s ḃ + R(z, ż, s),   k_s = M_t (2π f_s)², c_s = 2ζ M_t 2π f_s
///   m z̈ + R(z, ż, s) = −m b̈                        (eq. (1), f = −m b̈)
///   ṡ = the model terms' state rates
///
/// by classical Runge–Kutta (RK4) with `substeps` steps per sample. The sensors read the state at
/// the end of each sample through the virtual rig's sensor chain (bias, noise, creep,
/// quantisation). Starts at rest in the chosen well.
///
/// Real-time safe after construction (no allocation in step()). Holds a copy of the model. Not
/// thread-safe.
class ShakerPlant {
 public:
  /// Throws InputError naming the field when the shaker, the rate or the substeps are invalid,
  /// or the model has no such well.
  ShakerPlant(const analysis::Model& model, bool positive_well, const ShakerSpec& shaker,
              const SensorSpec& sensors, double sample_rate_hz, int substeps, std::uint64_t seed);

  /// Advances one sample with the drive `drive_fs` held over it; returns the sensors' reading.
  SensorChain::Reading step(double drive_fs);

  double time_s() const { return t_s_; }
  double table_m() const { return x_[kB]; }
  double table_acceleration_m_s2() const { return table_acceleration_m_s2_; }
  double z_m() const { return x_[kZ]; }
  double z_dot_m_s() const { return x_[kZDot]; }

 private:
  static constexpr std::size_t kB = 0, kBDot = 1, kZ = 2, kZDot = 3, kInternal = 4;
  /// dx/dt at state x under drive u; returns b̈.
  double rate(const std::vector<double>& x, double drive_fs, std::vector<double>& dx) const;

  analysis::Model model_;
  ShakerSpec shaker_;
  double k_s_n_m_, c_s_ns_m_;
  double dt_s_;
  int substeps_;
  double t_s_ = 0.0;
  std::vector<double> x_, k1_, k2_, k3_, k4_, trial_;
  double table_acceleration_m_s2_ = 0.0;
  std::mt19937_64 rng_;
  SensorChain sensors_;
};

}  // namespace oscilab::daq
