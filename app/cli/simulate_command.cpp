// oscilab-cli simulate: the virtual rig (contract §2).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/model/model_json.h"
#include "app/cli/commands.h"
#include "app/cli/option_parsing.h"
#include "app/cli/progress_bar.h"
#include "daq/recording/sidecar.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::cli {
namespace {

struct SimulateOptions {
  std::string model = "paper";
  std::string test = "stepped-sine";
  std::string well = "positive";
  double freq_hz = 9.0;
  std::string levels = "0.2:0.1:2.7";
  double hold_s = 10.0;
  double ramp_s = 0.5;
  double lead_in_s = 2.5;
  double rms_n = 2.0;
  std::string band_hz = "2:30";
  double duration_s = 120.0;
  double rate_hz = 512.0;
  std::uint64_t seed = 1;
  bool ideal_sensors = false;
  bool truth = false;
  std::string out;
};

void run(const SimulateOptions& options) {
  const analysis::Model model = analysis::model_from_spec(options.model);
  daq::RigSpec spec;
  spec.positive_well = analysis::well_from_string(options.well) == analysis::Well::Positive;
  spec.sample_rate_hz = options.rate_hz;
  spec.seed = options.seed;
  if (options.ideal_sensors) {
    spec.sensors.accelerometer = {0.0, 0.0, 0.0};
    spec.sensors.vibrometer = {0.0, 0.0};
    spec.sensors.creep.amplitude_m = 0.0;
  }

  const auto start = std::chrono::steady_clock::now();
  daq::RigRecording rig;
  {
    ProgressBar bar("simulate");
    if (options.test == "stepped-sine") {
      analysis::SteppedSineSchedule schedule;
      schedule.frequency_hz = options.freq_hz;
      schedule.levels_n = parse_levels(options.levels, "--levels");
      schedule.hold_s = options.hold_s;
      schedule.ramp_s = options.ramp_s;
      schedule.lead_in_s = options.lead_in_s;
      rig = daq::record_stepped_sine(model, schedule, spec, bar.callback());
    } else {
      analysis::RandomMotionSpec motion;
      const auto band = split(options.band_hz, ':');
      if (band.size() != 2) throw InputError("--band: \"" + options.band_hz + "\" is not LOW:HIGH");
      motion.low_hz = parse_number(band[0], "--band");
      motion.high_hz = parse_number(band[1], "--band");
      motion.force_rms_n = options.rms_n;
      motion.duration_s = options.duration_s;
      rig = daq::record_random(model, motion, spec, bar.callback());
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (rig.status != analysis::TimeSimulator::Status::Ok) {
    throw InputError("simulate: integration failed: " + rig.message);
  }
  daq::write_recording(rig.recording, options.out);
  if (options.truth) {
    try {
      daq::write_truth(rig, model, options.out);
    } catch (const InputError&) {
      // A failed run leaves no file: not the recording without its truth either.
      std::error_code ignored;
      std::filesystem::remove(options.out, ignored);
      std::filesystem::remove(daq::sidecar_path_for(options.out), ignored);
      throw;
    }
  }
  const double duration = rig.recording.duration_s();
  std::printf("wrote %s: %s test, %s well, %.1f s at %g Hz, %ld samples\n", options.out.c_str(),
              options.test.c_str(), options.well.c_str(), duration, options.rate_hz,
              static_cast<long>(rig.recording.sample_count()));
  std::printf("simulated in %.3f s (%.0fx real time, %ld model evaluations)\n", seconds,
              duration / seconds, rig.truth.rhs_evaluations);
  if (!rig.levels.empty()) {
    std::printf("true steady EDC per level (J): ");
    for (const auto& level : rig.levels) std::printf("%.3g@%.2gN ", level.edc_j, level.f0_n);
    std::printf("\n");
  }
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* command =
      app.add_subcommand("simulate",
                         "Virtual rig: simulate a model on the shaking table and write what the "
                         "accelerometer and the laser vibrometer record (recording + sidecar)");
  command->add_option("--model", o->model, "paper | illustrative | MODEL.json")
      ->capture_default_str();
  command->add_option("--test", o->test, "stepped-sine | random")
      ->check(CLI::IsMember({"stepped-sine", "random"}))
      ->capture_default_str();
  command->add_option("--well", o->well, "stable equilibrium the test starts from")
      ->check(CLI::IsMember({"positive", "negative"}))
      ->capture_default_str();
  command->add_option("--freq", o->freq_hz, "stepped sine: excitation frequency [Hz]")
      ->capture_default_str();
  command
      ->add_option("--levels", o->levels,
                   "stepped sine: force amplitudes f0 [N], A:STEP:B or A,B,...")
      ->capture_default_str();
  command->add_option("--hold", o->hold_s, "stepped sine: time per level, ramp included [s]")
      ->capture_default_str();
  command->add_option("--ramp", o->ramp_s, "stepped sine: amplitude ramp at each level's start [s]")
      ->capture_default_str();
  command->add_option("--lead-in", o->lead_in_s, "rest before the first level [s]")
      ->capture_default_str();
  command->add_option("--rms", o->rms_n, "random: force rms [N]")->capture_default_str();
  command->add_option("--band", o->band_hz, "random: force band LOW:HIGH [Hz]")
      ->capture_default_str();
  command->add_option("--duration", o->duration_s, "random: length [s]")->capture_default_str();
  command->add_option("--rate", o->rate_hz, "DAQ sample rate [Hz]")->capture_default_str();
  command->add_option("--seed", o->seed, "seed of noise, creep and random excitation")
      ->capture_default_str();
  command->add_flag("--ideal-sensors", o->ideal_sensors, "no bias, noise, quantisation or creep");
  command->add_flag("--truth", o->truth,
                    "also write <stem>.truth.csv (z, ż, z̈, b, f, R, D) and <stem>.truth.json "
                    "(true EDC per level)");
  command->add_option("--out", o->out, "recording to write (.wav .flac .w64 .csv ...)")->required();
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
