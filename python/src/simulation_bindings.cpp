// Time simulation of eq. (1) (TimeSimulator, Dormand–Prince 5(4)) and the virtual rig (what the
// real rig records), the same library calls as `oscilab-cli simulate`.
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/model/model.h"
#include "analysis/simulation/random_motion.h"
#include "analysis/simulation/stepped_levels.h"
#include "analysis/simulation/stepped_sine_motion.h"
#include "analysis/simulation/stepped_sine_run.h"
#include "analysis/simulation/time_simulator.h"
#include "bindings.h"
#include "daq/rig/virtual_rig.h"
#include "python_types.h"

namespace oscilab::python {
namespace {

const char* simulator_status(analysis::TimeSimulator::Status s) {
  switch (s) {
    case analysis::TimeSimulator::Status::Ok:
      return "ok";
    case analysis::TimeSimulator::Status::Cancelled:
      return "cancelled";
    case analysis::TimeSimulator::Status::NumericalIssue:
      return "numerical-issue";
  }
  return "unknown";
}

py::dict samples_dict(const analysis::TimeSimulator::Result& r) {
  py::dict d;
  d["t_s"] = to_array(r.t_s);
  d["z_m"] = to_array(r.z_m);
  d["z_dot_m_s"] = to_array(r.z_dot_m_s);
  d["z_ddot_m_s2"] = to_array(r.z_ddot_m_s2);
  d["f_n"] = to_array(r.f_n);
  d["restoring_force_n"] = to_array(r.restoring_force_n);
  d["damping_force_n"] = to_array(r.damping_force_n);
  d["work_in_j"] = to_array(r.work_in_j);
  d["dissipated_j"] = to_array(r.dissipated_j);
  d["status"] = simulator_status(r.status);
  d["message"] = r.message;
  d["rhs_evaluations"] = r.rhs_evaluations;
  return d;
}

py::dict level_energies(const std::vector<analysis::LevelEnergy>& levels) {
  std::vector<double> f0, edc, start, end;
  std::vector<int> cycles;
  for (const auto& l : levels) {
    f0.push_back(l.f0_n);
    edc.push_back(l.edc_j);
    cycles.push_back(l.cycles);
    start.push_back(l.start_s);
    end.push_back(l.end_s);
  }
  py::dict d;
  d["f0_n"] = to_array(f0);
  d["edc_j"] = to_array(edc);
  d["cycles"] = to_int_array(cycles);
  d["start_s"] = to_array(start);
  d["end_s"] = to_array(end);
  return d;
}

analysis::SteppedSineSchedule schedule_argument(double freq_hz, const py::object& levels_n,
                                                double hold_s, double ramp_s, double lead_in_s) {
  analysis::SteppedSineSchedule schedule;
  schedule.frequency_hz = freq_hz;
  schedule.levels_n = levels_argument(levels_n);
  schedule.hold_s = hold_s;
  schedule.ramp_s = ramp_s;
  schedule.lead_in_s = lead_in_s;
  return schedule;
}

analysis::RandomMotionSpec random_argument(double rms_n, const std::pair<double, double>& band,
                                           double duration_s, std::uint64_t seed) {
  analysis::RandomMotionSpec motion;
  motion.low_hz = band.first;
  motion.high_hz = band.second;
  motion.force_rms_n = rms_n;
  motion.duration_s = duration_s;
  motion.seed = seed;
  return motion;
}

}  // namespace

// levels_n: a sequence of amplitudes [N], or "A:STEP:B" (analysis::stepped_levels, the rule the
// CLI's --levels uses) or "A,B,...".
std::vector<double> levels_argument(const py::object& levels) {
  if (!py::isinstance<py::str>(levels)) {
    const Eigen::VectorXd v =
        to_vector(py::module_::import("numpy").attr("atleast_1d")(levels), "levels_n");
    return {v.data(), v.data() + v.size()};
  }
  const std::string text = levels.cast<std::string>();
  const auto number = [&](const std::string& part) {
    try {
      std::size_t used = 0;
      const double value = std::stod(part, &used);
      if (used != part.size()) throw std::invalid_argument(part);
      return value;
    } catch (const std::exception&) {
      throw InputError("levels_n: \"" + part + "\" is not a number");
    }
  };
  std::vector<std::string> parts;
  for (const char separator : {':', ','}) {
    if (text.find(separator) == std::string::npos) continue;
    std::size_t start = 0;
    for (std::size_t at; (at = text.find(separator, start)) != std::string::npos; start = at + 1) {
      parts.push_back(text.substr(start, at - start));
    }
    parts.push_back(text.substr(start));
    if (separator == ':') {
      if (parts.size() != 3) throw InputError("levels_n: \"" + text + "\" is not A:STEP:B");
      return analysis::stepped_levels(number(parts[0]), number(parts[1]), number(parts[2]),
                                      "levels_n: \"" + text + "\"");
    }
    break;
  }
  if (parts.empty()) parts.push_back(text);
  std::vector<double> out;
  for (const auto& part : parts) out.push_back(number(part));
  return out;
}

namespace {

// simulate(): the model integrated in time.
void bind_simulate(py::module_& m) {
  m.def(
      "simulate",
      [](const py::object& model_arg, const std::string& test, const std::string& well,
         const py::object& z0_m, double z_dot0_m_s, double freq_hz, const py::object& levels_n,
         double hold_s, double ramp_s, double lead_in_s, double rms_n,
         std::pair<double, double> band_hz, double duration_s, std::uint64_t seed,
         double sample_rate_hz, double relative_tolerance, double absolute_tolerance,
         const py::object& progress) {
        const analysis::Model model = model_argument(model_arg);
        const bool positive = well_argument(well) == analysis::Well::Positive;
        const double z0 = z0_m.is_none() ? model.well(positive).z_m : number_argument(z0_m, "z0_m");
        analysis::TimeSimulator::Options options;
        options.relative_tolerance = relative_tolerance;
        options.absolute_tolerance = absolute_tolerance;
        const analysis::TimeSimulator simulator(model, options);
        if (test == "stepped-sine") {
          const analysis::SteppedSineMotion motion(
              schedule_argument(freq_hz, levels_n, hold_s, ramp_s, lead_in_s), model.mass_kg());
          analysis::SteppedSineRun run;
          run_job(
              [&](const ReportFn& report, const CancelToken& cancel) {
                run = analysis::simulate_stepped_sine(simulator, motion, z0, sample_rate_hz,
                                                      fraction_reporter(report), cancel);
              },
              progress);
          py::dict d = samples_dict(run.samples);
          d["levels"] = level_energies(run.levels);
          return d;
        }
        if (test != "random") {
          throw InputError("test: \"" + test + "\" is not stepped-sine or random");
        }
        const analysis::RandomMotion motion(random_argument(rms_n, band_hz, duration_s, seed),
                                            model.mass_kg());
        analysis::TimeSimulator::Run run;
        run.z0_m = z0;
        run.z_dot0_m_s = z_dot0_m_s;
        run.duration_s = duration_s;
        run.sample_rate_hz = sample_rate_hz;
        analysis::TimeSimulator::Result result;
        run_job(
            [&](const ReportFn& report, const CancelToken& cancel) {
              result = simulator.simulate(motion, run, fraction_reporter(report), cancel);
            },
            progress);
        return samples_dict(result);
      },
      py::arg("model") = "paper", py::kw_only(), py::arg("test") = "stepped-sine",
      py::arg("well") = "positive", py::arg("z0_m") = py::none(), py::arg("z_dot0_m_s") = 0.0,
      py::arg("freq_hz") = 9.0, py::arg("levels_n") = "0.2:0.1:2.7", py::arg("hold_s") = 10.0,
      py::arg("ramp_s") = 0.5, py::arg("lead_in_s") = 2.5, py::arg("rms_n") = 2.0,
      py::arg("band_hz") = std::pair<double, double>(2.0, 30.0), py::arg("duration_s") = 120.0,
      py::arg("seed") = 1, py::arg("sample_rate_hz") = 512.0, py::arg("relative_tolerance") = 1e-9,
      py::arg("absolute_tolerance") = 1e-12, py::arg("progress") = py::none(),
      R"doc(Time simulation of eq. (1), m z̈ + R(z, ż) = f(t) = −m b̈(t), with error control
(Dormand–Prince 5(4)) and exact energy integrals: the true motion, no sensors.

model: a Model, a model dict, 'paper', 'illustrative' or a model JSON path.
test: 'stepped-sine' (freq_hz [Hz], levels_n: amplitudes [N] as a sequence or 'A:STEP:B',
hold_s, ramp_s, lead_in_s [s]; from rest in `well` unless z0_m [m] is given) or 'random'
(band-limited force: rms_n [N], band_hz (low, high) [Hz], duration_s [s], seed; from z0_m,
z_dot0_m_s [m/s]).
sample_rate_hz: output rate [Hz]; relative_tolerance, absolute_tolerance: the step control's.
Returns a dict of arrays at t = k / rate: t_s, z_m, z_dot_m_s, z_ddot_m_s2, f_n, restoring_force_n,
damping_force_n, work_in_j, dissipated_j; status ('ok', 'cancelled', 'numerical-issue'),
message, rhs_evaluations; for a stepped sine also levels (true steady EDC per level: f0_n, edc_j,
cycles, start_s, end_s). progress: callable(info) with info['fraction']; Ctrl-C stops it.)doc");
}

// virtual_rig(): a stepped sine or random test recorded by the virtual rig.
void bind_virtual_rig(py::module_& m) {
  m.def(
      "virtual_rig",
      [](const py::object& model_arg, const std::string& test, const std::string& well,
         double freq_hz, const py::object& levels_n, double hold_s, double ramp_s, double lead_in_s,
         double rms_n, std::pair<double, double> band_hz, double duration_s, double sample_rate_hz,
         std::uint64_t seed, bool ideal_sensors, const py::object& progress,
         const py::object& rate_hz) {
        // rate_hz: the former name of sample_rate_hz (simulate's), still taken, with a warning.
        if (!rate_hz.is_none()) {
          if (PyErr_WarnEx(PyExc_DeprecationWarning,
                           "virtual_rig(rate_hz=...) is now sample_rate_hz=..., as in simulate()",
                           1) != 0) {
            throw py::error_already_set();
          }
          sample_rate_hz = number_argument(rate_hz, "rate_hz");
        }
        const analysis::Model model = model_argument(model_arg);
        daq::RigSpec spec;
        spec.positive_well = well_argument(well) == analysis::Well::Positive;
        spec.sample_rate_hz = sample_rate_hz;
        spec.seed = seed;
        if (ideal_sensors) {
          spec.sensors.accelerometer = {0.0, 0.0, 0.0};
          spec.sensors.vibrometer = {0.0, 0.0};
          spec.sensors.creep.amplitude_m = 0.0;
        }
        if (test != "stepped-sine" && test != "random") {
          throw InputError("test: \"" + test + "\" is not stepped-sine or random");
        }
        const bool stepped = test == "stepped-sine";
        const analysis::SteppedSineSchedule schedule =
            stepped ? schedule_argument(freq_hz, levels_n, hold_s, ramp_s, lead_in_s)
                    : analysis::SteppedSineSchedule{};
        const analysis::RandomMotionSpec motion = random_argument(rms_n, band_hz, duration_s, seed);
        daq::RigRecording rig;
        run_job(
            [&](const ReportFn& report, const CancelToken& cancel) {
              rig = stepped ? daq::record_stepped_sine(model, schedule, spec,
                                                       fraction_reporter(report), cancel)
                            : daq::record_random(model, motion, spec, fraction_reporter(report),
                                                 cancel);
            },
            progress);
        if (rig.status == analysis::TimeSimulator::Status::NumericalIssue) {
          throw InputError("simulate: integration failed: " + rig.message);
        }
        py::dict d;
        d["recording"] = py::cast(std::move(rig.recording));
        py::dict truth = samples_dict(rig.truth);
        truth["b_m"] = to_array(rig.b_m);
        d["truth"] = truth;
        d["levels"] = level_energies(rig.levels);
        d["status"] = simulator_status(rig.status);
        d["message"] = rig.message;
        return d;
      },
      py::arg("model") = "paper", py::kw_only(), py::arg("test") = "stepped-sine",
      py::arg("well") = "positive", py::arg("freq_hz") = 9.0, py::arg("levels_n") = "0.2:0.1:2.7",
      py::arg("hold_s") = 10.0, py::arg("ramp_s") = 0.5, py::arg("lead_in_s") = 2.5,
      py::arg("rms_n") = 2.0, py::arg("band_hz") = std::pair<double, double>(2.0, 30.0),
      py::arg("duration_s") = 120.0, py::arg("sample_rate_hz") = 512.0, py::arg("seed") = 1,
      py::arg("ideal_sensors") = false, py::arg("progress") = py::none(),
      py::arg("rate_hz") = py::none(),
      R"doc(The virtual rig (`oscilab-cli simulate`): the model on the shaking table, an accelerometer
on the table and a laser vibrometer on the mass (bias, noise, quantisation, creep), stored as ADC
counts. Same arguments as the CLI's options (freq_hz [Hz], levels_n [N] sequence or 'A:STEP:B',
hold_s, ramp_s, lead_in_s, duration_s [s], rms_n [N], band_hz (low, high) [Hz], sample_rate_hz
[Hz], seed, ideal_sensors). rate_hz: sample_rate_hz's former name, deprecated.

Returns a dict: recording (a Recording: base_acc [m/s²] and y [m] with its sidecar; .write(path)
gives the CLI's file), truth (arrays t_s, z_m, z_dot_m_s, z_ddot_m_s2, f_n, restoring_force_n,
damping_force_n, work_in_j, dissipated_j, b_m), levels (true steady EDC per level), status,
message. Raises InputError (a ValueError) when the integration fails.)doc");
}

}  // namespace

void bind_simulation(py::module_& m) {
  bind_simulate(m);
  bind_virtual_rig(m);
}

}  // namespace oscilab::python
