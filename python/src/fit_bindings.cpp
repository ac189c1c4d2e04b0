// Identification (§4, §5) and model-gap diagnosis: the fit sequence both front-ends use
// (analysis/identification/fit_setup.h: prepare_fit, fit_edc) and diagnose(), results as the
// CLI's FIT JSON and report.json.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "analysis/common/input_error.h"
#include "analysis/common/json_limits.h"
#include "analysis/diagnosis/campaign_fit.h"
#include "analysis/diagnosis/diagnosis.h"
#include "analysis/identification/edc_fit.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/identification/fit_table.h"
#include "analysis/model/model.h"
#include "analysis/model/model_json.h"
#include "bindings.h"
#include "daq/recording/fit_json.h"
#include "daq/recording/json_file.h"
#include "daq/recording/recording.h"
#include "python_types.h"

namespace oscilab::python {
namespace {

// Recordings (paths, Recording objects) or an Analysis → the analysis, and the names the JSON
// lists as records (the paths as given, else the records' names).
std::shared_ptr<const analysis::CampaignAnalysis> campaign_of(const py::object& recordings,
                                                              const py::object& freq_hz,
                                                              const py::object& progress,
                                                              std::vector<std::string>& records) {
  if (py::isinstance<AnalysisHandle>(recordings)) {
    auto campaign = recordings.cast<const AnalysisHandle&>().campaign;
    for (const auto& r : campaign->records) records.push_back(r.name);
    return campaign;
  }
  AnalysisArguments arguments;
  arguments.freq_hz = freq_hz;
  const bool single = is_path(recordings);
  if (!single && !py::isinstance<daq::Recording>(recordings) &&
      !py::isinstance<py::iterable>(recordings)) {
    throw py::type_error(
        "recordings: expected a path, a Recording, an Analysis or a sequence of them, not " +
        py::str(py::type::of(recordings).attr("__name__")).cast<std::string>());
  }
  // A sequence is read once (it may be a generator).
  const py::object items = single || py::isinstance<daq::Recording>(recordings)
                               ? recordings
                               : py::object(py::list(py::iterable(recordings)));
  auto campaign = run_analysis(items, arguments, progress);
  bool all_paths = !py::isinstance<daq::Recording>(items);
  if (!single && all_paths) {
    for (const auto& item : items) {
      all_paths &= is_path(item);
    }
  }
  if (all_paths) {
    records = path_list(items, "recordings");
  } else {
    for (const auto& r : campaign->records) records.push_back(r.name);
  }
  return campaign;
}

FitProblem make_problem(const py::object& recordings, const py::object& model,
                        const std::string& stiffness, int harmonics, int max_harmonics,
                        double model_error, const py::object& freq_hz, const py::object& progress) {
  const analysis::StiffnessSource source = analysis::parse_stiffness_source(stiffness, "stiffness");
  FitProblem problem;
  problem.campaign = campaign_of(recordings, freq_hz, progress, problem.records);
  analysis::FitSetup setup;
  setup.base_model = model_argument(model);
  setup.stiffness = source;
  setup.cost =
      analysis::cost_settings(harmonics, max_harmonics, model_error, "harmonics", "max_harmonics");
  // The σ budget's calibration (harmonic balance sweeps) polls the cost's token: Ctrl-C stops it.
  run_job(
      [&](const ReportFn&, const CancelToken& cancel) {
        analysis::FitSetup cancellable = setup;
        cancellable.cost.cancel = cancel;
        problem.prepared = analysis::prepare_fit(*problem.campaign, cancellable);
      },
      py::none());
  return problem;
}

// The FIT JSON's dicts keyed by parameter (parameters, standard_errors, intervals_95) in θ's
// order, FitProblem.names, as the progress's best_parameters: a JSON object would sort them.
py::dict in_theta_order(py::dict result, const std::vector<std::string>& names) {
  for (const char* key : {"parameters", "standard_errors", "intervals_95"}) {
    if (!result.contains(key) || !py::isinstance<py::dict>(result[key])) continue;
    const py::dict given = result[key];
    py::dict ordered;
    for (const std::string& name : names) {
      if (given.contains(name)) ordered[py::str(name)] = given[py::str(name)];
    }
    for (const auto& [name, value] : given) {
      if (!ordered.contains(name)) ordered[name] = value;
    }
    result[key] = ordered;
  }
  return result;
}

py::dict run_fit(const FitProblem& problem, const std::string& method, int population,
                 int generations, double mutation, long evaluations, bool polish,
                 std::uint64_t seed, int threads, int bootstrap, const py::object& progress) {
  analysis::FitOptions options;
  options.seed = seed;
  options.threads = threads;
  options.max_evaluations = evaluations;
  options.genetic.population = population;
  options.genetic.generations = generations;
  options.genetic.mutation_rate = mutation;
  options.polish_after_genetic = polish;
  options.uncertainty.bootstrap_replicates = bootstrap;
  analysis::validate(options, "");
  options.method = analysis::parse_fit_method(method);
  options.genetic.elite = analysis::default_elite(population);
  std::shared_ptr<const analysis::EdcObjective> objective = problem.prepared.objective;
  const long budget = analysis::evaluation_budget(options);
  const std::vector<std::string> names = objective->form().names();
  analysis::FitResult fit;
  run_job(
      [&](const ReportFn& report, const CancelToken& cancel) {
        analysis::CampaignFit result = analysis::fit_campaign(
            problem.prepared, *problem.campaign, options,
            [&](const analysis::FitProgress& p) {
              ProgressReport r;
              r.fraction = p.stage == analysis::FitStage::Uncertainty
                               ? 1.0
                               : std::min(1.0, static_cast<double>(p.evaluations) /
                                                   static_cast<double>(budget));
              r.extra["stage"] = analysis::to_string(p.stage);
              r.extra["evaluations"] = p.evaluations;
              r.extra["best_weighted_cost"] = p.best_weighted_cost;
              r.extra["best_theta"] = std::vector<double>(
                  p.best_theta.data(), p.best_theta.data() + p.best_theta.size());
              r.named_key = "best_parameters";
              for (std::size_t i = 0; i < names.size() && i < std::size_t(p.best_theta.size());
                   ++i) {
                r.named.emplace_back(names[i], p.best_theta[static_cast<Eigen::Index>(i)]);
              }
              report(r);
            },
            cancel);
        fit = std::move(result.fit);
        objective = std::move(result.objective);
      },
      progress);
  return in_theta_order(
      to_python(daq::fit_json(fit, *objective, problem.records, problem.prepared.notes)),
      objective->form().names());
}

// The FitProblem class: a fit's problem made once, θ evaluated and fitted.
void bind_fit_problem(py::module_& m) {
  // The search's defaults are analysis::FitOptions' (as `oscilab-cli fit` and the app's form).
  const analysis::FitOptions kSearch;
  py::class_<FitProblem>(m, "FitProblem", R"doc(
A friction fit's problem (fit_setup.h's prepare_fit): the paper's model form (eq. (7), θ of
eq. (9)) of the base model with the recordings' mass and the chosen stiffness, the usable EDC
levels of both wells, and the objective: eq. (8) and the σ-weighted cost. Made by prepare_fit().
)doc")
      .def_property_readonly(
          "names", [](const FitProblem& p) { return p.prepared.objective->form().names(); },
          "Parameter names of θ in its order, the order of every dict keyed by parameter (the "
          "result's parameters, standard_errors, intervals_95, the progress's best_parameters).")
      .def_property_readonly(
          "initial_theta",
          [](const FitProblem& p) { return to_array(p.prepared.objective->form().initial()); },
          "The form's starting θ (the base model's values), SI units.")
      .def_property_readonly(
          "level_count", [](const FitProblem& p) { return p.prepared.objective->level_count(); },
          "Number of measured levels in the cost.")
      .def_property_readonly(
          "sigma_j", [](const FitProblem& p) { return to_array(p.prepared.objective->sigma_j()); },
          "σ_k of each level [J] (the σ budget, or the fixed floor), groups in order.")
      .def_property_readonly(
          "notes", [](const FitProblem& p) { return py::cast(p.prepared.notes); },
          "What the set-up changed (the recordings' mass, the RFS stiffness).")
      .def_property_readonly(
          "records", [](const FitProblem& p) { return py::cast(p.records); },
          "The records the FIT JSON lists.")
      .def(
          "evaluate",
          [](const FitProblem& p, const py::object& theta_arg) {
            const Eigen::VectorXd theta = to_vector(theta_arg, "theta");
            const auto& objective = *p.prepared.objective;
            if (theta.size() != objective.form().size()) {
              throw InputError("theta: " + std::to_string(theta.size()) + " values for " +
                               std::to_string(objective.form().size()) + " parameters");
            }
            analysis::EdcEvaluation e;
            {
              py::gil_scoped_release release;
              e = objective.evaluate(theta);
            }
            py::dict d;
            d["ok"] = e.ok;
            d["message"] = e.message;
            d["cost_j"] = e.cost_j;
            d["weighted_cost"] = e.weighted_cost;
            d["residuals"] = to_array(e.residuals);
            py::list edc;
            for (const auto& group : e.edc_mod_j) edc.append(to_array(group));
            d["edc_mod_j"] = edc;
            py::dict deviation;
            deviation["positive"] = e.mean_deviation_pct_positive;
            deviation["negative"] = e.mean_deviation_pct_negative;
            d["mean_deviation_pct"] = deviation;
            return d;
          },
          py::arg("theta"),
          "One evaluation of the cost at θ (SI, in `names` order): cost_j [J] of eq. (8), "
          "weighted_cost (χ² the fit minimises), residuals (r_k in σ), edc_mod_j (the model's "
          "EDC per group and level [J]), mean_deviation_pct {positive, negative} [%], ok, "
          "message. The GIL is released while it runs.")
      .def(
          "fit",
          [](const FitProblem& p, const std::string& method, int population, int generations,
             double mutation, long evaluations, bool polish, std::uint64_t seed, int threads,
             int bootstrap, const py::object& progress) {
            return run_fit(p, method, population, generations, mutation, evaluations, polish, seed,
                           threads, bootstrap, progress);
          },
          py::kw_only(), py::arg("method") = analysis::fit_method_name(kSearch.method),
          py::arg("population") = kSearch.genetic.population,
          py::arg("generations") = kSearch.genetic.generations,
          py::arg("mutation") = kSearch.genetic.mutation_rate,
          py::arg("evaluations") = kSearch.max_evaluations,
          py::arg("polish") = kSearch.polish_after_genetic, py::arg("seed") = kSearch.seed,
          py::arg("threads") = kSearch.threads,
          py::arg("bootstrap") = kSearch.uncertainty.bootstrap_replicates,
          py::arg("progress") = py::none(),
          "Runs the fit on this problem; arguments and result as oscilab.fit().");
}

