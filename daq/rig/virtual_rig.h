#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/common/job.h"
#include "analysis/model/model.h"
#include "analysis/simulation/random_motion.h"
#include "analysis/simulation/stepped_sine_run.h"
#include "analysis/simulation/time_simulator.h"
#include "daq/recording/recording.h"
#include "daq/rig/sensor_models.h"

namespace oscilab::daq {

/// What the virtual rig is asked to do: which well the test starts in, the sample rate of the
/// DAQ, the sensors, and the seed of every random draw (noise, creep, random excitation).
struct RigSpec {
  bool positive_well = true;
  double sample_rate_hz = 512.0;
  SensorSpec sensors;
  std::uint64_t seed = 1;
  analysis::TimeSimulator::Options integration;
};

/// A recording as the real rig makes it, plus the truth behind it (for tests and validation).
struct RigRecording {
  Recording recording;                        // base_acc [m/s²] and y [m], sidecar with excitation
  analysis::TimeSimulator::Result truth;      // z, ż, z̈, f, R, D at the sample times
  Eigen::VectorXd b_m;                        // true table displacement at the sample times
  std::vector<analysis::LevelEnergy> levels;  // stepped sine: true steady EDC per level
  analysis::TimeSimulator::Status status = analysis::TimeSimulator::Status::Ok;
  std::string message;
};

/// The sidecar of what the rig records: base_acc [m/s²] and y [m], stored as ADC counts of the
/// sensors' lsb (so integer containers are lossless), mass, and the rig's settings.
Sidecar rig_sidecar(const analysis::Model& model, const RigSpec& spec);

/// The virtual rig (§2, §3): a model on a shaking table, an accelerometer on the table and a laser
/// vibrometer on the mass. The table moves so that the model feels f = −m b̈; the accelerometer
/// reads b̈ + bias + noise, the vibrometer y = z + b + creep + noise, both quantised.
RigRecording record_stepped_sine(const analysis::Model& model,
                                 const analysis::SteppedSineSchedule& schedule, const RigSpec& spec,
                                 const ProgressFn& progress = {}, const CancelToken& cancel = {});
RigRecording record_random(const analysis::Model& model, const analysis::RandomMotionSpec& motion,
                           const RigSpec& spec, const ProgressFn& progress = {},
                           const CancelToken& cancel = {});

/// Truth beside a recording: `<stem>.truth.csv` (t_s, z_m, z_dot_m_s, z_ddot_m_s2, b_m, f_n,
/// restoring_force_n, damping_force_n) and `<stem>.truth.json` (model, well, per-level EDC).
void write_truth(const RigRecording& rig, const analysis::Model& model,
                 const std::string& recording_path);

}  // namespace oscilab::daq
