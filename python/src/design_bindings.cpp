// The adaptive test (analysis/design/adaptive_test.h) on the virtual rig: the same loop, decision
// log and report as `oscilab-cli adaptive-test`.
#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/design/adaptive_test.h"
#include "analysis/design/adaptive_test_report.h"
#include "analysis/identification/fit_setup.h"
#include "bindings.h"
#include "daq/rig/rig_level_runner.h"
#include "python_types.h"

namespace oscilab::python {
namespace {

// A (min, max) pair of forces, N.
std::pair<double, double> range_argument(const py::handle& object, const std::string& name) {
  const Eigen::VectorXd range = to_vector(object, name);
  if (range.size() != 2) throw InputError(name + ": expected (min, max) in N");
  return {range(0), range(1)};
}

// adaptive_test's docstring.
constexpr const char* kAdaptiveTestDoc =
    R"doc(The adaptive stepped-sine test on the virtual rig (`oscilab-cli adaptive-test`): a pilot
in each well, then after every level the baseline and each candidate effect refitted and weighed
(BIC weights), the next setting proposed where the plausible models differ most per second of
shaker time, run and analysed, until one model is clear at the noise, nothing is left to tell
apart or the budget is spent; then the diagnosis of every recording made.

rig_model: the rig's truth (a Model, 'paper' or a model JSON path); out: the folder the
recordings are written to (NN_pilot_positive.wav ...). model, stiffness, harmonics,
max_harmonics, model_error, seed, threads, max_seconds: as diagnose(). freq_hz, freq_span_hz,
freq_step_hz: the admissible frequencies [Hz]; f0_range_n (min, max) and f0_step_n: the forcing
grid [N]; wells: 'both', 'positive' or 'negative'; pilot_levels_n [N]; hold_s, ramp_s, lead_in_s:
each level's dwell and ramp and the rest before a run [s]; well_change_s: shaker time of a change
of well [s]; budget_s: shaker-time budget [s]; leader_weight, min_discrimination: the stop rule;
max_levels: adaptive levels at most; effects: the candidate effects weighed (empty: all);
global_evaluations, initial_evaluations, refit_evaluations: model evaluations of the fits.
progress: callable(info) with fraction and, from the first decision on, decision (the latest
line of the CLI's decisions.jsonl; its 'decision' counts them); return False to cancel (the
result then has status 'cancelled').
Returns the CLI's report.json as a dict (verdict, steps, shaker_time_s, adaptive_test {levels,
leader, stop_reason, weights, agrees_with_diagnosis ...}) with status, decisions (every line of
decisions.jsonl) and recordings (the paths written); and final_model_object when there is one.
Ctrl-C stops it (KeyboardInterrupt); the GIL is released.)doc";

// The core's option fields as adaptive_test's keywords, for its refusals.
const std::vector<std::pair<std::string, std::string>> kKeywordOfField = {
    {"settings.f0_range_n", "f0_range_n"},
    {"settings.f0_step_n", "f0_step_n"},
    {"settings.freq_hz", "freq_hz"},
    {"settings.freq_span_hz", "freq_span_hz"},
    {"settings.freq_step_hz", "freq_step_hz"},
    {"settings.wells", "wells"},
    {"settings.dwell_s", "hold_s"},
    {"settings.settling_s", "lead_in_s"},
    {"settings.well_change_s", "well_change_s"},
    {"stop.leader_weight", "leader_weight"},
    {"stop.min_discrimination", "min_discrimination"},
    {"stop.budget_s", "budget_s"},
    {"hypotheses.global_evaluations", "global_evaluations"},
    {"hypotheses.initial_evaluations", "initial_evaluations"},
    {"hypotheses.refit_evaluations", "refit_evaluations"},
    {"hypotheses.threads", "threads"},
    {"hypotheses.effects", "effects"}};

}  // namespace

