#include "daq/rig/virtual_rig.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/simulation/stepped_sine_motion.h"
#include "daq/recording/temporary_file.h"

namespace oscilab::daq {
namespace {

using analysis::TimeSimulator;

void check(const RigSpec& spec) {
  if (!(spec.sample_rate_hz > 0)) {
    throw InputError("virtual rig: sample rate " + std::to_string(spec.sample_rate_hz) +
                     " Hz must be positive");
  }
}

// An excitation the recording cannot resolve is refused before it is simulated: a forcing at or
// beyond the Nyquist frequency would alias, and one at 1e9 Hz would keep the integrator's error
// control stepping for ever.
void check_below_nyquist(double freq_hz, const RigSpec& spec, const char* what) {
  if (!(freq_hz < 0.5 * spec.sample_rate_hz)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "virtual rig: %s %g Hz is not below the Nyquist frequency, %g Hz at %g Hz", what,
                  freq_hz, 0.5 * spec.sample_rate_hz, spec.sample_rate_hz);
    throw InputError(text);
  }
}

}  // namespace

Sidecar rig_sidecar(const analysis::Model& model, const RigSpec& spec) {
  Sidecar sidecar;
  sidecar.sample_rate_hz = spec.sample_rate_hz;
  sidecar.mass_kg = model.mass_kg();
  ChannelInfo acc;
  acc.name = "base_acc";
  acc.role = ChannelRole::Base;
  acc.quantity = Quantity::Acceleration;
  acc.unit = "m/s^2";
  acc.sensor = "accelerometer";
  ChannelInfo y;
  y.name = "y";
  y.role = ChannelRole::Mass;
  y.quantity = Quantity::Displacement;
  y.unit = "m";
  y.sensor = "laser vibrometer";
  // Quantised channels store ADC counts: scale = lsb, so integer containers (FLAC) are lossless.
  if (spec.sensors.accelerometer.lsb_m_s2 > 0) acc.scale = spec.sensors.accelerometer.lsb_m_s2;
  if (spec.sensors.vibrometer.lsb_m > 0) y.scale = spec.sensors.vibrometer.lsb_m;
  sidecar.channels = {acc, y};
  const auto& a = spec.sensors.accelerometer;
  const auto& v = spec.sensors.vibrometer;
  sidecar.extra["virtual_rig"] = {
      {"model", model.to_json()},
      {"well", analysis::to_string(analysis::well_of(spec.positive_well))},
      {"seed", spec.seed},
      {"accelerometer",
       {{"bias_m_s2", a.bias_m_s2},
        {"noise_rms_m_s2", a.noise_rms_m_s2},
        {"lsb_m_s2", a.lsb_m_s2}}},
      {"vibrometer", {{"noise_rms_m", v.noise_rms_m}, {"lsb_m", v.lsb_m}}},
      {"creep_amplitude_m", spec.sensors.creep.amplitude_m}};
  return sidecar;
}

namespace {

// Samples the sensors along the simulated motion: y = z + b + creep + noise, b̈ + bias + noise.
void measure(const analysis::TableMotion& motion, const RigSpec& spec, std::mt19937_64& rng,
             RigRecording& rig) {
  const auto& t = rig.truth.t_s;
  const Eigen::Index n = t.size();
  SensorChain sensors(spec.sensors, rng);
  rig.recording.samples_si.resize(n, 2);
  rig.b_m.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const analysis::TableState table = motion.at(t[k]);
    rig.b_m[k] = table.b_m;
    const SensorChain::Reading reading =
        sensors.read(t[k], table.b_m, table.b_ddot_m_s2, rig.truth.z_m[k]);
    rig.recording.samples_si(k, 0) = reading.base_acc_m_s2;
    rig.recording.samples_si(k, 1) = reading.y_m;
  }
}

}  // namespace

RigRecording record_stepped_sine(const analysis::Model& model,
                                 const analysis::SteppedSineSchedule& schedule, const RigSpec& spec,
                                 const ProgressFn& progress, const CancelToken& cancel) {
  check(spec);
  check_below_nyquist(schedule.frequency_hz, spec, "excitation frequency");
  const analysis::SteppedSineMotion motion(schedule, model.mass_kg());
  const TimeSimulator simulator(model, spec.integration);
  const double z0 = model.well(spec.positive_well).z_m;
  analysis::SteppedSineRun run =
      analysis::simulate_stepped_sine(simulator, motion, z0, spec.sample_rate_hz, progress, cancel);

  RigRecording rig;
  rig.truth = std::move(run.samples);
  rig.levels = std::move(run.levels);
  rig.status = rig.truth.status;
  rig.message = rig.truth.message;
  rig.recording.sidecar = rig_sidecar(model, spec);
  Excitation excitation;
  excitation.type = "stepped-sine";
  excitation.frequency_hz = schedule.frequency_hz;
  for (std::size_t i = 0; i < schedule.levels_n.size(); ++i) {
    excitation.levels.push_back(
        {schedule.levels_n[i], schedule.steady_start_s(i), schedule.steady_end_s(i)});
  }
  excitation.extra["hold_s"] = schedule.hold_s;
  excitation.extra["ramp_s"] = schedule.ramp_s;
  excitation.extra["lead_in_s"] = schedule.lead_in_s;
  rig.recording.sidecar.excitation = excitation;
  rig.recording.sidecar.notes = "virtual rig: stepped sine, model \"" + model.name() + "\", " +
                                analysis::to_string(analysis::well_of(spec.positive_well)) +
                                " well, seed " + std::to_string(spec.seed);
  std::mt19937_64 rng(spec.seed);
  measure(motion, spec, rng, rig);
  return rig;
}

