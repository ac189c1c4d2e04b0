// Harmonic balance with pseudo-arclength continuation in the forcing amplitude (§4.2), Floquet
// stability, folds and period doublings: the continue_branch of `oscilab-cli hbm`.
#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/edc/well.h"
#include "analysis/hbm/branch.h"
#include "analysis/hbm/branch_switching.h"
#include "analysis/hbm/continuation.h"
#include "analysis/model/model.h"
#include "analysis/simulation/amplitude_sweep.h"
#include "analysis/simulation/bifurcation_map.h"
#include "bindings.h"
#include "python_types.h"

namespace oscilab::python {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

py::dict events_table(const analysis::Branch& branch, analysis::PointMarker kind) {
  std::vector<double> f0, amp;
  std::vector<int> index;
  for (const analysis::BranchEvent& e : branch.events_of(kind)) {
    f0.push_back(e.f0_n);
    amp.push_back(e.amp_m);
    index.push_back(static_cast<int>(e.point_index));
  }
  py::dict d;
  d["f0_n"] = to_array(f0);
  d["amp_m"] = to_array(amp);
  d["point_index"] = to_int_array(index);
  return d;
}

// The branch as columns named like the branch CSV (write_branch_csv), in continuation order.
py::dict branch_dict(const analysis::Branch& branch) {
  const std::size_t n = branch.points.size();
  std::vector<double> f0(n), amp(n), z1(n), phase(n), edc(n), freq(n), edc_diss(n), mu1_abs(n),
      mu2_abs(n), mu1_re(n), mu1_im(n), mu2_re(n), mu2_im(n), mean(n);
  std::vector<int> stable(n), iterations(n);
  py::list marker;
  Eigen::MatrixXd coefficients;
  for (std::size_t i = 0; i < n; ++i) {
    const analysis::BranchPoint& p = branch.points[i];
    const analysis::HbmMeasures& m = p.measures;
    if (i == 0) coefficients.resize(static_cast<Eigen::Index>(n), p.coefficients.size());
    if (p.coefficients.size() == coefficients.cols()) {
      coefficients.row(static_cast<Eigen::Index>(i)) = p.coefficients.transpose();
    }
    f0[i] = p.f0_n;
    amp[i] = m.amp_m;
    z1[i] = std::abs(m.z1_m);
    phase[i] = std::arg(m.z1_m) + 0.0;
    edc[i] = m.edc_j + 0.0;
    stable[i] = p.stability_known && p.floquet.stable ? 1 : 0;
    freq[i] = p.freq_hz;
    edc_diss[i] = m.edc_dissipation_j;
    mean[i] = m.mean_m;
    if (p.stability_known) {
      const auto& mu = p.floquet.multipliers;
      mu1_abs[i] = std::abs(mu[0]);
      mu2_abs[i] = std::abs(mu[1]);
      mu1_re[i] = mu[0].real();
      mu1_im[i] = mu[0].imag();
      mu2_re[i] = mu[1].real();
      mu2_im[i] = mu[1].imag();
    } else {
      mu1_abs[i] = mu2_abs[i] = mu1_re[i] = mu1_im[i] = mu2_re[i] = mu2_im[i] = kNaN;
    }
    marker.append(analysis::marker_name(p.marker));
    iterations[i] = p.newton_iterations;
  }
  py::dict d;
  d["f0_n"] = to_array(f0);
  d["amp_m"] = to_array(amp);
  d["z1_abs_m"] = to_array(z1);
  d["phase_rad"] = to_array(phase);
  d["edc_j"] = to_array(edc);
  d["stable"] = to_int_array(stable);
  d["freq_hz"] = to_array(freq);
  d["edc_dissipation_j"] = to_array(edc_diss);
  d["mu1_abs"] = to_array(mu1_abs);
  d["mu2_abs"] = to_array(mu2_abs);
  d["mu1_re"] = to_array(mu1_re);
  d["mu1_im"] = to_array(mu1_im);
  d["mu2_re"] = to_array(mu2_re);
  d["mu2_im"] = to_array(mu2_im);
  d["marker"] = marker;
  d["newton_iterations"] = to_int_array(iterations);
  d["z_mean_m"] = to_array(mean);
  d["coefficients"] = to_array(coefficients);
  d["folds"] = events_table(branch, analysis::PointMarker::Fold);
  d["period_doublings"] = events_table(branch, analysis::PointMarker::PeriodDoubling);
  d["branch_points"] = events_table(branch, analysis::PointMarker::BranchPoint);
  py::list events;
  for (const analysis::BranchEvent& e : branch.events) {
    py::dict event;
    event["kind"] = analysis::marker_name(e.kind);
    event["f0_n"] = e.f0_n;
    event["freq_hz"] = e.freq_hz;
    event["amp_m"] = e.amp_m;
    event["point_index"] = e.point_index;
    events.append(event);
  }
  d["events"] = events;
  d["status"] = job_status_name(branch.status);
  d["message"] = branch.message;
  d["well"] = analysis::to_string(analysis::well_of(branch.positive_well));
  d["harmonics"] = branch.hbm.harmonics;
  d["subharmonic"] = branch.hbm.subharmonic;
  d["samples"] = branch.samples;
  d["steps_accepted"] = branch.steps_accepted;
  d["steps_rejected"] = branch.steps_rejected;
  d["newton_iterations_total"] = branch.newton_iterations;
  return d;
}

// hbm_branch(): a branch by harmonic balance with continuation.
void bind_hbm_branch(py::module_& m) {
  m.def(
      "hbm_branch",
      [](const py::object& model_arg, double freq_hz, std::pair<double, double> f0_n,
         const std::string& well, int harmonics, int subharmonic, int samples, int floquet_steps,
         bool stability, double max_step, const std::vector<double>& landing,
         bool follow_period_doubling, const py::object& progress) {
        const analysis::Model model = model_argument(model_arg);
        // 'both': one branch per well, as `hbm --well both`, in one job.
        const std::vector<analysis::Well> wells = wells_argument(well);
        analysis::ContinuationOptions options;
        options.start = f0_n.first;
        options.end = f0_n.second;
        options.freq_hz = freq_hz;
        options.hbm.harmonics = harmonics;
        options.hbm.subharmonic = subharmonic;
        options.hbm.samples = samples;
        options.floquet.steps_per_forcing_period = floquet_steps;
        options.stability = stability;
        options.max_step = max_step;
        options.initial_step = std::min(options.initial_step, max_step);
        options.landing = landing;
        if (follow_period_doubling && !stability) {
          throw InputError(
              "follow_period_doubling: period doublings are found from the Floquet multipliers; "
              "drop stability=False");
        }
        std::vector<analysis::Branch> branches(wells.size());
        std::vector<std::vector<analysis::PeriodDoublingSwitch>> doubled(wells.size());
        run_job(
            [&](const ReportFn& report, const CancelToken& cancel) {
              const double n = static_cast<double>(wells.size());
              for (std::size_t i = 0; i < wells.size() && !cancel.cancelled(); ++i) {
                const ProgressFn part = [&report, i, n](double fraction) {
                  ProgressReport r;
                  r.fraction = (static_cast<double>(i) + fraction) / n;
                  report(r);
                };
                analysis::ContinuationOptions o = options;
                o.positive_well = wells[i] == analysis::Well::Positive;
                branches[i] = analysis::continue_branch(model, o, part, cancel);
                if (follow_period_doubling) {
                  doubled[i] =
                      analysis::follow_period_doublings(model, branches[i], o, part, cancel);
                }
              }
            },
            progress);
        py::dict by_well;
        for (std::size_t i = 0; i < wells.size(); ++i) {
          py::dict d = branch_dict(branches[i]);
          d["period"] = subharmonic;
          if (follow_period_doubling) {
            py::list list;
            for (const analysis::PeriodDoublingSwitch& s : doubled[i]) {
              py::dict b = branch_dict(s.branch);
              b["period"] = s.subharmonic;
              b["status"] = job_status_name(s.status);
              b["message"] = s.message;
              b["f0_flip_n"] = s.f0_flip_n;
              b["f0_pitchfork_n"] = s.f0_pitchfork_n;
              list.append(b);
            }
            d["period_doubled"] = list;
          }
          if (wells.size() == 1) return d;
          by_well[py::str(wells[i] == analysis::Well::Positive ? "positive" : "negative")] = d;
        }
        return by_well;
      },
      py::arg("model") = "paper", py::kw_only(), py::arg("freq_hz") = 9.0,
      py::arg("f0_n") = std::pair<double, double>(0.1, 3.7), py::arg("well") = "positive",
      py::arg("harmonics") = 7, py::arg("subharmonic") = 1, py::arg("samples") = 0,
      py::arg("floquet_steps") = 1024, py::arg("stability") = true, py::arg("max_step") = 0.1,
      py::arg("landing") = std::vector<double>{}, py::arg("follow_period_doubling") = false,
      py::arg("progress") = py::none(),
      R"doc(Harmonic balance with pseudo-arclength continuation in the forcing amplitude
(`oscilab-cli hbm`): the periodic response of the model at freq_hz [Hz] from f0_n[0] to f0_n[1]
[N], growing from the stable equilibrium of `well`, folds followed, not jumped.

harmonics: H; subharmonic: ν (period-νT ansatz); samples: AFT samples per period (0: default);
floquet_steps: RK4 steps per forcing period of the monodromy; stability: Floquet multipliers;
max_step: largest scaled arc-length step; landing: f0 values [N] to land on exactly.
Returns a dict of arrays in continuation order named like the branch CSV: f0_n, amp_m, z1_abs_m,
phase_rad, edc_j, stable (1/0), freq_hz, edc_dissipation_j, mu1_abs, mu2_abs, mu1_re, mu1_im,
mu2_re, mu2_im (NaN without stability), marker, newton_iterations; and z_mean_m, coefficients
(points × [a0, a1, b1, …]), folds, period_doublings, branch_points ({f0_n, amp_m, point_index}
arrays), events, status, message, well, harmonics, subharmonic, samples, steps_accepted,
steps_rejected, period (1 for ν = 1). A continuation that stops early is status != 'ok' with the
points so far. follow_period_doubling: at the first period doubling switch onto the period-2
branch and continue it over the f0 range (and once more at its first period doubling: period 4),
as `hbm --follow-period-doubling`; the result then has period_doubled, a list of such dicts with
period (in forcing periods), f0_flip_n and f0_pitchfork_n [N]. well='both' (as `hbm --well
both`): {'positive': branch, 'negative': branch}, both computed in one call.)doc");
}

// amplitude_sweep(): the time-integrated sweep up and down in f0.
void bind_amplitude_sweep(py::module_& m) {
  m.def(
      "amplitude_sweep",
      [](const py::object& model_arg, double freq_hz, double f0_max_n, double up_s,
         const py::object& down_s, const std::string& well, int samples_per_period,
         const py::object& progress) {
        const analysis::Model model = model_argument(model_arg);
        analysis::AmplitudeSweepOptions options;
        options.freq_hz = freq_hz;
        options.f0_max_n = f0_max_n;
        options.up_s = up_s;
        options.down_s = down_s.is_none() ? up_s : number_argument(down_s, "down_s");
        options.positive_well = well_argument(well) == analysis::Well::Positive;
        options.samples_per_period = samples_per_period;
        options.validate();
        analysis::AmplitudeSweep sweep;
        run_job(
            [&](const ReportFn& report, const CancelToken& cancel) {
              sweep = analysis::amplitude_sweep(model, options, fraction_reporter(report), cancel);
            },
            progress);
        std::vector<double> f0, amp, t;
        py::list direction;
        for (const analysis::AmplitudeSweepPeriod& p : sweep.periods) {
          f0.push_back(p.f0_n);
          amp.push_back(p.amp_m);
          t.push_back(p.t_s);
          direction.append(p.up ? "up" : "down");
        }
        py::dict d;
        d["f0_n"] = to_array(f0);
        d["direction"] = direction;
        d["amp_m"] = to_array(amp);
        d["t_s"] = to_array(t);
        const auto jump = [](const analysis::AmplitudeSweepJump& j) {
          py::dict out;
          out["f0_n"] = j.f0_n;
          out["amp_before_m"] = j.amp_before_m;
          out["amp_after_m"] = j.amp_after_m;
          return out;
        };
        d["jump_up"] = jump(sweep.jump_up);
        d["jump_down"] = jump(sweep.jump_down);
        d["status"] = job_status_name(sweep.status);
        d["message"] = sweep.message;
        return d;
      },
      py::arg("model") = "paper", py::kw_only(), py::arg("freq_hz") = 9.0,
      py::arg("f0_max_n") = 3.7, py::arg("up_s") = 400.0, py::arg("down_s") = py::none(),
      py::arg("well") = "positive", py::arg("samples_per_period") = 64,
      py::arg("progress") = py::none(),
      R"doc(The amplitude sweep of §4.2 (Fig. 12) by time integration (`oscilab-cli hbm --sweep`): f0
ramps slowly from 0 up to f0_max_n [N] in up_s [s] and back down in down_s [s] (default: up_s) at
freq_hz [Hz], from rest at the equilibrium of `well`; where the harmonic-balance branch folds the
response jumps (hysteresis).

Returns a dict: one entry per forcing period, named like the sweep CSV: f0_n [N] (mid-period),
direction ('up'/'down'), amp_m [m] ((max z − min z) / 2 over the period, from
samples_per_period samples), t_s [s] (its start); jump_up and jump_down ({f0_n, amp_before_m,
amp_after_m}: the largest period-to-period change each way), status, message.)doc");
}

// bifurcation_map(): the stepped time simulation's Poincaré points.
void bind_bifurcation_map(py::module_& m) {
  m.def(
      "bifurcation_map",
      [](const py::object& model_arg, double freq_hz, std::pair<double, double> f0_n, double step_n,
         const py::object& levels_n, const std::string& well, int hold_periods, int ramp_periods,
         int sampled_periods, double cluster_tolerance_m, const py::object& progress) {
        const analysis::Model model = model_argument(model_arg);
        analysis::BifurcationMapOptions options;
        options.freq_hz = freq_hz;
        options.start_n = f0_n.first;
        options.end_n = f0_n.second;
        options.step_n = step_n;
        if (!levels_n.is_none()) options.levels_n = levels_argument(levels_n);
        const std::vector<analysis::Well> wells = wells_argument(well);
        options.positive_well = wells.front() == analysis::Well::Positive;
        options.negative_well = wells.back() == analysis::Well::Negative;
        options.hold_periods = hold_periods;
        options.ramp_periods = ramp_periods;
        options.sampled_periods = sampled_periods;
        options.cluster_tolerance_m = cluster_tolerance_m;
        options.validate();
        analysis::BifurcationMap map;
        run_job(
            [&](const ReportFn& report, const CancelToken& cancel) {
              map = analysis::bifurcation_map(model, options, fraction_reporter(report), cancel);
            },
            progress);
        std::vector<double> row_f0, row_z;
        std::vector<int> row_period;
        py::list row_well;
        for (const analysis::BifurcationMapRow& r : map.rows) {
          row_f0.push_back(r.f0_n);
          row_z.push_back(r.z_m);
          row_period.push_back(r.period);
          row_well.append(r.positive_well ? "positive" : "negative");
        }
        py::dict rows;
        rows["f0_n"] = to_array(row_f0);
        rows["well"] = row_well;
        rows["z_m"] = to_array(row_z);
        rows["period"] = to_int_array(row_period);
        std::vector<double> f0, spread, z_min, z_max;
        std::vector<int> points;
        py::list level_well;
        for (const analysis::BifurcationMapLevel& l : map.levels) {
          f0.push_back(l.f0_n);
          points.push_back(l.distinct_points);
          spread.push_back(l.spread_m);
          z_min.push_back(l.z_min_m);
          z_max.push_back(l.z_max_m);
          level_well.append(l.positive_well ? "positive" : "negative");
        }
        py::dict levels;
        levels["f0_n"] = to_array(f0);
        levels["well"] = level_well;
        levels["distinct_points"] = to_int_array(points);
        levels["spread_m"] = to_array(spread);
        levels["z_min_m"] = to_array(z_min);
        levels["z_max_m"] = to_array(z_max);
        py::dict d;
        d["rows"] = rows;
        d["levels"] = levels;
        d["status"] = job_status_name(map.status);
        d["message"] = map.message;
        return d;
      },
      py::arg("model") = "paper", py::kw_only(), py::arg("freq_hz") = 9.0,
      py::arg("f0_n") = std::pair<double, double>(0.1, 3.7), py::arg("step_n") = 0.05,
      py::arg("levels_n") = py::none(), py::arg("well") = "both", py::arg("hold_periods") = 200,
      py::arg("ramp_periods") = 5, py::arg("sampled_periods") = 32,
      py::arg("cluster_tolerance_m") = 1e-5, py::arg("progress") = py::none(),
      R"doc(Bifurcation map by time simulation (§5.2, Fig. 17; `oscilab-cli hbm --map`): a stepped sine
at freq_hz [Hz] whose level steps from f0_n[0] to f0_n[1] by step_n [N] (or through levels_n, a
sequence or 'A:STEP:B'), simulated from rest at the equilibrium of `well` ('positive',
'negative' or 'both'), the state carried from level to level as on the rig; z sampled once per
forcing period at the same phase (a Poincaré section) over the last sampled_periods of each hold
of hold_periods (ramp_periods of ramp). One point per level: period 1; two: period 2.

Returns a dict: rows (columns f0_n [N], well, z_m [m], period: the map CSV), levels (columns
f0_n, well, distinct_points (sections closer than cluster_tolerance_m [m] are one), spread_m,
z_min_m, z_max_m), status ('ok', 'cancelled' with the levels done), message.)doc");
}

}  // namespace

void bind_hbm(py::module_& m) {
  bind_hbm_branch(m);
  bind_amplitude_sweep(m);
  bind_bifurcation_map(m);
}

}  // namespace oscilab::python