// merge(): FIT JSONs to one table.
void bind_merge(py::module_& m) {
  m.def(
      "merge",
      [](const py::object& fits) {
        if (!is_path(fits) && py::len(fits) == 0) throw InputError("fits: no FIT JSON given");
        std::vector<analysis::FitSummary> rows;
        for (const std::string& path : path_list(fits, "fits")) {
          rows.push_back(
              analysis::read_fit_summary(daq::read_json_file(path, kMaxJsonTextBytes), path));
        }
        const analysis::FitTable table = analysis::fit_table(std::move(rows));
        const auto numpy = py::module_::import("numpy");
        const auto texts = [&](auto field) {
          py::list out;
          for (const analysis::FitSummary& r : table.rows) out.append(py::str(field(r)));
          return numpy.attr("array")(out, py::arg("dtype") = "U");
        };
        const auto reals = [&](auto field) {
          std::vector<double> out;
          for (std::size_t k = 0; k < table.rows.size(); ++k) out.push_back(field(k));
          return to_array(out);
        };
        py::dict out;
        out["fit"] = texts([](const analysis::FitSummary& r) { return r.source; });
        out["records"] = texts([](const analysis::FitSummary& r) { return r.records; });
        out["method"] = texts([](const analysis::FitSummary& r) { return r.method; });
        out["cost_j"] = reals([&](std::size_t k) { return table.rows[k].cost_j; });
        out["mean_deviation_pct_positive"] =
            reals([&](std::size_t k) { return table.rows[k].mean_deviation_pct_positive; });
        out["mean_deviation_pct_negative"] =
            reals([&](std::size_t k) { return table.rows[k].mean_deviation_pct_negative; });
        std::vector<int> evaluations;
        for (const analysis::FitSummary& r : table.rows) {
          evaluations.push_back(static_cast<int>(r.evaluations));
        }
        out["evaluations"] = to_int_array(evaluations);
        out["seconds"] = reals([&](std::size_t k) { return table.rows[k].seconds; });
        for (const std::string& p : table.parameters) {
          out[py::str(p)] = reals([&](std::size_t k) { return table.parameter(k, p); });
          out[py::str(p + "_std")] =
              reals([&](std::size_t k) { return table.standard_error(k, p); });
        }
        return out;
      },
      py::arg("fits"),
      R"doc(Many fits joined into one table (`oscilab-cli merge`): one row per FIT JSON, the columns
of the CLI's CSV in its order (fit, records, method, cost_j [J], mean_deviation_pct_positive,
mean_deviation_pct_negative, evaluations, seconds [s], then each parameter p and p_std, the union
of the fits' parameters in first-seen order) as a dict of NumPy arrays: unicode (<U...) for the
text, int64 for evaluations, float64 otherwise (NaN where a fit has no such parameter or error).
fits: a path or a sequence of paths (str, bytes or os.PathLike) of FIT JSONs written by fit().
pandas.DataFrame(oscilab.merge(paths)) takes it as it is.)doc");
}

