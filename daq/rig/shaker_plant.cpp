#include "daq/rig/shaker_plant.h"

#include <cmath>
#include <numbers>

#include "analysis/common/input_error.h"

namespace oscilab::daq {
namespace {

bool positive_and_finite(double value) { return std::isfinite(value) && value > 0.0; }

}  // namespace

std::string ShakerSpec::validate() const {
  if (!positive_and_finite(table_mass_kg)) return "table mass: must be positive";
  if (!positive_and_finite(suspension_hz)) return "suspension frequency: must be positive";
  if (!std::isfinite(suspension_damping_ratio) || suspension_damping_ratio < 0.0) {
    return "suspension damping ratio: must be zero or positive";
  }
  if (!positive_and_finite(force_n_per_fs)) return "force per full scale: must be positive";
  return "";
}

ShakerPlant::ShakerPlant(const analysis::Model& model, bool positive_well, const ShakerSpec& shaker,
                         const SensorSpec& sensors, double sample_rate_hz, int substeps,
                         std::uint64_t seed)
    : model_(model), shaker_(shaker), rng_(seed), sensors_(sensors, rng_) {
  if (const std::string why = shaker_.validate(); !why.empty()) {
    throw InputError("shaker: " + why);
  }
  if (!positive_and_finite(sample_rate_hz))
    throw InputError("plant: the sample rate must be positive");
  if (substeps < 1 || substeps > 1000) throw InputError("plant: substeps must be 1 to 1000");
  const double omega_s = 2.0 * std::numbers::pi * shaker_.suspension_hz;
  k_s_n_m_ = shaker_.table_mass_kg * omega_s * omega_s;
  c_s_ns_m_ = 2.0 * shaker_.suspension_damping_ratio * shaker_.table_mass_kg * omega_s;
  dt_s_ = 1.0 / sample_rate_hz;
  substeps_ = substeps;
  const double z0_m = model_.well(positive_well).z_m;
  const std::size_t size = kInternal + static_cast<std::size_t>(model_.state_size());
  x_.assign(size, 0.0);
  x_[kZ] = z0_m;
  const std::vector<double> internal = model_.initial_state(z0_m);
  for (std::size_t i = 0; i < internal.size(); ++i) x_[kInternal + i] = internal[i];
  k1_.assign(size, 0.0);
  k2_ = k3_ = k4_ = trial_ = k1_;
}

double ShakerPlant::rate(const std::vector<double>& x, double drive_fs,
                         std::vector<double>& dx) const {
  const double* internal = model_.state_size() > 0 ? x.data() + kInternal : nullptr;
  const double restoring_n = model_.restoring_force(x[kZ], x[kZDot], internal);
  const double table_acc_m_s2 =
      (shaker_.force_n_per_fs * drive_fs - k_s_n_m_ * x[kB] - c_s_ns_m_ * x[kBDot] + restoring_n) /
      shaker_.table_mass_kg;
  dx[kB] = x[kBDot];
  dx[kBDot] = table_acc_m_s2;
  dx[kZ] = x[kZDot];
  dx[kZDot] = -table_acc_m_s2 - restoring_n / model_.mass_kg();  // eq. (1)
  if (internal != nullptr) model_.state_rate(x[kZ], x[kZDot], internal, dx.data() + kInternal);
  return table_acc_m_s2;
}

SensorChain::Reading ShakerPlant::step(double drive_fs) {
  const double h = dt_s_ / substeps_;
  const std::size_t n = x_.size();
  for (int s = 0; s < substeps_; ++s) {
    rate(x_, drive_fs, k1_);
    for (std::size_t i = 0; i < n; ++i) trial_[i] = x_[i] + 0.5 * h * k1_[i];
    rate(trial_, drive_fs, k2_);
    for (std::size_t i = 0; i < n; ++i) trial_[i] = x_[i] + 0.5 * h * k2_[i];
    rate(trial_, drive_fs, k3_);
    for (std::size_t i = 0; i < n; ++i) trial_[i] = x_[i] + h * k3_[i];
    rate(trial_, drive_fs, k4_);
    for (std::size_t i = 0; i < n; ++i) {
      x_[i] += h / 6.0 * (k1_[i] + 2.0 * k2_[i] + 2.0 * k3_[i] + k4_[i]);
    }
  }
  t_s_ += dt_s_;
  table_acceleration_m_s2_ = rate(x_, drive_fs, k1_);
  return sensors_.read(t_s_, x_[kB], table_acceleration_m_s2_, x_[kZ]);
}

}  // namespace oscilab::daq
