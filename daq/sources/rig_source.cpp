#include "daq/sources/rig_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/simulation/operated_sine_motion.h"
#include "analysis/simulation/time_stepper.h"
#include "daq/rig/sensor_models.h"

namespace oscilab::daq {

std::vector<ExcitationStep> rig_schedule(const std::vector<double>& levels_n, double hold_s,
                                         double lead_in_s, double frequency_hz) {
  if (!(hold_s > 0) || !(lead_in_s >= 0) || !(frequency_hz > 0)) {
    throw InputError("stepped sine: needs hold > 0, lead-in >= 0 and frequency > 0");
  }
  std::vector<ExcitationStep> steps;
  steps.reserve(levels_n.size() + 1);
  for (std::size_t i = 0; i < levels_n.size(); ++i) {
    steps.push_back({lead_in_s + static_cast<double>(i) * hold_s, levels_n[i], frequency_hz});
  }
  // At rest after the last level.
  steps.push_back({lead_in_s + static_cast<double>(levels_n.size()) * hold_s, 0.0, frequency_hz});
  return steps;
}
namespace {

// The integration's largest step, as TimeSimulator chooses it: one sample or 2 ms.
double max_step_s(const RigSpec& rig) {
  constexpr double kDefaultMaxStepS = 2e-3;
  return rig.integration.max_step_s > 0 ? rig.integration.max_step_s
                                        : std::min(1.0 / rig.sample_rate_hz, kDefaultMaxStepS);
}

}  // namespace

RigSource::RigSource(analysis::Model model, Options options)
    : model_(std::move(model)), options_(std::move(options)) {
  const RigSpec& rig = options_.rig;
  if (!(rig.sample_rate_hz > 0) || !std::isfinite(rig.sample_rate_hz)) {
    throw InputError("virtual rig: sample rate " + std::to_string(rig.sample_rate_hz) +
                     " Hz must be positive");
  }
  if (!(options_.speed >= 0) || !std::isfinite(options_.speed)) {
    throw InputError("virtual rig: speed " + std::to_string(options_.speed) +
                     " must be >= 0 (0: as fast as possible)");
  }
  if (options_.block_rows < 1 || options_.block_rows > 65536) {
    throw InputError("virtual rig: block size " + std::to_string(options_.block_rows) +
                     " samples must be within 1..65536");
  }
  for (std::size_t i = 1; i < options_.schedule.size(); ++i) {
    if (options_.schedule[i].t_s < options_.schedule[i - 1].t_s) {
      throw InputError("virtual rig: schedule step " + std::to_string(i) + " (t = " +
                       std::to_string(options_.schedule[i].t_s) + " s) is before the previous");
    }
  }
  if (options_.duration_s && !(*options_.duration_s > 0)) {
    throw InputError("virtual rig: duration must be positive");
  }
  // Validates the frequency and ramp once, with the message the operator will see.
  [[maybe_unused]] const analysis::OperatedSineMotion check(model_.mass_kg(), options_.frequency_hz,
                                                            options_.ramp_s);
  current_ = {0.0, 0.0, options_.frequency_hz};

  Sidecar sidecar = rig_sidecar(model_, rig);
  sidecar.channels[0].range =
      std::make_pair(-options_.accelerometer_range_m_s2, options_.accelerometer_range_m_s2);
  sidecar.channels[1].range =
      std::make_pair(-options_.vibrometer_range_m, options_.vibrometer_range_m);
  Excitation excitation;
  excitation.type = "stepped-sine";
  excitation.frequency_hz = options_.frequency_hz;
  excitation.extra["ramp_s"] = options_.ramp_s;
  excitation.extra["levels_live"] = true;  // levels arrive as `level` events (acquisition.h)
  sidecar.excitation = excitation;
  sidecar.notes = "live virtual rig, model \"" + model_.name() + "\", " +
                  analysis::to_string(analysis::well_of(rig.positive_well)) + " well, seed " +
                  std::to_string(rig.seed);
  set_layout(sidecar);
}

RigSource::~RigSource() { stop(); }

void RigSource::set_excitation(double f0_n, double frequency_hz) {
  if (!(f0_n >= 0) || !std::isfinite(f0_n) || !(frequency_hz > 0) || !std::isfinite(frequency_hz)) {
    throw InputError("virtual rig: excitation " + std::to_string(f0_n) + " N at " +
                     std::to_string(frequency_hz) + " Hz: need f0 >= 0 and a positive frequency");
  }
  const std::lock_guard lock(command_mutex_);
  pending_ = ExcitationStep{0.0, f0_n, frequency_hz};
}

ExcitationStep RigSource::excitation() const {
  const std::lock_guard lock(command_mutex_);
  return pending_.value_or(current_);
}

void RigSource::run() {
  const RigSpec& rig = options_.rig;
  const double rate_hz = rig.sample_rate_hz;
  // Stored values are ADC counts of the sensors' lsb; ideal sensors (lsb 0) store SI values.
  const double acc_lsb = rig.sensors.accelerometer.lsb_m_s2, y_lsb = rig.sensors.vibrometer.lsb_m;
  const auto stored = [](double value, double lsb) {
    return lsb > 0 ? std::nearbyint(value / lsb) : value;
  };

  analysis::OperatedSineMotion motion(model_.mass_kg(), options_.frequency_hz, options_.ramp_s);
  const double z0 = model_.well(rig.positive_well).z_m;
  analysis::TimeStepper stepper(model_, rig.integration.relative_tolerance,
                                rig.integration.absolute_tolerance, max_step_s(rig), z0, 0.0);
  std::mt19937_64 rng(rig.seed);
  SensorChain sensors(rig.sensors, rng);

  const auto apply = [&](double t_s, double f0_n, double frequency_hz) {
    motion.change(t_s, f0_n, frequency_hz);
    {
      const std::lock_guard lock(command_mutex_);
      current_ = {t_s, f0_n, frequency_hz};
    }
    post_event({t_s,
                EventKind::Level,
                "f0 " + std::to_string(f0_n) + " N at " + std::to_string(frequency_hz) + " Hz",
                {{"f0_n", f0_n},
                 {"frequency_hz", frequency_hz},
                 {"ramp_s", options_.ramp_s},
                 {"steady_from_s", t_s + options_.ramp_s}}});
  };

  const auto total_samples =
      options_.duration_s
          ? static_cast<std::uint64_t>(std::floor(*options_.duration_s * rate_hz + 0.5))
          : std::numeric_limits<std::uint64_t>::max();
  std::size_t next_step = 0;
  std::uint64_t sequence = 0, first_sample = 0;
  const auto wall_start = std::chrono::steady_clock::now();
  while (!stop_requested() && first_sample < total_samples) {
    const int rows = static_cast<int>(
        std::min<std::uint64_t>(options_.block_rows, total_samples - first_sample));
    const double block_start_s = static_cast<double>(first_sample) / rate_hz;
    const double block_end_s = static_cast<double>(first_sample + rows) / rate_hz;
    {
      std::optional<ExcitationStep> command;
      {
        // Taken and made current under one lock, so excitation() never shows the old value
        // between the two.
        const std::lock_guard lock(command_mutex_);
        command.swap(pending_);
        if (command) current_ = {block_start_s, command->f0_n, command->frequency_hz};
      }
      if (command) apply(block_start_s, command->f0_n, command->frequency_hz);
    }
    // Pace: a block is handed over when its last sample would have been measured.
    if (options_.speed > 0) {
      const auto due =
          wall_start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(block_end_s / options_.speed));
      std::this_thread::sleep_until(due);
    }
    RawBlock* block = begin_block(options_.speed == 0);
    for (int r = 0; r < rows; ++r) {
      const double t_s =
          static_cast<double>(first_sample + static_cast<std::uint64_t>(r)) / rate_hz;
      while (next_step < options_.schedule.size() && options_.schedule[next_step].t_s <= t_s) {
        const ExcitationStep& step = options_.schedule[next_step++];
        apply(std::max(step.t_s, stepper.time_s()), step.f0_n, step.frequency_hz);
      }
      if (!stepper.advance_to(motion, t_s)) {
        post_event({t_s, EventKind::Error, "the rig's integration failed (step underflow)"});
        return;
      }
      const analysis::TableState table = motion.at(t_s);
      const SensorChain::Reading reading =
          sensors.read(t_s, table.b_m, table.b_ddot_m_s2, stepper.z_m());
      if (!block) continue;  // the queue is full: the samples are lost, as on real hardware
      const double acc = std::clamp(reading.base_acc_m_s2, -options_.accelerometer_range_m_s2,
                                    options_.accelerometer_range_m_s2);
      const double y =
          std::clamp(reading.y_m, -options_.vibrometer_range_m, options_.vibrometer_range_m);
      block->values[2 * static_cast<std::size_t>(r)] = stored(acc, acc_lsb);
      block->values[2 * static_cast<std::size_t>(r) + 1] = stored(y, y_lsb);
    }
    if (block) {
      block->sequence = sequence;
      block->first_sample = first_sample;
      block->rows = rows;
      block->channels = 2;
      end_block(*block);
    } else {
      count_overflow(first_sample);
    }
    ++sequence;
    first_sample += static_cast<std::uint64_t>(rows);
  }
  if (first_sample >= total_samples) {
    post_event({static_cast<double>(first_sample) / rate_hz, EventKind::SourceEnded,
                "the virtual rig reached its duration"});
  }
}

}  // namespace oscilab::daq