// prepare_fit() and fit().
void bind_fit_functions(py::module_& m) {
  // The search's defaults are analysis::FitOptions' (as `oscilab-cli fit` and the app's form).
  const analysis::FitOptions kSearch;
  m.def(
      "prepare_fit",
      [](const py::object& recordings, const py::object& model, const std::string& stiffness,
         int harmonics, int max_harmonics, double model_error, const py::object& freq_hz,
         const py::object& progress) {
        return make_problem(recordings, model, stiffness, harmonics, max_harmonics, model_error,
                            freq_hz, progress);
      },
      py::arg("recordings"), py::kw_only(), py::arg("model") = "paper",
      py::arg("stiffness") = "model", py::arg("harmonics") = 7, py::arg("max_harmonics") = 63,
      py::arg("model_error") = -1.0, py::arg("freq_hz") = py::none(),
      py::arg("progress") = py::none(),
      R"doc(The fit's problem without running it (a FitProblem: evaluate θ, then fit). Arguments as
oscilab.fit(); `progress` reports the analysis of paths.)doc");

  m.def(
      "fit",
      [](const py::object& recordings, const py::object& model, const std::string& method,
         int population, int generations, double mutation, long evaluations, bool polish,
         std::uint64_t seed, int threads, int harmonics, int max_harmonics, double model_error,
         int bootstrap, const std::string& stiffness, const py::object& freq_hz,
         const std::string& model_form, const py::object& progress) {
        if (model_form != "paper") {
          throw InputError("model_form: unknown form \"" + model_form + "\" (paper)");
        }
        const FitProblem problem = make_problem(recordings, model, stiffness, harmonics,
                                                max_harmonics, model_error, freq_hz, py::none());
        return run_fit(problem, method, population, generations, mutation, evaluations, polish,
                       seed, threads, bootstrap, progress);
      },
      py::arg("recordings"), py::kw_only(), py::arg("model") = "paper",
      py::arg("method") = analysis::fit_method_name(kSearch.method),
      py::arg("population") = kSearch.genetic.population,
      py::arg("generations") = kSearch.genetic.generations,
      py::arg("mutation") = kSearch.genetic.mutation_rate,
      py::arg("evaluations") = kSearch.max_evaluations,
      py::arg("polish") = kSearch.polish_after_genetic, py::arg("seed") = kSearch.seed,
      py::arg("threads") = kSearch.threads, py::arg("harmonics") = 7, py::arg("max_harmonics") = 63,
      py::arg("model_error") = -1.0,
      py::arg("bootstrap") = kSearch.uncertainty.bootstrap_replicates,
      py::arg("stiffness") = "model", py::arg("freq_hz") = py::none(),
      py::arg("model_form") = "paper", py::arg("progress") = py::none(),
      R"doc(Identifies the friction model from the EDCs of stepped-sine records (`oscilab-cli fit`):
θ of eq. (9) by the paper's genetic algorithm ('ga'), CMA-ES with a BOBYQA polish ('cmaes') or
BOBYQA alone ('local').

recordings: paths, Recording objects, or an Analysis. model: the base model (mass, stiffness,
starting friction): a Model, 'paper' or a model JSON path. population, generations, mutation: the
GA's; polish: BOBYQA after the GA; evaluations: model evaluations of cmaes or local; seed (same
seed, same result); threads (0: all cores); harmonics: H of the model's harmonic balance;
max_harmonics: largest reference H of the σ budget; model_error: fixed relative error floor
(negative: the σ budget); bootstrap: replicates over levels; stiffness: 'model' or 'rfs';
freq_hz: excitation frequency [Hz] (default: sidecar, else detected).
progress: callable(info) with fraction, stage, evaluations, best_weighted_cost, best_theta;
return False to cancel (the result then has status 'cancelled' and the best θ so far).
Ctrl-C cancels the fit and raises KeyboardInterrupt once it has stopped; the GIL is released.

Returns the FIT JSON of the CLI as a dict: parameters {fd_zminus_n, fd_zero_n, fd_zplus_n, ks,
c_ns_m, vt_m_s}, cost_j [J], mean_deviation_pct {positive, negative} [%], evaluations, seconds,
status, message, standard_errors, intervals_95, levels, model, notes ...)doc");
}