RigRecording record_random(const analysis::Model& model,
                           const analysis::RandomMotionSpec& motion_spec, const RigSpec& spec,
                           const ProgressFn& progress, const CancelToken& cancel) {
  check(spec);
  check_below_nyquist(motion_spec.high_hz, spec, "band's upper edge");
  analysis::RandomMotionSpec seeded = motion_spec;
  seeded.seed = spec.seed;
  const analysis::RandomMotion motion(seeded, model.mass_kg());
  const TimeSimulator simulator(model, spec.integration);
  TimeSimulator::Run run;
  run.z0_m = model.well(spec.positive_well).z_m;
  run.duration_s = motion.duration_s();
  run.sample_rate_hz = spec.sample_rate_hz;

  RigRecording rig;
  rig.truth = simulator.simulate(motion, run, progress, cancel);
  rig.status = rig.truth.status;
  rig.message = rig.truth.message;
  rig.recording.sidecar = rig_sidecar(model, spec);
  Excitation excitation;
  excitation.type = "random";
  excitation.extra["band_hz"] = {seeded.low_hz, seeded.high_hz};
  excitation.extra["force_rms_n"] = seeded.force_rms_n;
  excitation.extra["fade_s"] = seeded.fade_s;
  rig.recording.sidecar.excitation = excitation;
  rig.recording.sidecar.notes = "virtual rig: band-limited random, model \"" + model.name() +
                                "\", start in the " +
                                analysis::to_string(analysis::well_of(spec.positive_well)) +
                                " well, seed " + std::to_string(spec.seed);
  // A different stream from the excitation's phases (seeded with the same number).
  std::mt19937_64 rng(spec.seed ^ 0x9E3779B97F4A7C15ULL);
  measure(motion, spec, rng, rig);
  return rig;
}

void write_truth(const RigRecording& rig, const analysis::Model& model,
                 const std::string& recording_path) {
  const std::filesystem::path path(recording_path);
  const std::string stem = (path.parent_path() / path.stem()).string();
  // Both files complete under temporary names before either takes its own (TemporaryFile): a
  // failed write leaves neither.
  const std::string csv_path = stem + ".truth.csv";
  TemporaryFile csv_file(csv_path);
  std::FILE* csv = std::fopen(csv_file.path().c_str(), "w");
  if (!csv) throw InputError(csv_path + ": cannot write: " + std::strerror(errno));
  std::fprintf(csv, "t_s,z_m,z_dot_m_s,z_ddot_m_s2,b_m,f_n,restoring_force_n,damping_force_n\n");
  const auto& s = rig.truth;
  for (Eigen::Index k = 0; k < s.t_s.size(); ++k) {
    std::fprintf(csv, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", s.t_s[k], s.z_m[k],
                 s.z_dot_m_s[k], s.z_ddot_m_s2[k], rig.b_m[k], s.f_n[k], s.restoring_force_n[k],
                 s.damping_force_n[k]);
  }
  const bool ok = std::ferror(csv) == 0;
  if (std::fclose(csv) != 0 || !ok) {
    throw InputError(csv_path + ": write failed: " + std::strerror(errno));
  }

  nlohmann::json levels = nlohmann::json::array();
  for (const auto& level : rig.levels) {
    levels.push_back({{"f0_n", level.f0_n},
                      {"edc_true_j", level.edc_j},
                      {"cycles", level.cycles},
                      {"start_s", level.start_s},
                      {"end_s", level.end_s}});
  }
  const nlohmann::json truth = {
      {"model", model.to_json()},
      {"well", rig.recording.sidecar.extra["virtual_rig"]["well"]},
      {"note",
       "edc_true_j: exact ∫D ż dt of the simulation over the whole forcing cycles of the "
       "second half of each level's steady hold, per cycle"},
      {"levels", levels}};
  const std::string json_path = stem + ".truth.json";
  TemporaryFile json_file(json_path);
  {
    std::ofstream out(json_file.path());
    out << truth.dump(2) << '\n';
    out.close();
    if (!out) throw InputError(json_path + ": write failed: " + std::strerror(errno));
  }
  csv_file.commit();
  json_file.commit();
}

}  // namespace oscilab::daq
