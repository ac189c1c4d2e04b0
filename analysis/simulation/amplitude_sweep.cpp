#include "analysis/simulation/amplitude_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <ostream>

#include "analysis/common/input_error.h"
#include "analysis/simulation/amplitude_sweep_motion.h"
#include "analysis/simulation/time_simulator.h"

namespace oscilab::analysis {

void AmplitudeSweepOptions::validate() const {
  if (!(freq_hz > 0.0) || !std::isfinite(freq_hz)) {
    throw InputError("amplitude sweep: freq_hz: " + std::to_string(freq_hz) + " must be positive");
  }
  if (!(f0_max_n > 0.0) || !std::isfinite(f0_max_n)) {
    throw InputError("amplitude sweep: f0_max_n: " + std::to_string(f0_max_n) +
                     " must be positive");
  }
  if (!(up_s * freq_hz >= 2.0) || !(down_s * freq_hz >= 2.0)) {
    throw InputError("amplitude sweep: each direction must last at least two forcing periods");
  }
  if (samples_per_period < 8) {
    throw InputError("amplitude sweep: samples_per_period must be at least 8");
  }
  // Checked here, before the time simulation would refuse it, so that a front end that writes
  // other results first (hbm --sweep) refuses the whole command before writing anything.
  const double samples = (up_s + down_s) * freq_hz * samples_per_period;
  if (!(samples < TimeSimulator::kMaxSamples)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "amplitude sweep: %g s up and %g s down at %g samples a period of %g Hz are "
                  "%.3g samples, more than the %.3g a time simulation holds",
                  up_s, down_s, samples_per_period * 1.0, freq_hz, samples,
                  TimeSimulator::kMaxSamples);
    throw InputError(text);
  }
}

namespace {

AmplitudeSweepJump largest_jump(const std::vector<AmplitudeSweepPeriod>& periods, bool up) {
  AmplitudeSweepJump jump;
  jump.up = up;
  double largest = -1.0;
  for (std::size_t i = 1; i < periods.size(); ++i) {
    const AmplitudeSweepPeriod& a = periods[i - 1];
    const AmplitudeSweepPeriod& b = periods[i];
    if (a.up != up || b.up != up) continue;
    const double change = std::abs(b.amp_m - a.amp_m);
    if (change > largest) {
      largest = change;
      jump.f0_n = 0.5 * (a.f0_n + b.f0_n);
      jump.amp_before_m = a.amp_m;
      jump.amp_after_m = b.amp_m;
    }
  }
  return jump;
}

}  // namespace

AmplitudeSweep amplitude_sweep(const Model& model, const AmplitudeSweepOptions& options,
                               const ProgressFn& progress, const CancelToken& cancel) {
  options.validate();
  AmplitudeSweep sweep;
  sweep.options = options;
  const AmplitudeSweepMotion motion(options.freq_hz, options.f0_max_n, options.up_s, options.down_s,
                                    model.mass_kg());
  TimeSimulator::Run run;
  run.z0_m = model.well(options.positive_well).z_m;
  run.duration_s = motion.duration_s();
  run.sample_rate_hz = options.freq_hz * options.samples_per_period;
  const TimeSimulator::Result result =
      TimeSimulator(model, {}).simulate(motion, run, progress, cancel);

  // Period n covers samples [n S, (n + 1) S] (both ends: the next period starts where this ends).
  const long s = options.samples_per_period;
  const double period_s = 1.0 / options.freq_hz;
  for (long n = 0; (n + 1) * s < result.z_m.size(); ++n) {
    const auto segment = result.z_m.segment(n * s, s + 1);
    AmplitudeSweepPeriod period;
    period.t_s = static_cast<double>(n) * period_s;
    const double middle_s = period.t_s + 0.5 * period_s;
    period.f0_n = motion.f0_n(middle_s);
    period.up = middle_s <= options.up_s;
    period.amp_m = 0.5 * (segment.maxCoeff() - segment.minCoeff());
    sweep.periods.push_back(period);
  }
  sweep.jump_up = largest_jump(sweep.periods, true);
  sweep.jump_down = largest_jump(sweep.periods, false);
  if (result.status == TimeSimulator::Status::Cancelled) {
    sweep.status = JobStatus::Cancelled;
    sweep.message = "cancelled";
  } else if (result.status != TimeSimulator::Status::Ok) {
    sweep.status = JobStatus::NumericalIssue;
    sweep.message = result.message;
  }
  return sweep;
}

void write_amplitude_sweep_csv(const AmplitudeSweep& sweep, std::ostream& out) {
  out << "f0_n,direction,amp_m,t_s\n";
  out.precision(10);
  for (const AmplitudeSweepPeriod& p : sweep.periods) {
    out << p.f0_n << ',' << (p.up ? "up" : "down") << ',' << p.amp_m << ',' << p.t_s << '\n';
  }
}

void write_amplitude_sweep_csv(const AmplitudeSweep& sweep, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw InputError(path + ": cannot write");
  write_amplitude_sweep_csv(sweep, file);
  if (!file) throw InputError(path + ": write failed");
}

}  // namespace oscilab::analysis
