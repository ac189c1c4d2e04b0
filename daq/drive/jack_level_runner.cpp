#include "daq/drive/jack_level_runner.h"

#include <chrono>
#include <cstdio>
#include <optional>
#include <thread>
#include <utility>

#include "analysis/common/input_error.h"
#include "daq/jack/interleaved_resampler.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/recording/recording.h"

namespace oscilab::daq {
namespace {

using Clock = std::chrono::steady_clock;

// The ring holds this much of the inputs; the runner drains it every few milliseconds while a
// run lasts (between runs, while the loop refits, it overflows and that is thrown away).
constexpr double kCaptureS = 10.0;
// What the resampler passes flat, as a fraction of the output's Nyquist frequency (JackSource's).
constexpr double kPassbandEnd = 0.9;
// The drive's callback not run for this long: the run stops (its period is milliseconds).
constexpr double kStalledS = 2.0;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

/// The inputs of one run as the drive saw them, resampled to the analysis rate, on the
/// controller's sample clock (first_sample: the controller's count at the run's first frame).
struct JackLevelRunner::Capture {
  InterleavedResampler resampler;
  std::vector<double> acceleration_m_s2, position_m;
  bool started = false;
  std::uint32_t first_sample = 0;
  std::uint32_t next_sample = 0;  // the frame the next slot must start at (no gap)
};

JackLevelRunner::JackLevelRunner(Options options)
    : options_(std::move(options)), drive_([this] {
        JackDriveClient::Options drive = options_.drive;
        drive.capture_s = kCaptureS;
        return drive;
      }()) {
  if (!(options_.mass_kg > 0.0) || !std::isfinite(options_.mass_kg)) {
    throw InputError("JACK level runner: the mass must be positive");
  }
  if (const std::string why = drive_.start(); !why.empty()) throw InputError(why);
}

analysis::LevelRun JackLevelRunner::run(const std::vector<double>& levels_n, double freq_hz,
                                        bool positive_well, const std::string& purpose) {
  const char* well = positive_well ? "positive" : "negative";
  if (positive_well != options_.positive_well) {
    throw InputError(std::string("well: the mass sits in the ") +
                     (options_.positive_well ? "positive" : "negative") +
                     " well of the shaker, and a run on a real rig cannot move it to the " + well +
                     " one");
  }
  const double rate_hz = drive_.rate_hz();
  Capture capture;
  if (const std::string why = capture.resampler.open(rate_hz, options_.analysis_rate_hz, 2,
                                                     kPassbandEnd, drive_.capture().slot_frames());
      !why.empty()) {
    throw InputError("JACK level runner: " + why);
  }
  // What the ring holds from before this run is not part of it.
  while (drive_.capture().front() != nullptr) drive_.capture().pop();
  (void)drive_.take_events();
  const std::uint64_t dropped_before = drive_.capture_dropped();
  const auto start = Clock::now();
  std::uint64_t last_samples = drive_.status().samples;
  Clock::time_point last_progress = start;

  const auto take_samples = [&](std::size_t made) {
    const double* out = capture.resampler.output();
    for (std::size_t k = 0; k < made; ++k) {
      capture.acceleration_m_s2.push_back(out[2 * k] * options_.drive.acceleration_scale_m_s2);
      capture.position_m.push_back(out[2 * k + 1] * options_.drive.position_scale_m);
    }
  };
  // Drains the capture into the resampler and the drive's events into the log; throws at an
  // abort, a lost frame or a server gone. Returns the events drained.
  const auto pump = [&] {
    while (const FrameSlot* slot = drive_.capture().front()) {
      if (!capture.started) {
        capture.started = true;
        capture.first_sample = capture.next_sample = slot->frame_time;
      }
      if (slot->frame_time != capture.next_sample) {
        throw InputError("JACK level runner: the capture lost frames (the runner fell behind)");
      }
      capture.next_sample = slot->frame_time + slot->frames;
      std::size_t fed = 0;
      while (fed < slot->frames) {
        std::size_t used = 0;
        take_samples(
            capture.resampler.process(slot->data.data() + 2 * fed, slot->frames - fed, used));
        fed += used;
        if (used == 0) break;
      }
      drive_.capture().pop();
    }
    if (drive_.capture_dropped() != dropped_before) {
      throw InputError("JACK level runner: the capture ring overflowed (the runner fell behind)");
    }
    std::vector<DriveEvent> drained;
    for (const TimedDriveEvent& timed : drive_.take_events()) {
      events_.push_back(timed.event);
      drained.push_back(timed.event);
      if (timed.event.state == DriveState::Aborted) {
        throw DriveAborted("drive: " + drive_abort_text(timed.event, options_.drive.controller),
                           timed.event);
      }
    }
    if (drive_.shut_down()) throw InputError("drive: the JACK server shut down");
    // A server that stops running the drive's callback (an overloaded machine without real-time
    // scheduling) is said as such, not left to look like a level that never settles.
    const std::uint64_t samples = drive_.status().samples;
    if (samples != last_samples) {
      last_samples = samples;
      last_progress = Clock::now();
    } else if (seconds_since(last_progress) > kStalledS) {
      char text[160];
      std::snprintf(text, sizeof text,
                    "drive: the JACK server has not run the drive for %.0f s (an overloaded "
                    "server, or one without real-time scheduling)",
                    kStalledS);
      throw InputError(text);
    }
    return drained;
  };
  const auto pump_for = [&](double seconds) {
    const auto until = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < until) {
      pump();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  };
  // The controller's 0-based sample index at the last period's end, as run time.
  const auto run_time_of = [&](std::uint64_t controller_samples) {
    return static_cast<double>(static_cast<std::uint32_t>(controller_samples) -
                               capture.first_sample) /
           rate_hz;
  };
  const auto ramp_down = [&] {
    if (!drive_.ramp_down().empty()) return;
    const auto until =
        Clock::now() + std::chrono::duration<double>(options_.drive.controller.ramp_s + 5.0);
    while (Clock::now() < until && drive_.status().state != DriveState::Idle) {
      pump();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  };

  Excitation excitation;
  excitation.type = "stepped-sine";
  excitation.frequency_hz = freq_hz;
  pump_for(options_.lead_in_s);
  for (const double f0_n : levels_n) {
    const double target = f0_n / options_.mass_kg;
    if (const std::string why = drive_.set_level(target, freq_hz); !why.empty()) {
      ramp_down();
      throw InputError(why);
    }
    const double timeout_s = options_.drive.controller.ramp_s + options_.settle_timeout_s;
    const auto until = Clock::now() + std::chrono::duration<double>(timeout_s);
    std::optional<DriveEvent> on_target;
    while (!on_target && Clock::now() < until) {
      for (const DriveEvent& event : pump()) {
        if (event.state == DriveState::OnTarget && event.target_m_s2 == target) on_target = event;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (!on_target) {
      ramp_down();
      char text[160];
      std::snprintf(text, sizeof text,
                    "drive: level %.4g N did not come within the tolerance of f0/m in %.4g s", f0_n,
                    timeout_s);
      throw InputError(text);
    }
    pump_for(options_.hold_s);
    ExcitationLevel level;
    level.f0_n = f0_n;
    level.start_s = run_time_of(on_target->sample - 1);
    level.end_s = run_time_of(drive_.status().samples);
    excitation.levels.push_back(level);
  }
  ramp_down();
  pump_for(0.2);
  while (const std::size_t made = capture.resampler.flush()) take_samples(made);

  Recording recording;
  Sidecar& sidecar = recording.sidecar;
  sidecar.sample_rate_hz = options_.analysis_rate_hz;
  sidecar.mass_kg = options_.mass_kg;
  ChannelInfo base;
  base.name = "base_acc";
  base.role = ChannelRole::Base;
  base.quantity = Quantity::Acceleration;
  base.unit = "m/s^2";
  base.sensor = "accelerometer (" + options_.drive.acceleration_port + ")";
  ChannelInfo mass;
  mass.name = "y";
  mass.role = ChannelRole::Mass;
  mass.quantity = Quantity::Displacement;
  mass.unit = "m";
  mass.sensor = "vibrometer (" + options_.drive.position_port + ")";
  sidecar.channels = {base, mass};
  sidecar.excitation = excitation;
  sidecar.extra["drive"] = {{"server_rate_hz", rate_hz},
                            {"drive_port", options_.drive.drive_port},
                            {"well", well},
                            {"tolerance", options_.drive.controller.tolerance}};
  const auto n = static_cast<Eigen::Index>(capture.acceleration_m_s2.size());
  recording.samples_si.resize(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) {
    recording.samples_si(k, 0) = capture.acceleration_m_s2[static_cast<std::size_t>(k)];
    recording.samples_si(k, 1) = capture.position_m[static_cast<std::size_t>(k)];
  }
  char name[96];
  std::snprintf(name, sizeof name, "%02zu_%s_%s.wav", paths_.size(), purpose.c_str(), well);
  const std::string path = options_.folder + "/" + name;
  write_recording(recording, path);
  paths_.push_back(path);
  analysis::LevelRun out;
  out.channels = measurement_channels(recording);
  out.channels.name = name;
  out.shaker_s = seconds_since(start);
  return out;
}

}  // namespace oscilab::daq
