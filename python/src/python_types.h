// Handles the Python module passes between its functions (an analysis reused by fit and
// diagnose), and helpers shared by several binding files.
#pragma once

#include <memory>
#include <string>

#include "analysis/identification/fit_setup.h"
#include "analysis/pipeline/offline_analysis.h"
#include "bindings.h"

namespace oscilab::python {

/// An offline analysis held by Python; shared so a fit can keep it alive.
struct AnalysisHandle {
  std::shared_ptr<const analysis::CampaignAnalysis> campaign;
};

/// The keyword arguments of analyze(), also taken by fit() and diagnose() when they are given
/// paths.
struct AnalysisArguments {
  py::object freq_hz = py::none();
  py::object well = py::none();
  bool detect_levels = false;
  int harmonics = 8;
  double highpass_hz = 1.0;
  double lowpass_hz = 60.0;
  double well_boundary_m = 0.0;
};

/// The analysis of `recordings` (paths, Recording objects, or an Analysis returned as it is).
std::shared_ptr<const analysis::CampaignAnalysis> run_analysis(const py::object& recordings,
                                                               const AnalysisArguments& arguments,
                                                               const py::object& progress);

/// "ok", "cancelled", "no-convergence", "numerical-issue", "invalid-input".
std::string job_status_name(JobStatus status);

}  // namespace oscilab::python

namespace oscilab::analysis {
class Model;
}

namespace oscilab::python {
/// A Model, a model dict, or a spec ('paper', 'illustrative', a path) → the model.
analysis::Model model_argument(const py::handle& object);
}  // namespace oscilab::python

namespace oscilab::python {
/// Amplitudes [N]: a sequence, or "A:STEP:B" (analysis::stepped_levels, the CLI's --levels rule)
/// or "A,B,...". Throws InputError naming levels_n.
std::vector<double> levels_argument(const py::object& levels);
}  // namespace oscilab::python

namespace oscilab::python {
/// A fit's problem held by Python: the objective over the campaign's levels (eq. (8) and the σ
/// budget), the notes of its set-up, and the record names the FIT JSON lists.
struct FitProblem {
  std::shared_ptr<const analysis::CampaignAnalysis> campaign;
  analysis::PreparedFit prepared;
  std::vector<std::string> records;
};
}  // namespace oscilab::python
