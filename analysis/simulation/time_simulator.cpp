#include "analysis/simulation/time_simulator.h"
#include "analysis/model/excitation_force.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/simulation/time_stepper.h"

namespace oscilab::analysis {
namespace {

using State = std::vector<double>;
constexpr std::size_t kZ = TimeStepper::kZ, kZDot = TimeStepper::kZDot,
                      kWorkIn = TimeStepper::kWorkIn, kDissipated = TimeStepper::kDissipated,
                      kInternal = TimeStepper::kInternal;

}  // namespace

TimeSimulator::TimeSimulator(Model model, Options options)
    : model_(std::move(model)), options_(options) {
  if (!(options_.relative_tolerance > 0) || !(options_.absolute_tolerance > 0)) {
    throw InputError("time simulation: tolerances must be positive");
  }
  if (!(options_.max_step_s >= 0)) throw InputError("time simulation: max_step_s must be >= 0");
}

TimeSimulator::Result TimeSimulator::simulate(const TableMotion& motion, const Run& run,
                                              const ProgressFn& progress,
                                              const CancelToken& cancel) const {
  const double sample_rate_hz = run.sample_rate_hz, duration_s = run.duration_s;
  if (!(sample_rate_hz > 0) || !(duration_s >= 0) || !std::isfinite(duration_s)) {
    throw InputError("time simulation: need a positive sample rate and a finite duration");
  }
  if (!std::is_sorted(run.probe_times_s.begin(), run.probe_times_s.end()) ||
      (!run.probe_times_s.empty() &&
       (run.probe_times_s.front() < 0 || run.probe_times_s.back() > duration_s))) {
    throw InputError("time simulation: probe times must be increasing and within the run");
  }
  if (!(duration_s * sample_rate_hz < kMaxSamples)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "time simulation: %g s at %g Hz is %.3g samples, more than the %.3g one run "
                  "holds (a day at 512 Hz is 4.4e+07)",
                  duration_s, sample_rate_hz, duration_s * sample_rate_hz, kMaxSamples);
    throw InputError(text);
  }
  const auto samples = static_cast<Eigen::Index>(std::floor(duration_s * sample_rate_hz)) + 1;
  const double dt_out = 1.0 / sample_rate_hz;
  Result result;
  for (auto* v : {&result.t_s, &result.z_m, &result.z_dot_m_s, &result.z_ddot_m_s2, &result.f_n,
                  &result.restoring_force_n, &result.damping_force_n, &result.work_in_j,
                  &result.dissipated_j}) {
    v->resize(samples);
  }

  constexpr double kDefaultMaxStepS = 2e-3;
  const double max_step =
      options_.max_step_s > 0 ? options_.max_step_s : std::min(dt_out, kDefaultMaxStepS);
  TimeStepper stepper(model_, options_.relative_tolerance, options_.absolute_tolerance, max_step,
                      run.z0_m, run.z_dot0_m_s);
  const State& x = stepper.state();
  const auto advance_to = [&](double t_target) { return stepper.advance_to(motion, t_target); };
  const auto t_now = [&] { return stepper.time_s(); };

  const auto record = [&](Eigen::Index k, const State& state, double t) {
    const double z = state[kZ], z_dot = state[kZDot];
    const double* s = model_.state_size() > 0 ? state.data() + kInternal : nullptr;
    const double f = excitation_force_n(model_.mass_kg(), motion.at(t).b_ddot_m_s2);
    const double d = model_.dissipative_force(z, z_dot, s);
    const double r = model_.elastic_force(z) + d;
    result.t_s[k] = t;
    result.z_m[k] = z;
    result.z_dot_m_s[k] = z_dot;
    result.z_ddot_m_s2[k] = (f - r) / model_.mass_kg();
    result.f_n[k] = f;
    result.restoring_force_n[k] = r;
    result.damping_force_n[k] = d;
    result.work_in_j[k] = state[kWorkIn];
    result.dissipated_j[k] = state[kDissipated];
  };

  const auto probes = static_cast<Eigen::Index>(run.probe_times_s.size());
  for (auto* v : {&result.probe_t_s, &result.probe_work_in_j, &result.probe_dissipated_j,
                  &result.probe_mechanical_j}) {
    v->resize(probes);
  }
  Eigen::Index next_probe = 0;
  const auto probe = [&](const State& state, double t) {
    const double z_dot = state[kZDot];
    result.probe_t_s[next_probe] = t;
    result.probe_work_in_j[next_probe] = state[kWorkIn];
    result.probe_dissipated_j[next_probe] = state[kDissipated];
    result.probe_mechanical_j[next_probe] =
        0.5 * model_.mass_kg() * z_dot * z_dot + model_.potential_j(state[kZ]);
    ++next_probe;
  };
  while (next_probe < probes && run.probe_times_s[next_probe] <= 0.0) probe(x, 0.0);

  record(0, x, 0.0);
  Eigen::Index k = 1;
  const auto fail = [&](double t) {
    result.status = Status::NumericalIssue;
    result.message = "the integration failed at t = " + std::to_string(t) + " s (state " +
                     (std::isfinite(x[kZ]) ? "finite" : "not finite") + ", step underflow)";
  };
  const Eigen::Index chunk = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(sample_rate_hz));
  while (k < samples && result.status == Status::Ok) {
    const Eigen::Index chunk_end = std::min(samples, k + chunk);
    for (; k < chunk_end; ++k) {
      const double t = static_cast<double>(k) * dt_out;
      while (next_probe < probes && run.probe_times_s[next_probe] <= t) {
        const double tp = run.probe_times_s[next_probe];
        if (!advance_to(tp)) break;
        probe(x, tp);
      }
      if (!advance_to(t) || !std::isfinite(x[kZ]) || !std::isfinite(x[kZDot])) {
        fail(t_now());
        break;
      }
      record(k, x, t);
    }
    if (result.status != Status::Ok) break;
    if (progress) progress(static_cast<double>(k) / static_cast<double>(samples));
    if (cancel.cancelled() && k < samples) {
      result.status = Status::Cancelled;
      result.message = "cancelled at t = " + std::to_string(static_cast<double>(k) * dt_out) + " s";
      break;
    }
  }
  // Probes after the last output sample (duration not a multiple of the sample interval).
  while (result.status == Status::Ok && next_probe < probes) {
    const double tp = run.probe_times_s[next_probe];
    if (!advance_to(tp)) {
      fail(t_now());
      break;
    }
    probe(x, tp);
  }
  result.rhs_evaluations = stepper.rhs_evaluations();
  if (result.status != Status::Ok) {
    for (auto* v : {&result.t_s, &result.z_m, &result.z_dot_m_s, &result.z_ddot_m_s2, &result.f_n,
                    &result.restoring_force_n, &result.damping_force_n, &result.work_in_j,
                    &result.dissipated_j}) {
      v->conservativeResize(k);
    }
    for (auto* v : {&result.probe_t_s, &result.probe_work_in_j, &result.probe_dissipated_j,
                    &result.probe_mechanical_j}) {
      v->conservativeResize(next_probe);
    }
  }
  return result;
}

}  // namespace oscilab::analysis