void bind_design(py::module_& m) {
  m.def(
      "adaptive_test",
      [](const py::object& rig_model, const py::object& out, const py::object& model,
         const std::string& stiffness, double freq_hz, double freq_span_hz, double freq_step_hz,
         const py::object& f0_range_n, double f0_step_n, const std::string& wells,
         const py::object& pilot_levels_n, double hold_s, double ramp_s, double lead_in_s,
         double well_change_s, double budget_s, double leader_weight, double min_discrimination,
         int max_levels, const std::vector<std::string>& effects, long global_evaluations,
         int initial_evaluations, int refit_evaluations, std::uint64_t seed, int threads,
         int harmonics, int max_harmonics, double model_error, double max_seconds,
         const py::object& progress) {
        if (wells != "both" && wells != "positive" && wells != "negative") {
          throw InputError("wells: \"" + wells + "\" is not positive, negative or both");
        }
        if (!(hold_s > 0.0) || !(ramp_s >= 0.0) || !(ramp_s < hold_s) || !(lead_in_s >= 0.0)) {
          throw InputError("hold_s, ramp_s, lead_in_s: hold > ramp >= 0, lead-in >= 0");
        }
        if (!(max_seconds >= 0.0)) throw InputError("max_seconds: must be >= 0");
        analysis::AdaptiveTestOptions options;
        analysis::AdmissibleSettings& settings = options.settings;
        std::tie(settings.f0_min_n, settings.f0_max_n) = range_argument(f0_range_n, "f0_range_n");
        settings.f0_step_n = f0_step_n;
        settings.freq_hz = freq_hz;
        settings.freq_span_hz = freq_span_hz;
        settings.freq_step_hz = freq_step_hz;
        settings.positive_well = wells != "negative";
        settings.negative_well = wells != "positive";
        settings.dwell_s = hold_s;
        settings.settling_s = lead_in_s;
        settings.well_change_s = well_change_s;
        const Eigen::VectorXd pilot = to_vector(pilot_levels_n, "pilot_levels_n");
        options.pilot_levels_n.assign(pilot.data(), pilot.data() + pilot.size());
        options.stop = analysis::StopRule{leader_weight, min_discrimination, budget_s};
        options.max_levels = max_levels;
        options.setup.base_model = model_argument(model);
        options.setup.stiffness = analysis::parse_stiffness_source(stiffness, "stiffness");
        options.setup.cost = analysis::cost_settings(harmonics, max_harmonics, model_error,
                                                     "harmonics", "max_harmonics");
        options.hypotheses.effects = effects;
        options.hypotheses.global_evaluations = global_evaluations;
        options.hypotheses.initial_evaluations = initial_evaluations;
        options.hypotheses.refit_evaluations = refit_evaluations;
        options.hypotheses.seed = seed;
        options.hypotheses.threads = threads;
        options.next.threads = threads;
        options.diagnosis.max_seconds = max_seconds;
        options.diagnosis.seed = seed;
        options.diagnosis.threads = threads;
        analysis::validate_as_named(options, kKeywordOfField);
        const analysis::Model truth = model_argument(rig_model);
        const std::string folder = path_string(out);
        std::error_code error;
        std::filesystem::create_directories(folder, error);
        if (error) throw InputError(folder + ": cannot create: " + error.message());

        daq::RigLevelRunner rig(truth, folder, {hold_s, ramp_s, lead_in_s}, seed);
        std::mutex decisions_mutex;
        std::vector<nlohmann::json> decisions;
        analysis::AdaptiveTestResult result;
        run_job(
            [&](const ReportFn& report, const CancelToken& cancel) {
              // Every report carries the latest decision: the caller sees the last report
              // whenever it looks (reports coalesce), and a decision must not be lost behind the
              // fraction of the run that follows it.
              ProgressReport latest;
              const auto on_decision = [&](const analysis::AdaptiveDecision& d,
                                           const std::vector<analysis::ModelHypothesis>& h) {
                nlohmann::json line = analysis::adaptive_decision_json(d, h);
                latest.extra["decision"] = line;
                {
                  const std::lock_guard lock(decisions_mutex);
                  decisions.push_back(std::move(line));
                }
                report(latest);
              };
              result = analysis::run_adaptive_test(
                  rig, options, on_decision,
                  [&](double fraction) {
                    latest.fraction = fraction;
                    report(latest);
                  },
                  cancel);
            },
            progress);
        nlohmann::json report = analysis::adaptive_test_report_json(result, rig.paths());
        report["decisions"] = decisions;
        report["recordings"] = rig.paths();
        py::dict dict = to_python(report);
        if (result.diagnosis.final_form) {
          dict["final_model_object"] =
              py::cast(result.diagnosis.final_form->build(result.diagnosis.final_theta));
        }
        return dict;
      },
      py::arg("rig_model"), py::arg("out"), py::kw_only(), py::arg("model") = "paper",
      py::arg("stiffness") = "identified", py::arg("freq_hz") = 9.0, py::arg("freq_span_hz") = 0.0,
      py::arg("freq_step_hz") = 0.25, py::arg("f0_range_n") = std::vector<double>{0.2, 2.7},
      py::arg("f0_step_n") = 0.1, py::arg("wells") = "both",
      py::arg("pilot_levels_n") = std::vector<double>{0.2, 1.0, 1.8, 2.7}, py::arg("hold_s") = 10.0,
      py::arg("ramp_s") = 1.0, py::arg("lead_in_s") = 2.5, py::arg("well_change_s") = 10.0,
      py::arg("budget_s") = 520.0, py::arg("leader_weight") = 0.99,
      py::arg("min_discrimination") = 1.0, py::arg("max_levels") = 40,
      py::arg("effects") = std::vector<std::string>{}, py::arg("global_evaluations") = 400,
      py::arg("initial_evaluations") = 400, py::arg("refit_evaluations") = 300, py::arg("seed") = 1,
      py::arg("threads") = 0, py::arg("harmonics") = 7, py::arg("max_harmonics") = 63,
      py::arg("model_error") = -1.0, py::arg("max_seconds") = 120.0,
      py::arg("progress") = py::none(), kAdaptiveTestDoc);
}

}  // namespace oscilab::python
