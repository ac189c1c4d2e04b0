#include "analysis/simulation/time_simulator.h"
#include "analysis/model/excitation_force.h"

#include <algorithm>
#include <array>
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

// The run's checks: a positive rate, a finite duration within kMaxSamples, probes in order within
// the run. Throws InputError saying which.
void validate_run(const TimeSimulator::Run& run, double max_samples) {
  const double sample_rate_hz = run.sample_rate_hz, duration_s = run.duration_s;
  if (!(sample_rate_hz > 0) || !(duration_s >= 0) || !std::isfinite(duration_s)) {
    throw InputError("time simulation: need a positive sample rate and a finite duration");
  }
  if (!std::is_sorted(run.probe_times_s.begin(), run.probe_times_s.end()) ||
      (!run.probe_times_s.empty() &&
       (run.probe_times_s.front() < 0 || run.probe_times_s.back() > duration_s))) {
    throw InputError("time simulation: probe times must be increasing and within the run");
  }
  if (!(duration_s * sample_rate_hz < max_samples)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "time simulation: %g s at %g Hz is %.3g samples, more than the %.3g one run "
                  "holds (a day at 512 Hz is 4.4e+07)",
                  duration_s, sample_rate_hz, duration_s * sample_rate_hz, max_samples);
    throw InputError(text);
  }
}

// Writes the samples and the probes of a run into its Result: each output sample's state, forces
// and energy integrals, each probe's energies.
class Trace {
 public:
  Trace(const Model& model, const TableMotion& motion, TimeSimulator::Result& result,
        Eigen::Index samples, Eigen::Index probes)
      : model_(model), motion_(motion), result_(result) {
    for (Eigen::VectorXd* v : sample_columns()) v->resize(samples);
    for (Eigen::VectorXd* v : probe_columns()) v->resize(probes);
  }

  void record(Eigen::Index k, const State& state, double t) {
    const double z = state[kZ], z_dot = state[kZDot];
    const double* s = model_.state_size() > 0 ? state.data() + kInternal : nullptr;
    const double f = excitation_force_n(model_.mass_kg(), motion_.at(t).b_ddot_m_s2);
    const double d = model_.dissipative_force(z, z_dot, s);
    const double r = model_.elastic_force(z) + d;
    result_.t_s[k] = t;
    result_.z_m[k] = z;
    result_.z_dot_m_s[k] = z_dot;
    result_.z_ddot_m_s2[k] = (f - r) / model_.mass_kg();
    result_.f_n[k] = f;
    result_.restoring_force_n[k] = r;
    result_.damping_force_n[k] = d;
    result_.work_in_j[k] = state[kWorkIn];
    result_.dissipated_j[k] = state[kDissipated];
  }

  void probe(const State& state, double t) {
    const double z_dot = state[kZDot];
    result_.probe_t_s[probes_] = t;
    result_.probe_work_in_j[probes_] = state[kWorkIn];
    result_.probe_dissipated_j[probes_] = state[kDissipated];
    result_.probe_mechanical_j[probes_] =
        0.5 * model_.mass_kg() * z_dot * z_dot + model_.potential_j(state[kZ]);
    ++probes_;
  }

  Eigen::Index probes_done() const { return probes_; }

  // A run that stopped early keeps the samples and probes written.
  void truncate(Eigen::Index samples) {
    for (Eigen::VectorXd* v : sample_columns()) v->conservativeResize(samples);
    for (Eigen::VectorXd* v : probe_columns()) v->conservativeResize(probes_);
  }

 private:
  std::array<Eigen::VectorXd*, 9> sample_columns() {
    return {&result_.t_s,
            &result_.z_m,
            &result_.z_dot_m_s,
            &result_.z_ddot_m_s2,
            &result_.f_n,
            &result_.restoring_force_n,
            &result_.damping_force_n,
            &result_.work_in_j,
            &result_.dissipated_j};
  }
  std::array<Eigen::VectorXd*, 4> probe_columns() {
    return {&result_.probe_t_s, &result_.probe_work_in_j, &result_.probe_dissipated_j,
            &result_.probe_mechanical_j};
  }

  const Model& model_;
  const TableMotion& motion_;
  TimeSimulator::Result& result_;
  Eigen::Index probes_ = 0;
};

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
  validate_run(run, kMaxSamples);
  const double sample_rate_hz = run.sample_rate_hz;
  const auto samples = static_cast<Eigen::Index>(std::floor(run.duration_s * sample_rate_hz)) + 1;
  const double dt_out = 1.0 / sample_rate_hz;
  const auto probes = static_cast<Eigen::Index>(run.probe_times_s.size());
  Result result;
  Trace trace(model_, motion, result, samples, probes);

  constexpr double kDefaultMaxStepS = 2e-3;
  const double max_step =
      options_.max_step_s > 0 ? options_.max_step_s : std::min(dt_out, kDefaultMaxStepS);
  TimeStepper stepper(model_, options_.relative_tolerance, options_.absolute_tolerance, max_step,
                      run.z0_m, run.z_dot0_m_s);
  const State& x = stepper.state();
  const auto advance_to = [&](double t_target) { return stepper.advance_to(motion, t_target); };
  const auto next_probe_at = [&](double t) {
    return trace.probes_done() < probes && run.probe_times_s[trace.probes_done()] <= t;
  };
  while (next_probe_at(0.0)) trace.probe(x, 0.0);

  trace.record(0, x, 0.0);
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
      while (next_probe_at(t)) {
        const double tp = run.probe_times_s[trace.probes_done()];
        if (!advance_to(tp)) break;
        trace.probe(x, tp);
      }
      if (!advance_to(t) || !std::isfinite(x[kZ]) || !std::isfinite(x[kZDot])) {
        fail(stepper.time_s());
        break;
      }
      trace.record(k, x, t);
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
  while (result.status == Status::Ok && trace.probes_done() < probes) {
    const double tp = run.probe_times_s[trace.probes_done()];
    if (!advance_to(tp)) {
      fail(stepper.time_s());
      break;
    }
    trace.probe(x, tp);
  }
  result.rhs_evaluations = stepper.rhs_evaluations();
  if (result.status != Status::Ok) trace.truncate(k);
  return result;
}

}  // namespace oscilab::analysis