// diagnose().
void bind_diagnose(py::module_& m) {
  m.def(
      "diagnose",
      [](const py::object& recordings, const py::object& model, std::uint64_t seed, int threads,
         int harmonics, int max_harmonics, double model_error, double max_seconds, bool edc_only,
         double bic_threshold, int max_steps, long baseline_evaluations, long candidate_evaluations,
         const std::string& model_form, const std::string& stiffness, const py::object& progress) {
        if (model_form != "paper") {
          throw InputError("model_form: unknown form \"" + model_form + "\" (paper)");
        }
        if (!(max_seconds >= 0.0)) throw InputError("max_seconds: must be ≥ 0");
        if (max_steps < 1) throw InputError("max_steps: must be at least 1");
        if (baseline_evaluations < 10 || candidate_evaluations < 10) {
          throw InputError("baseline_evaluations, candidate_evaluations: must be at least 10");
        }
        std::vector<std::string> records;
        const auto campaign = campaign_of(recordings, py::none(), py::none(), records);
        analysis::FitSetup setup;
        setup.base_model = model_argument(model);
        setup.stiffness = analysis::parse_stiffness_source(stiffness, "stiffness");
        setup.cost = analysis::cost_settings(harmonics, max_harmonics, model_error, "harmonics",
                                             "max_harmonics");
        std::vector<std::string> notes;
        std::optional<analysis::ModelForm> form;
        {
          py::gil_scoped_release release;
          form = analysis::fit_form(*campaign, setup, notes);
        }
        analysis::DiagnosisOptions options;
        options.cost = setup.cost;
        options.max_seconds = max_seconds;
        options.use_fingerprints = !edc_only;
        options.bic_threshold = bic_threshold;
        options.max_steps = max_steps;
        options.baseline_evaluations = baseline_evaluations;
        options.candidate_evaluations = candidate_evaluations;
        options.seed = seed;
        options.threads = threads;
        analysis::DiagnosisResult result;
        run_job(
            [&](const ReportFn& report, const CancelToken& cancel) {
              result = analysis::diagnose(
                  *campaign, *form, options,
                  [&report](const analysis::DiagnosisProgress& p) {
                    ProgressReport r;
                    r.fraction = p.fraction;
                    r.extra = {{"phase", analysis::to_string(p.phase)},
                               {"step", p.step},
                               {"max_steps", p.max_steps},
                               {"candidates_done", p.candidates_done},
                               {"candidates", p.candidates},
                               {"candidate", p.candidate},
                               {"evaluations", p.evaluations},
                               {"message", p.describe()}};
                    report(r);
                  },
                  cancel);
            },
            progress);
        nlohmann::json report = analysis::diagnosis_report_json(result, records, bic_threshold);
        report["notes"] = notes;
        py::dict out = to_python(report);
        if (result.final_form) {
          out["final_model_object"] = py::cast(result.final_form->build(result.final_theta));
        }
        return out;
      },
      py::arg("recordings"), py::kw_only(), py::arg("model") = "paper", py::arg("seed") = 1,
      py::arg("threads") = 0, py::arg("harmonics") = 7, py::arg("max_harmonics") = 63,
      py::arg("model_error") = -1.0, py::arg("max_seconds") = 120.0, py::arg("edc_only") = false,
      py::arg("bic_threshold") = 10.0, py::arg("max_steps") = 3,
      py::arg("baseline_evaluations") = 1500, py::arg("candidate_evaluations") = 600,
      py::arg("model_form") = "paper", py::arg("stiffness") = "identified",
      py::arg("progress") = py::none(),
      R"doc(The model-gap diagnosis (`oscilab-cli diagnose`): fit the paper's form, map where model
and measurement disagree, refit every candidate effect, accept the best by joint ΔBIC, repeat.

recordings: paths, Recording objects or an Analysis (stepped-sine records of both wells).
max_seconds: wall-clock bound [s] (0: none); edc_only: compare on the EDC alone; bic_threshold:
accept when ΔBIC < −this; max_steps: effects added at most; baseline_evaluations,
candidate_evaluations: model evaluations of those fits; stiffness: 'identified' (K(z)'s
coefficients identified with the friction, starting from the records' stiffness slice or the
model's), 'rfs' or 'model' (held); progress: callable(info) with fraction (never decreasing),
phase ('baseline', 'settling', 'candidates', 'finalists', 'accepting', 'done'), step, max_steps,
candidates_done, candidates, candidate (the last refitted), evaluations and message (in words);
return False to cancel; other arguments as fit().
Returns report.json as a dict: baseline {cost_j ...}, steps [{effect, evidence, cost_before_j,
cost_after_j}], verdict (an effect name of contract §3, or 'none'), final_model, notes; and
final_model_object (a Model) when there is one. Ctrl-C stops it (KeyboardInterrupt).)doc");
}

}  // namespace

void bind_fit(py::module_& m) {
  bind_fit_problem(m);
  bind_merge(m);
  bind_fit_functions(m);
  bind_diagnose(m);
}

}  // namespace oscilab::python
