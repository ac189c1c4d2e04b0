// Shared pieces of the Python module: conversions (JSON, arrays), the error rule, and the runner
// of long jobs (GIL released, progress, Ctrl-C). Each bind_* adds one concept's functions.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "analysis/common/job.h"
#include "analysis/edc/well.h"

namespace oscilab::python {

namespace py = pybind11;

void bind_recording(py::module_& m);
void bind_analysis(py::module_& m);
void bind_models(py::module_& m);
void bind_simulation(py::module_& m);
void bind_hbm(py::module_& m);
void bind_fit(py::module_& m);
void bind_design(py::module_& m);
void bind_live(py::module_& m);
void bind_bench(py::module_& m);

// --- Conversions (convert.cpp) ---------------------------------------------------------------

/// JSON → Python: null → None, numbers → int/float (exactly the stored double), arrays → list,
/// objects → dict (key order kept).
py::object to_python(const nlohmann::json& json);
/// Python → JSON: None, bool, int, float, str, lists/tuples, dicts with str keys, and NumPy
/// scalars and 1-D arrays (as lists). Throws InputError naming `where` for anything else.
nlohmann::json to_json(const py::handle& object, const std::string& where);
/// A dict or a JSON text → JSON.
nlohmann::json json_argument(const py::handle& object, const std::string& where);

py::array_t<double> to_array(const Eigen::VectorXd& v);
py::array_t<double> to_array(const std::vector<double>& v);
py::array_t<double> to_array(const Eigen::MatrixXd& m);  // 2-D, C order, copied
/// Integers as int64, the dtype of every integer column the module returns (docs/python.md).
py::array_t<std::int64_t> to_int_array(const std::vector<int>& v);
/// A 1-D float64 array (copied); throws InputError naming `where` otherwise.
Eigen::VectorXd to_vector(const py::handle& object, const std::string& where);

/// One path or a sequence of paths (str or os.PathLike) → strings.
std::vector<std::string> path_list(const py::handle& object, const std::string& where);
/// Whether `object` is a path: str, bytes or os.PathLike (as open() takes).
bool is_path(const py::handle& object);
/// A path (str, bytes decoded with the file-system encoding, os.PathLike) as a string.
std::string path_string(const py::handle& object);

/// A number given as a Python object (an optional argument): a float of it, or TypeError naming
/// the argument (`name: expected a number, not str`).
double number_argument(const py::handle& object, const std::string& name);
/// A str given as a Python object: the string, or TypeError naming the argument.
std::string text_argument(const py::handle& object, const std::string& name);

/// A `well` argument: "positive" or "negative"; throws InputError naming the value otherwise.
analysis::Well well_argument(const std::string& well);
/// A `well` argument that may also be "both": the wells it names, positive first.
std::vector<analysis::Well> wells_argument(const std::string& well);

// --- Long jobs (job_runner.cpp) --------------------------------------------------------------

/// What a job tells the caller's Python progress callback: the fraction done and, for fits,
/// more (stage, evaluations, best cost and θ), as a dict.
struct ProgressReport {
  double fraction = 0.0;
  nlohmann::json extra = nlohmann::json::object();
  /// Named values in their own order (a JSON object would sort them), handed on as the dict
  /// `named_key`: a fit's best θ by parameter name, in θ's order.
  std::string named_key;
  std::vector<std::pair<std::string, double>> named;
};
using ReportFn = std::function<void(const ProgressReport&)>;

/// Runs `work(report, cancel)` on a pooled worker thread with the GIL released, while the calling
/// thread waits: every 20 ms, or at once when the job reports progress, it re-acquires the GIL,
/// checks for signals (PyErr_CheckSignals: Ctrl-C raises KeyboardInterrupt there) and hands the
/// latest report to `progress` (None: no callback). On a signal, or when the callback raises, the
/// job's CancelToken is set, the job is waited for (it returns its best so far) and the Python
/// exception propagates: the job has stopped when KeyboardInterrupt arrives. A callback that
/// returns False cancels the job without an exception (its result says cancelled). C++
/// exceptions of the job are rethrown on the calling thread (InputError → ValueError/OSError).
void run_job(const std::function<void(const ReportFn&, const CancelToken&)>& work,
             const py::object& progress);

/// A ProgressFn (fraction only) that forwards to `report`.
ProgressFn fraction_reporter(const ReportFn& report);

}  // namespace oscilab::python

// --- Tables shared by the offline and the live analysis (analysis_bindings.cpp) ----------------

namespace oscilab::analysis {
struct LevelResult;
struct CycleFit;
struct EdcTableRow;
struct CycleTableRow;
}  // namespace oscilab::analysis

namespace oscilab::python {

/// The EDC table (analysis::edc_table_columns, docs/contracts.md §3) as a dict of NumPy arrays
/// keyed and ordered like the CSV of `analyze --edc`: float64 for reals, int64 for counts, bool
/// for `usable`, unicode (<U…) for text.
py::dict level_table(const std::vector<analysis::EdcTableRow>& rows);
/// Levels without a record (the live analysis's): the same columns but `record`, and each
/// level's own flags.
py::dict level_table(const std::vector<analysis::LevelResult>& levels);
/// The fitted cycles (analysis::cycle_table_columns) as columns named like the CSV of
/// `analyze --cycles`, with the same dtypes.
py::dict cycle_table(const std::vector<analysis::CycleTableRow>& rows);
/// Cycles without a record (the live analysis's): the same columns but `record`.
py::dict cycle_table(const std::vector<analysis::CycleFit>& cycles);

}  // namespace oscilab::python
