// The C++ side of the overhead benchmark (python/benchmarks/overhead.py): the same library calls
// as the bindings, timed inside C++ (steady clock, GIL released), so that the Python call's
// overhead is the difference. Not part of the public API.
#include <chrono>
#include <vector>

#include "analysis/common/input_error.h"
#include "bindings.h"
#include "daq/recording/campaign_reader.h"
#include "python_types.h"

namespace oscilab::python {

void bind_bench(py::module_& m) {
  m.def(
      "_bench_analyze",
      [](const py::object& recordings, int repeats) {
        const std::vector<std::string> paths = path_list(recordings, "recordings");
        std::vector<double> seconds;
        py::gil_scoped_release release;
        for (int i = 0; i < repeats; ++i) {
          const auto start = std::chrono::steady_clock::now();
          {
            // Made and freed inside the timing, as the Python call's result is (its refcount
            // drops to zero before the script reads the clock).
            const analysis::CampaignAnalysis campaign =
                daq::analyze_recordings(paths, {}, analysis::PipelineSettings{});
          }
          seconds.push_back(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
        return seconds;
      },
      py::arg("recordings"), py::arg("repeats") = 5,
      "Seconds of each of `repeats` C++ calls of daq::analyze_recordings (what analyze() runs).");
  m.def(
      "_bench_evaluate",
      [](const FitProblem& problem, const py::object& theta_arg, int repeats) {
        const Eigen::VectorXd theta = to_vector(theta_arg, "theta");
        if (theta.size() != problem.prepared.objective->form().size()) {
          throw InputError("theta: wrong number of parameters");
        }
        std::vector<double> seconds;
        py::gil_scoped_release release;
        for (int i = 0; i < repeats; ++i) {
          const auto start = std::chrono::steady_clock::now();
          bool ok = false;
          {
            const analysis::EdcEvaluation e = problem.prepared.objective->evaluate(theta);
            ok = e.ok;
          }
          seconds.push_back(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
          if (!ok && i == 0) break;  // not a θ worth timing
        }
        return seconds;
      },
      py::arg("problem"), py::arg("theta"), py::arg("repeats") = 20,
      "Seconds of each of `repeats` C++ calls of EdcObjective::evaluate (FitProblem.evaluate).");
}

}  // namespace oscilab::python
