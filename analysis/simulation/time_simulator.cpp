#include "analysis/simulation/time_simulator.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

namespace odeint = boost::numeric::odeint;
using State = std::vector<double>;

// State layout: [z, ż, W_in, W_diss, s_0 ... s_{n-1}].
constexpr std::size_t kZ = 0, kZDot = 1, kWorkIn = 2, kDissipated = 3, kInternal = 4;

struct EquationOfMotion {
  const Model& model;
  const TableMotion& motion;
  long* evaluations;

  void operator()(const State& x, State& dxdt, double t) const {
    ++*evaluations;
    const double z = x[kZ], z_dot = x[kZDot];
    const double* s = model.state_size() > 0 ? x.data() + kInternal : nullptr;
    const double f = -model.mass_kg() * motion.at(t).b_ddot_m_s2;  // eq. (1)
    const double d = model.dissipative_force(z, z_dot, s);
    const double r = model.elastic_force(z) + d;
    dxdt[kZ] = z_dot;
    dxdt[kZDot] = (f - r) / model.mass_kg();
    dxdt[kWorkIn] = f * z_dot;
    dxdt[kDissipated] = d * z_dot;
    if (s) model.state_rate(z, z_dot, s, dxdt.data() + kInternal);
  }
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
  const double sample_rate_hz = run.sample_rate_hz, duration_s = run.duration_s;
  if (!(sample_rate_hz > 0) || !(duration_s >= 0) || !std::isfinite(duration_s)) {
    throw InputError("time simulation: need a positive sample rate and a finite duration");
  }
  if (!std::is_sorted(run.probe_times_s.begin(), run.probe_times_s.end()) ||
      (!run.probe_times_s.empty() &&
       (run.probe_times_s.front() < 0 || run.probe_times_s.back() > duration_s))) {
    throw InputError("time simulation: probe times must be increasing and within the run");
  }
  const auto samples = static_cast<Eigen::Index>(std::floor(duration_s * sample_rate_hz)) + 1;
  const double dt_out = 1.0 / sample_rate_hz;
  Result result;
  for (auto* v : {&result.t_s, &result.z_m, &result.z_dot_m_s, &result.z_ddot_m_s2, &result.f_n,
                  &result.restoring_force_n, &result.damping_force_n, &result.work_in_j,
                  &result.dissipated_j}) {
    v->resize(samples);
  }

  State x(kInternal + static_cast<std::size_t>(model_.state_size()), 0.0);
  x[kZ] = run.z0_m;
  x[kZDot] = run.z_dot0_m_s;
  const std::vector<double> s0 = model_.initial_state(run.z0_m);
  std::copy(s0.begin(), s0.end(), x.begin() + kInternal);

  EquationOfMotion system{model_, motion, &result.rhs_evaluations};
  const double max_step = options_.max_step_s > 0 ? options_.max_step_s : dt_out;
  auto stepper = odeint::make_dense_output(options_.absolute_tolerance, options_.relative_tolerance,
                                           max_step, odeint::runge_kutta_dopri5<State>());

  const auto record = [&](Eigen::Index k, const State& state, double t) {
    const double z = state[kZ], z_dot = state[kZDot];
    const double* s = model_.state_size() > 0 ? state.data() + kInternal : nullptr;
    const double f = -model_.mass_kg() * motion.at(t).b_ddot_m_s2;
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
  stepper.initialize(x, 0.0, std::min(1e-4, dt_out));
  State xk(x.size());
  Eigen::Index k = 1;
  // Output samples are interpolated from the dense output (4th-order continuous extension of
  // Dormand–Prince), so the step size never depends on the output rate.
  const Eigen::Index chunk = std::max<Eigen::Index>(1, static_cast<Eigen::Index>(sample_rate_hz));
  while (k < samples) {
    const Eigen::Index chunk_end = std::min(samples, k + chunk);
    for (; k < chunk_end; ++k) {
      const double t = static_cast<double>(k) * dt_out;
      while (stepper.current_time() < t) stepper.do_step(system);
      while (next_probe < probes && run.probe_times_s[next_probe] <= t) {
        const double tp = run.probe_times_s[next_probe];
        stepper.calc_state(tp, xk);
        probe(xk, tp);
      }
      stepper.calc_state(t, xk);
      if (!std::isfinite(xk[kZ]) || !std::isfinite(xk[kZDot])) {
        result.status = Status::NumericalIssue;
        result.message = "the state is no longer finite at t = " + std::to_string(t) + " s";
        break;
      }
      record(k, xk, t);
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
    while (stepper.current_time() < tp) stepper.do_step(system);
    stepper.calc_state(tp, xk);
    probe(xk, tp);
  }
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
